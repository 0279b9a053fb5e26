// The PLY reader tests' shared helpers (ply_test_support.h).
#include "ply_test_support.h"

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "rt/loader/ply.h"

namespace ply_test {

const char* enc_name(Enc e) {
    switch (e) {
        case Enc::Ascii:
            return "ascii";
        case Enc::Little:
            return "binary_little_endian";
        case Enc::Big:
            return "binary_big_endian";
    }
    return "?";
}

void encode_binary(std::string& out, const Val& v, bool big) {
    const std::string& t = v.type;
    if (t == "char" || t == "int8")
        put(out, static_cast<int8_t>(v.value), big);
    else if (t == "uchar" || t == "uint8")
        put(out, static_cast<uint8_t>(v.value), big);
    else if (t == "short" || t == "int16")
        put(out, static_cast<int16_t>(v.value), big);
    else if (t == "ushort" || t == "uint16")
        put(out, static_cast<uint16_t>(v.value), big);
    else if (t == "int" || t == "int32")
        put(out, static_cast<int32_t>(v.value), big);
    else if (t == "uint" || t == "uint32")
        put(out, static_cast<uint32_t>(v.value), big);
    else if (t == "float" || t == "float32")
        put(out, static_cast<float>(v.value), big);
    else if (t == "double" || t == "float64")
        put(out, v.value, big);
    else
        throw std::logic_error("test bug: unknown type " + t);
}

std::string encode_ascii(const Val& v) {
    const std::string& t = v.type;
    char buf[64];
    if (t == "float" || t == "float32" || t == "double" || t == "float64")
        std::snprintf(buf, sizeof buf, "%.17g", v.value);
    else
        std::snprintf(buf, sizeof buf, "%lld", static_cast<long long>(v.value));
    return buf;
}

Record xyz(const char* type, double x, double y, double z) { return {{type, x}, {type, y}, {type, z}}; }
Record face(const char* count_type, const char* index_type, std::vector<int64_t> ids) {
    Record r{{count_type, static_cast<double>(ids.size())}};
    for (int64_t i : ids) r.push_back({index_type, static_cast<double>(i)});
    return r;
}

std::vector<double> flat(const std::vector<rt::Vec3>& v) {
    std::vector<double> out;
    for (const rt::Vec3& p : v) out.insert(out.end(), {double(p.x), double(p.y), double(p.z)});
    return out;
}

PlyFile reference_mesh() {
    PlyFile f;
    f.elements =
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\n";
    for (size_t i = 0; i < 4; ++i)
        f.records.push_back(xyz("float", kQuadPositions[3 * i], kQuadPositions[3 * i + 1], kQuadPositions[3 * i + 2]));
    f.records.push_back(face("uchar", "int", {0, 1, 2}));
    f.records.push_back(face("uchar", "int", {0, 2, 3}));
    return f;
}

}  // namespace ply_test
