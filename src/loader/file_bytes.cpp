// FileBytes (file_bytes.h): the file mapped or read into one buffer.
#include "file_bytes.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>

#include "rt/core/error.h"

namespace rt::ply_reader {
namespace {

std::string errno_text(int e) {
#if defined(__GLIBC__) && defined(_GNU_SOURCE)
    char buf[256];
    return strerror_r(e, buf, sizeof buf);  // GNU variant: returns the message
#else
    return std::strerror(e);
#endif
}

}  // namespace

FileBytes::~FileBytes() {
    if (map_) ::munmap(map_, size_);
}

void FileBytes::load(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) throw InputError(path + ": cannot open: " + errno_text(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};

    struct stat st;
    if (::fstat(fd, &st) != 0) throw InputError(path + ": cannot open: " + errno_text(errno));
    if (S_ISDIR(st.st_mode)) throw InputError(path + ": cannot open: " + errno_text(EISDIR));
    // Devices are refused (/dev/zero would be read until memory runs out); pipes
    // are read, up to kMaxStreamBytes.
    if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) throw InputError(path + ": cannot open: not a regular file");

    if (S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) >= kMapThreshold) {
        void* m = ::mmap(nullptr, static_cast<size_t>(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
        if (m != MAP_FAILED) {
            ::madvise(m, static_cast<size_t>(st.st_size), MADV_SEQUENTIAL);
            map_ = m;
            size_ = static_cast<size_t>(st.st_size);
            return;
        }
        // Fall through to read() (e.g. a file system without mmap support).
    }

    // Regular files: one read of the known size (+1 so that EOF is seen without
    // growing). Pipes and the like: grow as needed. Not zero-initialised.
    size_t cap = S_ISREG(st.st_mode) ? static_cast<size_t>(st.st_size) + 1 : size_t(1) << 16;
    heap_.reset(new unsigned char[cap]);
    for (;;) {
        if (size_ == cap) {
            if (cap >= kMaxStreamBytes)
                throw InputError(path + ": cannot read: more than " + std::to_string(kMaxStreamBytes >> 20) +
                                 " MiB from a pipe");
            const size_t new_cap = cap * 2;
            std::unique_ptr<unsigned char[]> bigger(new unsigned char[new_cap]);
            std::memcpy(bigger.get(), heap_.get(), size_);
            heap_ = std::move(bigger);
            cap = new_cap;
        }
        const ssize_t got = ::read(fd, heap_.get() + size_, cap - size_);
        if (got < 0) {
            if (errno == EINTR) continue;
            throw InputError(path + ": cannot read: " + errno_text(errno));
        }
        if (got == 0) break;
        size_ += static_cast<size_t>(got);
    }
}

}  // namespace rt::ply_reader
