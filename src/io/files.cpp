#include "rt/io/files.h"

#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>

#include "rt/core/error.h"

namespace rt {

std::string read_text_file(const std::string& path) {
    struct stat st;
    const bool known = ::stat(path.c_str(), &st) == 0;
    if (known && !S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode))
        throw InputError(path + ": cannot read: " + (S_ISDIR(st.st_mode) ? "is a folder" : "not a regular file"));
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    std::string out;
    // A regular file's size is known: one allocation, not the doublings of append
    // (which hold up to twice the file at the peak of a large scene's load).
    if (known && S_ISREG(st.st_mode) && st.st_size > 0) out.reserve(static_cast<size_t>(st.st_size));
    char buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
    const bool bad = std::ferror(f) != 0;
    const int e = errno;
    std::fclose(f);
    if (bad) throw InputError(path + ": cannot read: " + std::strerror(e));
    return out;
}

std::string dirname_of(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

std::string lower_extension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    const size_t slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

}  // namespace rt
