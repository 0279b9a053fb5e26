// Binary little-endian PLY output for converted meshes (read back by src/loader/ply.cpp).
#include <cstring>
#include <string>

#include "rt/convert/convert.h"
#include "rt/core/error.h"
#include "rt/io/atomic_file.h"

namespace rt {
namespace {

void put_u32(std::string& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>((v >> (8 * i)) & 0xff);
}

void put_f32(std::string& out, float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    put_u32(out, bits);
}

}  // namespace

void write_ply(const std::string& path, const std::vector<double>& positions, const std::vector<uint32_t>& indices) {
    const size_t vertices = positions.size() / 3, triangles = indices.size() / 3;
    std::string out = "ply\nformat binary_little_endian 1.0\ncomment written by rtconvert\n";
    out += "element vertex " + std::to_string(vertices) + "\n";
    bool floats = true;
    for (double x : positions) floats = floats && double(static_cast<float>(x)) == x;
    out += floats ? "property float x\nproperty float y\nproperty float z\n"
                  : "property double x\nproperty double y\nproperty double z\n";
    out += "element face " + std::to_string(triangles) + "\n";
    out += "property list uchar int vertex_indices\nend_header\n";
    out.reserve(out.size() + vertices * (floats ? 12 : 24) + triangles * 13);
    for (size_t i = 0; i < vertices * 3; ++i) {
        if (floats) {
            put_f32(out, static_cast<float>(positions[i]));
        } else {
            uint64_t bits;
            std::memcpy(&bits, &positions[i], 8);
            put_u32(out, uint32_t(bits));
            put_u32(out, uint32_t(bits >> 32));
        }
    }
    for (size_t t = 0; t < triangles; ++t) {
        out += static_cast<char>(3);
        for (int k = 0; k < 3; ++k) put_u32(out, indices[3 * t + k]);
    }
    write_file_atomic(path, out);
}

}  // namespace rt
