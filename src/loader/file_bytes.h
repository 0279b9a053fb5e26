// The whole of a file in memory, for the PLY reader (ply.cpp): a read-only mapping
// for regular files of some size (no copy; MAP_POPULATE maps the cached pages up
// front), else one heap buffer filled by read(). Caveat of the mapping: if another
// process truncates the file while we parse it, the access past the new end raises
// SIGBUS; scene inputs are not rewritten while being rendered, and mapping saves
// copying every byte.
#pragma once
#include <cstddef>
#include <memory>
#include <string>

namespace rt::ply_reader {

class FileBytes {
public:
    FileBytes() = default;
    FileBytes(const FileBytes&) = delete;
    FileBytes& operator=(const FileBytes&) = delete;
    ~FileBytes();
    const unsigned char* data() const { return map_ ? static_cast<const unsigned char*>(map_) : heap_.get(); }
    size_t size() const { return size_; }

    static constexpr size_t kMapThreshold = size_t(1) << 20;
    // 4 GiB; 2 GiB where size_t is 32 bits (WebAssembly), so that doubling never wraps.
    static constexpr size_t kMaxStreamBytes =
        static_cast<size_t>(sizeof(size_t) > 4 ? uint64_t(1) << 32 : uint64_t(1) << 31);

    // Reads (or maps) the file at `path`. Throws rt::InputError "<path>: cannot open: ..."
    // or "<path>: cannot read: ..."; devices are refused, pipes read up to kMaxStreamBytes.
    void load(const std::string& path);

private:
    void* map_ = nullptr;
    std::unique_ptr<unsigned char[]> heap_;
    size_t size_ = 0;
};

}  // namespace rt::ply_reader
