// What the parts of the PLY reader share (the contract is in rt/loader/ply.h; ply.cpp
// drives the parts): the header's model (scalar types, properties, elements), the
// bytes being read with the messages that name a place in them, and the entry
// points of the header parser (ply_header.cpp) and of the two body decoders
// (ply_binary.cpp, ply_ascii.cpp). ply_format.cpp holds the out-of-line helpers.
//
// Every error is an rt::InputError with one line "<path>: byte <offset>: <what>"
// (header and binary body; the offset is absolute in the file, for the header the
// start of the offending line) or "<path>: line <n>: <what>" (ascii body; lines
// are counted from the top of the file, header included).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rt/loader/ply.h"
#include "triangle_sink.h"

namespace rt::ply_reader {

// ---------------------------------------------------------------------------------
// Types

enum class Type : uint8_t { I8, U8, I16, U16, I32, U32, F32, F64 };

constexpr size_t type_size(Type t) {
    switch (t) {
        case Type::I8:
        case Type::U8:
            return 1;
        case Type::I16:
        case Type::U16:
            return 2;
        case Type::I32:
        case Type::U32:
        case Type::F32:
            return 4;
        case Type::F64:
            return 8;
    }
    return 0;
}

constexpr bool is_integer(Type t) { return t != Type::F32 && t != Type::F64; }

// Both spellings of every PLY 1.0 scalar type: sets `out` and returns true for a
// known name.
bool parse_type(std::string_view s, Type& out);

// What the reader does with a property.
enum class Role : uint8_t { Skip, X, Y, Z, Indices };

struct Property {
    std::string name;
    Type type = Type::U8;  // scalar type, or the item type of a list
    bool is_list = false;
    Type count_type = Type::U8;  // lists only; always an integer type
    Role role = Role::Skip;
};

struct Element {
    std::string name;
    uint64_t count = 0;
    std::vector<Property> props;
    size_t offset = 0;  // byte offset of the "element" header line, for messages

    bool has_lists() const {
        for (const Property& p : props)
            if (p.is_list) return true;
        return false;
    }
    // Bytes of one record when it has no lists.
    size_t fixed_size() const {
        size_t n = 0;
        for (const Property& p : props) n += type_size(p.type);
        return n;
    }
};

enum class Format { Ascii, BinaryLittle, BinaryBig };

// What the header says (read_header): the elements in file order, where the body
// starts, and which elements hold the vertices and the faces.
struct PlyHeader {
    static constexpr size_t kNone = static_cast<size_t>(-1);

    Format format = Format::Ascii;
    std::vector<Element> elements;
    size_t body_offset = 0;  // first byte after the end_header line
    size_t body_line = 0;    // 1-based line number of that byte (ascii)
    size_t header_end = 0;   // offset of the end_header line, for messages
    size_t vertex_el = kNone;
    size_t face_el = kNone;  // kNone: a point set, no triangles
    uint64_t vertex_count = 0;
};

// ---------------------------------------------------------------------------------
// The bytes being read and the messages

// The file's bytes and its name for messages. The fail_ functions throw
// rt::InputError in the formats above.
struct PlyInput {
    const std::string& path;
    const unsigned char* data;
    size_t size;

    [[noreturn]] RT_PLY_COLD void fail_byte(size_t offset, const std::string& what) const;
    [[noreturn]] RT_PLY_COLD void fail_line(size_t line, const std::string& what) const;
    [[noreturn]] RT_PLY_COLD void fail_eof(size_t offset, const Element& el, uint64_t rec) const;
};

// "element '<name>' record <rec> of <count>", the place in messages about the body.
std::string record_text(const Element& el, uint64_t rec);
// The message for vertex index v of a mesh of nv vertices.
std::string bad_index_text(int64_t v, uint64_t nv);

// A token from the file, quoted for a one-line message: at most 40 characters,
// anything unprintable shown as '?'.
std::string quoted(std::string_view s);

constexpr bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

// ---------------------------------------------------------------------------------
// The parts

// Parses and checks the header (ply_header.cpp): locates the vertex x/y/z and the
// face index list by name, marks every other property Skip, and rejects element
// counts the bytes after the header cannot hold before anything is allocated.
PlyHeader read_header(const PlyInput& in);

// Decode the body described by `h` (which read_header returned for `in`) into
// mesh.positions and, fan-split, into `tris`; count the split polygons in
// mesh.polygons_split. Anything after the last element is ignored.
void read_binary_body(const PlyInput& in, const PlyHeader& h, PlyMesh& mesh, TriangleSink& tris);  // ply_binary.cpp
void read_ascii_body(const PlyInput& in, const PlyHeader& h, PlyMesh& mesh, TriangleSink& tris);   // ply_ascii.cpp

}  // namespace rt::ply_reader
