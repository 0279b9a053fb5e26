// Tests for rt::read_ply (src/loader/ply.cpp).
//
// Each test writes small PLY files into a fresh temporary folder and reads them back.
// Files are described once as typed records (PlyFile below) and rendered in any of
// the three encodings, so the same mesh can be checked in ascii, little and big
// endian. Expected results are worked out by hand in each test.
#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "rt/core/error.h"
#include "rt/loader/ply.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;

enum class Enc { Ascii, Little, Big };
const Enc kAllEncodings[] = {Enc::Ascii, Enc::Little, Enc::Big};

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

// One value of a record: its PLY type name and its value.
struct Val {
    std::string type;
    double value;
};
using Record = std::vector<Val>;

// Appends v to out in the given byte order.
template <typename T>
void put(std::string& out, T v, bool big) {
    unsigned char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    const bool host_little = [] {
        const uint16_t one = 1;
        unsigned char c;
        std::memcpy(&c, &one, 1);
        return c == 1;
    }();
    if (big == host_little)
        for (size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    out.append(reinterpret_cast<const char*>(b), sizeof(T));
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

// A PLY file: the header lines between "format" and "end_header", and the records.
struct PlyFile {
    std::string elements;  // "element ...\nproperty ...\n..." ('\n' line ends)
    std::vector<Record> records;

    std::string header(Enc enc, const std::string& eol = "\n") const {
        std::string h = "ply" + eol + "format " + enc_name(enc) + " 1.0" + eol + "comment written by test_ply" + eol;
        for (char c : elements) {
            if (c == '\n')
                h += eol;
            else
                h += c;
        }
        return h + "end_header" + eol;
    }
    std::string body(Enc enc) const {
        std::string b;
        for (const Record& r : records) {
            if (enc == Enc::Ascii) {
                for (size_t i = 0; i < r.size(); ++i) b += (i ? " " : "") + encode_ascii(r[i]);
                b += "\n";
            } else {
                for (const Val& v : r) encode_binary(b, v, enc == Enc::Big);
            }
        }
        return b;
    }
    std::string render(Enc enc, const std::string& eol = "\n") const { return header(enc, eol) + body(enc); }
};

// Records for common shapes.
Record xyz(const char* type, double x, double y, double z) { return {{type, x}, {type, y}, {type, z}}; }
Record face(const char* count_type, const char* index_type, std::vector<int64_t> ids) {
    Record r{{count_type, static_cast<double>(ids.size())}};
    for (int64_t i : ids) r.push_back({index_type, static_cast<double>(i)});
    return r;
}

// The reference mesh: 4 vertices, two triangles.
//   v0 (0,0,0) v1 (1,0,0) v2 (1,1,0.5) v3 (0,1,-2.25); faces (0,1,2) (0,2,3)
// x y z of each vertex, in order: the form the expectations below are written in.
std::vector<double> flat(const std::vector<rt::Vec3>& v) {
    std::vector<double> out;
    for (const rt::Vec3& p : v) out.insert(out.end(), {double(p.x), double(p.y), double(p.z)});
    return out;
}

// Values as a vertex holds them: each rounded to the nearest rt::Real (to +-0 below
// its range, to +-inf above it), the one rounding a coordinate owes. The identity
// for double, where every value here survives exactly.
std::vector<double> as_real(const std::vector<double>& v) {
    std::vector<double> out;
    for (double x : v) out.push_back(double(static_cast<rt::Real>(x)));
    return out;
}

const std::vector<double> kQuadPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0.5, 0, 1, -2.25};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

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

// The message of the rt::InputError that reading `path` throws, or a description of
// what happened instead.
std::string error_of(const std::string& path) {
    try {
        const rt::PlyMesh m = rt::read_ply(path);
        return "<no error: " + std::to_string(m.positions.size()) + " vertices>";
    } catch (const rt::InputError& e) {
        return e.what();
    } catch (const std::exception& e) {
        return std::string("<wrong exception type: ") + e.what() + ">";
    }
}

// Checks an InputError message: one line, "<path>: <place>..." and mentions `what`.
// `place` is e.g. "byte " or "line 13:".
void expect_error(const std::string& path, const std::string& place, const std::string& what) {
    const std::string m = error_of(path);
    EXPECT_EQ(m.rfind(path + ": " + place, 0), 0u) << "message: " << m;
    EXPECT_TRUE(contains(m, what)) << "expected '" << what << "' in: " << m;
    EXPECT_FALSE(contains(m, "\n")) << "message is not one line: " << m;
}

class PlyTest : public ::testing::Test {
protected:
    // Writes bytes to <tempdir>/<name> and returns the path.
    std::string write(const std::string& name, const std::string& bytes) {
        const std::string path = tmp_ / name;
        std::ofstream out(path, std::ios::binary);
        out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        if (!out) throw std::runtime_error("cannot write " + path);
        return path;
    }
    std::string write(Enc enc, const std::string& name, const PlyFile& f) {
        return write(std::string(enc_name(enc)) + "_" + name, f.render(enc));
    }

    TempDir tmp_;
};

// ---------------------------------------------------------------------------------
// Layouts and encodings

TEST_F(PlyTest, AllThreeEncodingsGiveTheSameMesh) {
    const PlyFile f = reference_mesh();
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "ref.ply", f));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
        EXPECT_EQ(m.polygons_split, 0u);
    }
}

TEST_F(PlyTest, ExtraVertexPropertiesAreSkipped) {
    // x, y, z interleaved with normals, colours, uv and a per-vertex list.
    PlyFile f;
    f.elements =
        "element vertex 4\n"
        "property float nx\nproperty float x\nproperty uchar red\nproperty float ny\n"
        "property float y\nproperty uchar green\nproperty uchar blue\nproperty float nz\n"
        "property float z\nproperty float u\nproperty float v\n"
        "element face 2\nproperty list uchar int vertex_indices\n";
    for (size_t i = 0; i < 4; ++i) {
        const double* p = &kQuadPositions[3 * i];
        f.records.push_back({{"float", 0.25},
                             {"float", p[0]},
                             {"uchar", 200},
                             {"float", -1},
                             {"float", p[1]},
                             {"uchar", 17},
                             {"uchar", 255},
                             {"float", 7},
                             {"float", p[2]},
                             {"float", 0.5},
                             {"float", 0.75}});
    }
    f.records.push_back(face("uchar", "int", {0, 1, 2}));
    f.records.push_back(face("uchar", "int", {0, 2, 3}));
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "extra.ply", f));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
    }
}

TEST_F(PlyTest, VertexListPropertyAndMixedCoordinateTypes) {
    // x short, y int, z uchar, plus a list inside the vertex record (general path).
    PlyFile f;
    f.elements =
        "element vertex 3\nproperty short x\nproperty list uchar float weights\n"
        "property int32 y\nproperty uint8 z\n"
        "element face 1\nproperty list uchar int vertex_indices\n";
    f.records.push_back({{"short", -3}, {"uchar", 2}, {"float", 1}, {"float", 2}, {"int32", 100000}, {"uint8", 7}});
    f.records.push_back({{"short", 5}, {"uchar", 0}, {"int32", -1}, {"uint8", 0}});
    f.records.push_back({{"short", 0}, {"uchar", 1}, {"float", 9}, {"int32", 2}, {"uint8", 255}});
    f.records.push_back(face("uchar", "int", {2, 1, 0}));
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "mixed.ply", f));
        EXPECT_EQ(flat(m.positions), (std::vector<double>{-3, 100000, 7, 5, -1, 0, 0, 2, 255}));
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{2, 1, 0}));
    }
}

TEST_F(PlyTest, ListCountAndIndexTypes) {
    const char* count_types[] = {"uchar", "uint8", "char", "int8",  "ushort", "uint16",
                                 "short", "int16", "int",  "int32", "uint",   "uint32"};
    const char* index_types[] = {"uchar", "uint8", "char",  "ushort", "uint16",
                                 "short", "int",   "int32", "uint",   "uint32"};
    for (const char* ct : count_types) {
        for (const char* it : index_types) {
            // A triangle and a quad: exercises both the triangle and the polygon path.
            PlyFile f;
            f.elements =
                "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
                "element face 2\nproperty list " +
                std::string(ct) + " " + it + " vertex_indices\n";
            for (size_t i = 0; i < 4; ++i)
                f.records.push_back(
                    xyz("float", kQuadPositions[3 * i], kQuadPositions[3 * i + 1], kQuadPositions[3 * i + 2]));
            f.records.push_back(face(ct, it, {3, 1, 2}));
            f.records.push_back(face(ct, it, {0, 1, 2, 3}));
            for (Enc enc : kAllEncodings) {
                SCOPED_TRACE(std::string(enc_name(enc)) + " list " + ct + " " + it);
                const rt::PlyMesh m = rt::read_ply(write(enc, std::string(ct) + "_" + it + ".ply", f));
                EXPECT_EQ(flat(m.positions), kQuadPositions);
                EXPECT_EQ(m.indices, (std::vector<uint32_t>{3, 1, 2, 0, 1, 2, 0, 2, 3}));
                EXPECT_EQ(m.polygons_split, 1u);
            }
        }
    }
}

TEST_F(PlyTest, VertexIndexSpelling) {
    PlyFile f = reference_mesh();
    f.elements =
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uint8 int32 vertex_index\n";
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "vertex_index.ply", f));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
    }
}

TEST_F(PlyTest, QuadAndPentagonAreFanSplit) {
    PlyFile f;
    f.elements =
        "element vertex 6\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 3\nproperty list uchar int vertex_indices\n";
    for (int i = 0; i < 6; ++i) f.records.push_back(xyz("float", i, 2 * i, -i));
    f.records.push_back(face("uchar", "int", {5, 4, 3, 2}));     // quad
    f.records.push_back(face("uchar", "int", {1, 2, 3}));        // triangle
    f.records.push_back(face("uchar", "int", {0, 1, 2, 3, 4}));  // pentagon
    const std::vector<uint32_t> expected = {
        5, 4, 3, 5, 3, 2,           // quad: (v0 v1 v2) (v0 v2 v3)
        1, 2, 3,                    // triangle as is
        0, 1, 2, 0, 2, 3, 0, 3, 4,  // pentagon: three triangles around v0
    };
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "polygons.ply", f));
        EXPECT_EQ(m.indices, expected);
        EXPECT_EQ(m.polygons_split, 2u);
        EXPECT_EQ(m.positions.size(), 6u);
        EXPECT_EQ(m.positions[5].y, 10.0);
    }
}

TEST_F(PlyTest, OtherElementsAndFacePropertiesAreSkipped) {
    PlyFile f;
    f.elements =
        "element material 2\nproperty float r\nproperty uchar id\nproperty list uchar uchar name\n"
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element edge 2\nproperty list int int verts\nproperty uchar flag\n"
        "element face 2\nproperty uchar flags\nproperty list uchar int vertex_indices\n"
        "property list ushort float texcoord\nproperty double area\n"
        "element extra 3\nproperty list short double stuff\n"
        "element nothing 5\n";  // no properties at all
    f.records.push_back({{"float", 0.5}, {"uchar", 1}, {"uchar", 3}, {"uchar", 65}, {"uchar", 66}, {"uchar", 67}});
    f.records.push_back({{"float", 1.5}, {"uchar", 2}, {"uchar", 0}});
    for (size_t i = 0; i < 4; ++i)
        f.records.push_back(xyz("float", kQuadPositions[3 * i], kQuadPositions[3 * i + 1], kQuadPositions[3 * i + 2]));
    f.records.push_back({{"int", 2}, {"int", 0}, {"int", 1}, {"uchar", 9}});
    f.records.push_back({{"int", 3}, {"int", 1}, {"int", 2}, {"int", 3}, {"uchar", 8}});
    Record f0 = {{"uchar", 1}};
    for (const Val& v : face("uchar", "int", {0, 1, 2})) f0.push_back(v);
    for (const Val& v : Record{{"ushort", 2}, {"float", 0.1}, {"float", 0.2}, {"double", 4.5}}) f0.push_back(v);
    Record f1 = {{"uchar", 0}};
    for (const Val& v : face("uchar", "int", {0, 2, 3})) f1.push_back(v);
    for (const Val& v : Record{{"ushort", 0}, {"double", -1}}) f1.push_back(v);
    f.records.push_back(f0);
    f.records.push_back(f1);
    f.records.push_back({{"short", 1}, {"double", 3}});
    f.records.push_back({{"short", 0}});
    f.records.push_back({{"short", 2}, {"double", 1}, {"double", 2}});
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "elements.ply", f));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
    }
}

TEST_F(PlyTest, FacesBeforeVerticesAndNoFaceElement) {
    // Indices are checked against the header's vertex count, so order does not matter.
    PlyFile f;
    f.elements =
        "element face 1\nproperty list uchar int vertex_indices\n"
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    f.records.push_back(face("uchar", "int", {2, 0, 1}));
    for (int i = 0; i < 3; ++i) f.records.push_back(xyz("float", i, i, i));
    PlyFile points;
    points.elements = "element vertex 2\nproperty double x\nproperty double y\nproperty double z\n";
    points.records.push_back(xyz("double", 1, 2, 3));
    points.records.push_back(xyz("double", 4, 5, 6));
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const rt::PlyMesh m = rt::read_ply(write(enc, "faces_first.ply", f));
        EXPECT_EQ(flat(m.positions), (std::vector<double>{0, 0, 0, 1, 1, 1, 2, 2, 2}));
        EXPECT_EQ(m.indices, (std::vector<uint32_t>{2, 0, 1}));
        const rt::PlyMesh p = rt::read_ply(write(enc, "points.ply", points));
        EXPECT_EQ(flat(p.positions), (std::vector<double>{1, 2, 3, 4, 5, 6}));
        EXPECT_TRUE(p.indices.empty());
    }
}

TEST_F(PlyTest, CrlfHeader) {
    const PlyFile f = reference_mesh();
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        std::string bytes = f.render(enc, "\r\n");
        if (enc == Enc::Ascii) {
            // CRLF in the body as well.
            std::string crlf;
            for (char c : bytes) {
                if (c == '\n' && (crlf.empty() || crlf.back() != '\r')) crlf += '\r';
                crlf += c;
            }
            bytes = crlf;
        }
        const rt::PlyMesh m = rt::read_ply(write(std::string(enc_name(enc)) + "_crlf.ply", bytes));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
    }
}

TEST_F(PlyTest, TrailingGarbageIsIgnored) {
    const PlyFile f = reference_mesh();
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        const std::string bytes = f.render(enc) + std::string("garbage\n\0\x01\xff", 11);
        const rt::PlyMesh m = rt::read_ply(write(std::string(enc_name(enc)) + "_trail.ply", bytes));
        EXPECT_EQ(flat(m.positions), kQuadPositions);
        EXPECT_EQ(m.indices, kQuadIndices);
    }
}

TEST_F(PlyTest, BigEndianDoubleCoordinates) {
    PlyFile f;
    f.elements =
        "element vertex 3\nproperty float64 x\nproperty double y\nproperty double z\n"
        "element face 1\nproperty list uint16 uint32 vertex_indices\n";
    const std::vector<double> pos = {0.1,    -1e-300, 123456789.123456789, 1e300, 2.0 / 3.0, -0.0, 3.141592653589793,
                                     5e-324, -7.25};
    for (int i = 0; i < 3; ++i) f.records.push_back(xyz("double", pos[3 * i], pos[3 * i + 1], pos[3 * i + 2]));
    f.records.push_back(face("uint16", "uint32", {1, 2, 0}));
    const std::string bytes = f.render(Enc::Big);
    // Spot-check the encoding itself: 0.1 big-endian starts with 0x3f 0xb9.
    const size_t body = f.header(Enc::Big).size();
    ASSERT_EQ(static_cast<unsigned char>(bytes[body]), 0x3fu);
    ASSERT_EQ(static_cast<unsigned char>(bytes[body + 1]), 0xb9u);
    const rt::PlyMesh m = rt::read_ply(write("be_double.ply", bytes));
    EXPECT_EQ(flat(m.positions), as_real(pos));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{1, 2, 0}));
    // The same values survive ascii (%.17g) too.
    const rt::PlyMesh a = rt::read_ply(write(Enc::Ascii, "double.ply", f));
    EXPECT_EQ(flat(a.positions), as_real(pos));
}

TEST_F(PlyTest, AsciiNumberSpellings) {
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "+1.5 -2e3 .25\n"
        "1E-2\t0\t  7\n"
        "  -0 3. 1e+1\n"
        "3 +0 1 2\n";
    const rt::PlyMesh m = rt::read_ply(write("spellings.ply", text));
    EXPECT_EQ(flat(m.positions), as_real({1.5, -2000, 0.25, 0.01, 0, 7, -0.0, 3, 10}));
    EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

// ---------------------------------------------------------------------------------
// Errors

TEST_F(PlyTest, MissingFileAndDirectory) {
    const std::string missing = tmp_ / "does_not_exist.ply";
    const std::string m = error_of(missing);
    EXPECT_EQ(m, missing + ": cannot open: " + std::strerror(ENOENT));
    const std::string d = error_of(tmp_.path());
    EXPECT_EQ(d.rfind(tmp_.path() + ": cannot open: ", 0), 0u) << d;
}

TEST_F(PlyTest, NotAPlyFile) {
    expect_error(write("empty.ply", ""), "byte 0:", "not a PLY file");
    expect_error(write("text.ply", "hello world\nformat ascii 1.0\n"), "byte 0:", "not a PLY file");
    expect_error(write("upper.ply", "PLY\nformat ascii 1.0\nend_header\n"), "byte 0:", "not a PLY file");
    expect_error(write("binary.ply", std::string("\x89PNG\r\n\x1a\n\0\0", 10)), "byte 0:", "not a PLY file");
}

TEST_F(PlyTest, HeaderErrors) {
    // The byte offset is that of the offending header line.
    expect_error(write("fmt.ply", "ply\nformat binary_middle_endian 1.0\nend_header\n"),
                 "byte 4:", "unknown format 'binary_middle_endian'");
    expect_error(write("ver.ply", "ply\nformat ascii 2.0\nend_header\n"), "byte 4:", "unsupported PLY version");
    expect_error(write("nofmt.ply", "ply\nelement vertex 0\nproperty float x\nend_header\n"), "byte ",
                 "missing format");
    expect_error(write("type.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float33 x\nend_header\n"),
                 "byte 38:", "unknown type 'float33'");
    expect_error(write("ltype.ply",
                       "ply\nformat ascii 1.0\nelement face 1\nproperty list uchar long "
                       "vertex_indices\nend_header\n"),
                 "byte ", "unknown type 'long'");
    expect_error(write("fcount.ply",
                       "ply\nformat ascii 1.0\nelement face 1\nproperty list float int "
                       "vertex_indices\nend_header\n"),
                 "byte ", "not an integer type");
    expect_error(write("count.ply", "ply\nformat ascii 1.0\nelement vertex -3\nend_header\n"),
                 "byte 21:", "bad element count '-3'");
    expect_error(write("kw.ply", "ply\nformat ascii 1.0\nelemnt vertex 3\nend_header\n"),
                 "byte 21:", "unknown header keyword 'elemnt'");
    expect_error(write("prop_first.ply", "ply\nformat ascii 1.0\nproperty float x\nend_header\n"),
                 "byte 21:", "before any element");
}

TEST_F(PlyTest, MissingEndHeader) {
    // Text header that simply stops.
    expect_error(write("noend.ply",
                       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                       "property float y\nproperty float z\n"),
                 "byte ", "missing end_header");
    // Without the final newline.
    expect_error(write("noend2.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_hea"), "byte ",
                 "missing end_header");
    // A binary body straight after the properties.
    PlyFile f = reference_mesh();
    std::string bytes = f.header(Enc::Little);
    bytes.erase(bytes.find("end_header\n"));
    bytes += f.body(Enc::Little);
    expect_error(write("noend3.ply", bytes), "byte ", "end_header");
}

TEST_F(PlyTest, MissingCoordinatesOrIndexList) {
    expect_error(write("noz.ply",
                       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                       "property float y\nproperty float nz\nend_header\n1 2 3\n"),
                 "byte 21:", "no property 'z'");
    expect_error(write("novertex.ply", "ply\nformat ascii 1.0\nend_header\n"), "byte ", "no 'vertex' element");
    expect_error(write("nolist.ply",
                       "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                       "property float y\nproperty float z\nelement face 0\n"
                       "property list uchar int indices\nend_header\n1 2 3\n"),
                 "byte ", "no 'vertex_indices'");
}

TEST_F(PlyTest, TruncatedBinaryBody) {
    const PlyFile ref = reference_mesh();
    for (Enc enc : {Enc::Little, Enc::Big}) {
        SCOPED_TRACE(enc_name(enc));
        // Triangles only: the size check sees that the declared records cannot fit.
        std::string bytes = ref.render(enc);
        bytes.resize(bytes.size() - 2);
        expect_error(write(std::string(enc_name(enc)) + "_short.ply", bytes), "byte ", "more than the file can hold");
        // A quad as the last face passes the size check (3 indices minimum) and then
        // runs out of bytes inside the record: reported at the start of the missing data.
        PlyFile q = ref;
        q.records.back() = face("uchar", "int", {0, 1, 2, 3});
        std::string qb = q.render(enc);
        qb.resize(qb.size() - 2);
        const size_t list_start = q.header(enc).size() + 4 * 12 + 13 + 1;
        expect_error(write(std::string(enc_name(enc)) + "_short_quad.ply", qb),
                     "byte " + std::to_string(list_start) + ":",
                     "unexpected end of file in element 'face' record 1 of 2");
        // Vertices cut in the middle.
        std::string vb = ref.header(enc) + ref.body(enc).substr(0, 30);
        expect_error(write(std::string(enc_name(enc)) + "_short_vertex.ply", vb), "byte ",
                     "more than the file can hold");
    }
}

TEST_F(PlyTest, TruncatedAsciiBody) {
    // 9 header lines; vertices on lines 10-12; the face on line 13 lacks its last index.
    const std::string text =
        "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0.0 0.0 0.0\n1.0 0.0 0.0\n0.0 1.0 0.0\n3 0 1\n";  // long enough for the size check
    expect_error(write("ascii_short.ply", text), "line 14:", "unexpected end of file in element 'face' record 0 of 1");
    const std::string no_nl = text.substr(0, text.size() - 1);
    expect_error(write("ascii_short2.ply", no_nl), "line 13:", "unexpected end of file");
}

TEST_F(PlyTest, VertexIndexOutOfRange) {
    // Index == vertex count, through the binary fast path (uchar + int).
    PlyFile f = reference_mesh();
    f.records.back() = face("uchar", "int", {0, 2, 4});
    for (Enc enc : {Enc::Little, Enc::Big}) {
        const size_t index_offset = f.header(enc).size() + 4 * 12 + 13 + 1 + 8;
        expect_error(write(enc, "range.ply", f), "byte " + std::to_string(index_offset) + ":",
                     "vertex index 4 out of range (vertex count 4)");
    }
    expect_error(write(Enc::Ascii, "range.ply", f), "line 16:", "vertex index 4 out of range");

    // Negative index, fast path and general path (short indices).
    f.records.back() = face("uchar", "int", {0, -1, 2});
    expect_error(write(Enc::Little, "neg.ply", f), "byte ", "vertex index -1 out of range");
    expect_error(write(Enc::Ascii, "neg.ply", f), "line 16:", "vertex index -1 out of range");
    PlyFile s = reference_mesh();
    s.elements =
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar short vertex_indices\n";
    s.records[4] = face("uchar", "short", {0, 1, -2});
    s.records[5] = face("uchar", "short", {0, 1, 2});
    expect_error(write(Enc::Big, "neg_short.ply", s), "byte ", "vertex index -2 out of range");
    // Large uint index in a quad.
    s.elements =
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uint uint vertex_indices\n";
    s.records[4] = face("uint", "uint", {0, 1, 2});
    s.records[5] = face("uint", "uint", {0, 1, 2, 4000000000LL});
    expect_error(write(Enc::Little, "big_uint.ply", s), "byte ", "vertex index 4000000000");
}

TEST_F(PlyTest, NonFiniteCoordinates) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    const double inf = std::numeric_limits<double>::infinity();
    PlyFile f = reference_mesh();
    f.records[2] = xyz("float", 1, nan, 0);
    for (Enc enc : {Enc::Little, Enc::Big}) {
        // Vertex 2's y: header + 2 records of 12 bytes + 4.
        const size_t off = f.header(enc).size() + 2 * 12 + 4;
        expect_error(write(enc, "nan.ply", f), "byte " + std::to_string(off) + ":", "non-finite coordinate");
    }
    f.records[2] = xyz("float", 1, 0, -inf);
    expect_error(write(Enc::Little, "inf.ply", f), "byte ", "non-finite coordinate");
    expect_error(write(Enc::Ascii, "inf.ply", f), "line 13:", "non-finite coordinate");
    // Double coordinates, general path (mixed types).
    PlyFile d;
    d.elements = "element vertex 1\nproperty double x\nproperty float y\nproperty double z\n";
    d.records.push_back({{"double", inf}, {"float", 0}, {"double", 0}});
    expect_error(write(Enc::Big, "inf_double.ply", d), "byte ", "non-finite coordinate");
    // ascii spellings that from_chars accepts; and numbers beyond double range.
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n";
    expect_error(write("nan.txt.ply", head + "0 nan 0\n"), "line 8:", "non-finite coordinate");
    expect_error(write("infinity.txt.ply", head + "0 0 -infinity\n"), "line 8:", "non-finite");
    expect_error(write("huge.txt.ply", head + "1e999 0 0\n"), "line 8:", "out of range");
}

TEST_F(PlyTest, BadAsciiNumbers) {
    const std::string head =
        "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    expect_error(write("bad1.ply", head + "0 0 0\n1.0abc 0 0\n3 0 1 1\n"), "line 11:", "bad number '1.0abc'");
    expect_error(write("bad2.ply", head + "0 0 0\n1 0 0\n3 0 1 1.0\n"), "line 12:", "bad integer '1.0'");
    expect_error(write("bad3.ply", head + "0 0 0\n1 0 0\nthree 0 1 1\n"), "line 12:", "bad integer 'three'");
}

TEST_F(PlyTest, NegativeListCounts) {
    // Index list with a signed count type.
    PlyFile f = reference_mesh();
    f.elements =
        "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list char int vertex_indices\n";
    f.records[4] = face("char", "int", {0, 1, 2});
    f.records[5] = {{"char", -1}, {"int", 0}, {"int", 0}, {"int", 0}};
    const size_t count_offset = f.header(Enc::Little).size() + 4 * 12 + 13;
    expect_error(write(Enc::Little, "neg_count.ply", f), "byte " + std::to_string(count_offset) + ":",
                 "negative list count -1");
    expect_error(write(Enc::Ascii, "neg_count.ply", f), "line 16:", "negative list count -1");
    // In a skipped element.
    PlyFile g = reference_mesh();
    g.elements += "element edge 1\nproperty list int int verts\n";
    g.records.push_back({{"int", -5}, {"int", 0}, {"int", 0}});
    for (Enc enc : {Enc::Little, Enc::Big})
        expect_error(write(enc, "neg_edge.ply", g), "byte ", "negative list count -5");
    expect_error(write(Enc::Ascii, "neg_edge.ply", g), "line ", "negative list count -5");
}

TEST_F(PlyTest, FacesWithFewerThanThreeVertices) {
    for (int n : {0, 1, 2}) {
        PlyFile f = reference_mesh();
        std::vector<int64_t> ids(static_cast<size_t>(n), 0);
        f.records[4] = face("uchar", "int", ids);
        // Padding so the size check (3 indices per face) passes.
        const std::string pad(64, '\0');
        const std::string what = "face with " + std::to_string(n) + " vertices";
        expect_error(write("small_le.ply", f.render(Enc::Little) + pad), "byte ", what);
        expect_error(write("small_be.ply", f.render(Enc::Big) + pad), "byte ", what);
        expect_error(write("small.txt.ply", f.render(Enc::Ascii) + pad), "line 15:", what);
    }
}

TEST_F(PlyTest, ImpossibleCountsFailFastWithoutAllocating) {
    // 2^40 faces, 2^40 vertices, and the largest 64-bit count, on tiny files.
    const std::string big = std::to_string(uint64_t(1) << 40);
    const std::string faces =
        "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
        "element face " +
        big + "\nproperty list uchar int vertex_indices\n";
    const std::string verts = "element vertex " + big + "\nproperty float x\nproperty float y\nproperty float z\n";
    const std::string skipped =
        "element vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
        "element junk 18446744073709551615\nproperty list uchar uchar stuff\n";
    // The small elements get their records, so only the huge count is at fault.
    PlyFile cases[3];
    cases[0].elements = faces;
    for (int i = 0; i < 3; ++i) cases[0].records.push_back(xyz("float", i, 0, 1));
    cases[1].elements = verts;
    cases[2].elements = skipped;
    cases[2].records.push_back(xyz("float", 1, 2, 3));
    const char* expected_element[3] = {"element 'face'", "element 'vertex'", "element 'junk'"};
    for (Enc enc : kAllEncodings) {
        SCOPED_TRACE(enc_name(enc));
        for (int c = 0; c < 3; ++c) {
            const PlyFile& f = cases[c];
            const std::string path = write(enc, "huge.ply", f);
            EXPECT_TRUE(contains(error_of(path), expected_element[c])) << error_of(path);
            const auto t0 = std::chrono::steady_clock::now();
            expect_error(path, "byte ", "more than the file can hold");
            const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            EXPECT_LT(secs, 1.0);
        }
    }
    // One past the largest 64-bit count is not a count at all.
    expect_error(write("overflow.ply",
                       "ply\nformat binary_little_endian 1.0\n"
                       "element vertex 18446744073709551616\nend_header\n"),
                 "byte ", "bad element count");
}

TEST_F(PlyTest, LargeBinaryFile) {
    // Files of 1 MiB and more are mapped rather than read; same results and errors.
    // A 300 x 300 vertex grid, two triangles per cell, plus one quad at the end.
    const int n = 300;
    const uint32_t nv = n * n;
    const uint32_t ntri = 2 * (n - 1) * (n - 1);
    for (Enc enc : {Enc::Little, Enc::Big}) {
        SCOPED_TRACE(enc_name(enc));
        const bool big = enc == Enc::Big;
        std::string bytes = std::string("ply\nformat ") + enc_name(enc) + " 1.0\nelement vertex " + std::to_string(nv) +
                            "\nproperty float x\nproperty float y\nproperty float z\n"
                            "element face " +
                            std::to_string(ntri + 1) + "\nproperty list uchar uint vertex_indices\nend_header\n";
        std::vector<double> pos;
        std::vector<uint32_t> idx;
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const float v[3] = {static_cast<float>(i) * 0.5f, static_cast<float>(j),
                                    static_cast<float>((i * 7 + j) % 13) - 6.0f};
                for (float c : v) {
                    put(bytes, c, big);
                    pos.push_back(c);
                }
            }
        }
        for (int j = 0; j + 1 < n; ++j) {
            for (int i = 0; i + 1 < n; ++i) {
                const uint32_t a = static_cast<uint32_t>(j * n + i), b = a + 1, c = a + n, d = c + 1;
                for (const uint32_t t : {a, b, d, a, d, c}) idx.push_back(t);
                put(bytes, uint8_t(3), big);
                for (const uint32_t t : {a, b, d}) put(bytes, t, big);
                put(bytes, uint8_t(3), big);
                for (const uint32_t t : {a, d, c}) put(bytes, t, big);
            }
        }
        put(bytes, uint8_t(4), big);
        for (const uint32_t t : {0u, 1u, nv - 1, nv - 2}) put(bytes, t, big);
        for (const uint32_t t : {0u, 1u, nv - 1, 0u, nv - 1, nv - 2}) idx.push_back(t);
        ASSERT_GT(bytes.size(), size_t(1) << 20);

        const rt::PlyMesh m = rt::read_ply(write(std::string(enc_name(enc)) + "_large.ply", bytes));
        EXPECT_EQ(flat(m.positions), pos);
        EXPECT_EQ(m.indices, idx);
        EXPECT_EQ(m.polygons_split, 1u);

        // The same file cut inside the final quad.
        expect_error(write(std::string(enc_name(enc)) + "_large_cut.ply", bytes.substr(0, bytes.size() - 3)),
                     "byte " + std::to_string(bytes.size() - 16) + ":", "unexpected end of file");
        // An out-of-range index in the last triangle of the fast path.
        std::string bad = bytes;
        const size_t last_tri_index = bytes.size() - 17 - 4;
        std::string v;
        put(v, nv, big);
        bad.replace(last_tri_index, 4, v);
        expect_error(write(std::string(enc_name(enc)) + "_large_bad.ply", bad),
                     "byte " + std::to_string(last_tri_index) + ":",
                     "vertex index " + std::to_string(nv) + " out of range");
    }
}

// ---------------------------------------------------------------------------------
// The course's own files

TEST(PlyOfficialFiles, TonRoosendaalMesh2) {
    SKIP_UNLESS_SHARED("the official PLY file mesh_2.ply");
    const std::string path = shared_dir() + "/scenes/hw1/akif_uslu/ton_Roosendaal_smooth_ply/mesh_2.ply";
    ASSERT_TRUE(file_exists(path)) << path << " is missing from the course's shared folder";
    const rt::PlyMesh m = rt::read_ply(path);
    EXPECT_EQ(m.positions.size(), 31072u);
    EXPECT_EQ(m.indices.size(), 3u * 62160u);
    EXPECT_EQ(m.polygons_split, 0u);
    for (uint32_t i : m.indices) ASSERT_LT(i, 31072u);
    for (const rt::Vec3& v : m.positions) ASSERT_TRUE(rt::isfinite(v));
    // Every vertex is used by some triangle.
    std::vector<char> used(31072, 0);
    for (uint32_t i : m.indices) used[i] = 1;
    size_t unused = 0;
    for (char u : used) unused += u == 0;
    EXPECT_EQ(unused, 0u);
}

}  // namespace
