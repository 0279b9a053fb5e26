// Tests for rt::read_ply (src/loader/ply.cpp), its errors: every broken file throws
// rt::InputError with a one-line message "<path>: byte N:" (binary) or "<path>: line N:"
// (ascii) naming what is wrong; impossible counts fail fast without allocating; and files
// of 1 MiB and more, which are mapped rather than read, give the same results and errors.
//
// Each test writes small PLY files into a fresh temporary folder and reads them back.
// Files are described once as typed records (PlyFile, ply_test_support.h) and rendered in
// any of the three encodings. Expected results are worked out by hand in each test.
#include <gtest/gtest.h>

#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "ply_test_support.h"
#include "rt/core/error.h"
#include "rt/loader/ply.h"
#include "test_support.h"

namespace {

using namespace ply_test;

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

}  // namespace
