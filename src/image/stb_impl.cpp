// stb_image_write's implementation, for our PNGs, compiled here from the header of Debian's
// libstb-dev (or the tarball's third_party/stb/, make dist) instead of linking libstb (the
// reader, stb_image, is stb_image_impl.cpp's): this way the PNG writer's zlib stream can
// come from libdeflate through stb's STBIW_ZLIB_COMPRESS hook (stb_image_write.h,
// "BUILDING"). Without libdeflate (RT_NO_LIBDEFLATE, mk/png.mk) stb's own compressor is
// used. Either way the pixels are the same, PNG being lossless.
#include <cstdlib>

#include "rt/io/memory.h"

// stb's image buffers (the filtered rows: as large as the image) from allocate_bytes,
// for its huge pages.
#define STBIW_MALLOC(sz) rt::allocate_bytes(sz)
#define STBIW_REALLOC(p, newsz) std::realloc(p, newsz)
#define STBIW_FREE(p) std::free(p)

#ifndef RT_NO_LIBDEFLATE
#include <libdeflate.h>

namespace {
// libdeflate's compressor of the level asked last on this thread, kept for the next
// image: allocating one (its hash tables) per image cost about a tenth of the write.
class CachedCompressor {
public:
    CachedCompressor() = default;
    CachedCompressor(const CachedCompressor&) = delete;
    CachedCompressor& operator=(const CachedCompressor&) = delete;
    ~CachedCompressor() { libdeflate_free_compressor(c_); }
    libdeflate_compressor* get(int level) {
        if (!c_ || level != level_) {
            libdeflate_free_compressor(c_);
            c_ = libdeflate_alloc_compressor(level);
            level_ = level;
        }
        return c_;
    }

private:
    libdeflate_compressor* c_ = nullptr;
    int level_ = 0;
};

// The hook's contract (stb_image_write.h, "BUILDING"): a zlib stream of
// data[0..data_len) in memory from malloc (stb frees it), its length in *out_len;
// nullptr on failure. `quality` is stbi_write_png_compression_level, read as
// libdeflate's level (0..12).
unsigned char* rt_zlib_compress(unsigned char* data, int data_len, int* out_len, int quality) {
    thread_local CachedCompressor cache;
    libdeflate_compressor* c = cache.get(quality);
    if (!c) return nullptr;
    const size_t bound = libdeflate_zlib_compress_bound(c, static_cast<size_t>(data_len));
    auto* out = static_cast<unsigned char*>(rt::allocate_bytes(bound));
    const size_t n = out ? libdeflate_zlib_compress(c, data, static_cast<size_t>(data_len), out, bound) : 0;
    if (n == 0) {  // no memory, or the bound was too small (never, by libdeflate's contract)
        std::free(out);
        return nullptr;
    }
    *out_len = static_cast<int>(n);
    return out;
}
}  // namespace

#define STBIW_ZLIB_COMPRESS rt_zlib_compress
#endif

#include "stb_warnings_off.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "stb_warnings_on.h"
