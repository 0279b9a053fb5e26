// Tests for rt::read_ply (src/loader/ply.cpp), the files it reads: the three encodings,
// properties and elements it skips, list count and index types, polygons fan-split, CRLF
// headers, ascii number spellings; and the course's own PLY file.
//
// Each test writes small PLY files into a fresh temporary folder and reads them back.
// Files are described once as typed records (PlyFile, ply_test_support.h) and rendered in
// any of the three encodings, so the same mesh can be checked in ascii, little and big
// endian. Expected results are worked out by hand in each test.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "ply_test_support.h"
#include "rt/loader/ply.h"
#include "test_support.h"

namespace {

using namespace ply_test;

// Values as a vertex holds them: each rounded to the nearest rt::Real (to +-0 below
// its range, to +-inf above it), the one rounding a coordinate owes. The identity
// for double, where every value here survives exactly.
std::vector<double> as_real(const std::vector<double>& v) {
    std::vector<double> out;
    for (double x : v) out.push_back(double(static_cast<rt::Real>(x)));
    return out;
}

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
