// PNG output through stb_image_write (Debian libstb-dev; compiled in src/image/stb_impl.cpp,
// its zlib stream from libdeflate where available) and binary PPM, written atomically.
#include <stb/stb_image_write.h>

#include <cmath>
#include <exception>
#include <string>
#include <string_view>

#include "rt/core/error.h"
#include "rt/image/image.h"
#include "rt/io/atomic_file.h"
#include "rt/io/files.h"

namespace rt {

namespace {
// stb's output callback: the whole PNG at once, written to the file straight from stb's
// buffer (a copy first cost a page fault per 4 KiB of PNG). Exceptions are kept for
// write_png to rethrow, so that stb frees its buffer.
struct PngSink {
    const std::string& path;
    std::exception_ptr error;
};
void write_bytes(void* context, void* data, int size) {
    auto* sink = static_cast<PngSink*>(context);
    try {
        write_file_atomic(sink->path, std::string_view(static_cast<const char*>(data), static_cast<size_t>(size)));
    } catch (...) {
        sink->error = std::current_exception();
    }
}

// The deflate level, 4 on either scale: libdeflate's where stb_impl.cpp hands stb's zlib
// stream to libdeflate (its levels 2 to 4 take about the same time, 5 and up markedly
// more; 4 makes the smallest files of the three), stb's own otherwise (as before).
// docs/performance.md has the measurements.
constexpr int kPngLevel = 4;
}  // namespace

void write_png(const Image& image, const std::string& path) {
    // One row filter, "up" (stb's 2; PNG spec 9.2), instead of stb's per-row trial of
    // all five, which encodes slower for files hardly smaller. Set here, on the one
    // thread that writes images.
    stbi_write_force_png_filter = 2;
    stbi_write_png_compression_level = kPngLevel;
    PngSink sink{path, nullptr};
    if (!stbi_write_png_to_func(write_bytes, &sink, image.width, image.height, 3, image.rgb.data(), image.width * 3))
        throw InputError(path + ": cannot encode PNG");
    if (sink.error) std::rethrow_exception(sink.error);
}

void write_ppm(const Image& image, const std::string& path) {
    const size_t n = size_t(image.width) * size_t(image.height) * 3;
    if (image.width <= 0 || image.height <= 0 || image.rgb.size() != n)
        throw InputError(path + ": cannot encode PPM: bad image size");
    std::string bytes = "P6\n" + std::to_string(image.width) + " " + std::to_string(image.height) + "\n255\n";
    bytes.append(reinterpret_cast<const char*>(image.rgb.data()), n);
    write_file_atomic(path, bytes);
}

ImageFormat image_format_of(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".png") return ImageFormat::Png;
    if (ext == ".ppm") return ImageFormat::Ppm;
    return ImageFormat::Unknown;
}

void write_image(const Image& image, const std::string& path) {
    switch (image_format_of(path)) {
        case ImageFormat::Png:
            return write_png(image, path);
        case ImageFormat::Ppm:
            return write_ppm(image, path);
        case ImageFormat::Unknown:
            break;
    }
    throw InputError(path + ": unknown image format (the name must end in .png or .ppm)");
}

}  // namespace rt
