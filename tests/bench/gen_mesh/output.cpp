// gen_mesh's output: files written under a temporary name and renamed, the binary
// little-endian PLY file of a mesh, and the fatal-error exit.
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gen_mesh.h"

namespace gen_mesh {

namespace {

void put_u32(unsigned char* p, uint32_t v) {
    p[0] = static_cast<unsigned char>(v);
    p[1] = static_cast<unsigned char>(v >> 8);
    p[2] = static_cast<unsigned char>(v >> 16);
    p[3] = static_cast<unsigned char>(v >> 24);
}
void put_f32(unsigned char* p, float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    put_u32(p, v);
}

}  // namespace

void die(const std::string& msg) {
    std::fprintf(stderr, "gen_mesh: %s\n", msg.c_str());
    std::exit(1);
}

Out::Out(const std::string& p) : path(p), tmp(p + ".tmp") {
    f = std::fopen(tmp.c_str(), "wb");
    if (!f) die(tmp + ": cannot open: " + std::strerror(errno));
}
void Out::write(const void* data, size_t n) {
    if (n && std::fwrite(data, 1, n, f) != n) die(tmp + ": write failed: " + std::strerror(errno));
}
void Out::commit() {
    if (std::fclose(f) != 0) die(tmp + ": write failed: " + std::strerror(errno));
    f = nullptr;
    if (std::rename(tmp.c_str(), path.c_str()) != 0) die(path + ": cannot rename: " + std::strerror(errno));
}

void write_ply(const std::string& path, const Generated& g) {
    const uint64_t nverts = g.pos.size() / 3, ntris = g.tri.size() / 3;
    Out out(path);
    char header[512];
    std::snprintf(header, sizeof header,
                  "ply\nformat binary_little_endian 1.0\n"
                  "comment raytracer tests/bench/gen_mesh: %s\n"
                  "element vertex %llu\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face %llu\nproperty list uchar int vertex_indices\nend_header\n",
                  g.comment.c_str(), static_cast<unsigned long long>(nverts), static_cast<unsigned long long>(ntris));
    out.write(std::string(header));
    std::vector<unsigned char> buf;
    buf.reserve(1 << 20);
    auto flush = [&](bool force) {
        if (force || buf.size() > (1u << 20) - 64) {
            out.write(buf.data(), buf.size());
            buf.clear();
        }
    };
    for (float x : g.pos) {
        unsigned char b4[4];
        put_f32(b4, x);
        buf.insert(buf.end(), b4, b4 + 4);
        flush(false);
    }
    for (uint64_t t = 0; t < ntris; ++t) {
        unsigned char rec[13];
        rec[0] = 3;
        put_u32(rec + 1, g.tri[3 * t]);
        put_u32(rec + 5, g.tri[3 * t + 1]);
        put_u32(rec + 9, g.tri[3 * t + 2]);
        buf.insert(buf.end(), rec, rec + 13);
        flush(false);
    }
    flush(true);
    out.commit();
}

}  // namespace gen_mesh
