#include "rt/io/atomic_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "rt/core/error.h"

namespace rt {

void write_file_atomic(const std::string& path, std::string_view bytes) {
    // Write beside the target and rename over it, so that readers never see a
    // partial file and a failure leaves nothing behind.
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f) throw InputError(path + ": cannot write: " + std::strerror(errno));
    const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
    const int write_errno = errno;
    if (std::fclose(f) != 0 || !ok) {
        const int e = ok ? errno : write_errno;
        std::remove(tmp.c_str());
        throw InputError(path + ": cannot write: " + std::strerror(e));
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const int e = errno;
        std::remove(tmp.c_str());
        throw InputError(path + ": cannot write: " + std::strerror(e));
    }
}

}  // namespace rt
