// Shared by the PLY reader's tests (tests/test_ply_*.cpp): PLY files described once as typed
// records (PlyFile) and rendered in any of the three encodings, the reference mesh, and
// the fixture PlyTest, which writes files into a fresh temporary folder.
#pragma once
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "rt/loader/ply.h"
#include "test_support.h"

namespace ply_test {

enum class Enc { Ascii, Little, Big };
const Enc kAllEncodings[] = {Enc::Ascii, Enc::Little, Enc::Big};

// The name of an encoding on the header's format line.
const char* enc_name(Enc e);

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

// v as its type's bytes, appended to out in the given byte order; v as ascii text.
void encode_binary(std::string& out, const Val& v, bool big);
std::string encode_ascii(const Val& v);

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
Record xyz(const char* type, double x, double y, double z);
Record face(const char* count_type, const char* index_type, std::vector<int64_t> ids);

// x y z of each vertex, in order: the form the expectations below are written in.
std::vector<double> flat(const std::vector<rt::Vec3>& v);

// The reference mesh: 4 vertices, two triangles.
//   v0 (0,0,0) v1 (1,0,0) v2 (1,1,0.5) v3 (0,1,-2.25); faces (0,1,2) (0,2,3)
PlyFile reference_mesh();
const std::vector<double> kQuadPositions = {0, 0, 0, 1, 0, 0, 1, 1, 0.5, 0, 1, -2.25};
const std::vector<uint32_t> kQuadIndices = {0, 1, 2, 0, 2, 3};

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

}  // namespace ply_test
