// The PLY reader's shared helpers (ply_format.h): type names and messages.
#include "ply_format.h"

#include "rt/core/error.h"

namespace rt::ply_reader {

bool parse_type(std::string_view s, Type& out) {
    struct Entry {
        const char* name;
        Type type;
    };
    static const Entry table[] = {
        {"char", Type::I8},   {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
        {"short", Type::I16}, {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
        {"int", Type::I32},   {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
        {"float", Type::F32}, {"float32", Type::F32}, {"double", Type::F64}, {"float64", Type::F64},
    };
    for (const Entry& e : table) {
        if (s == e.name) {
            out = e.type;
            return true;
        }
    }
    return false;
}

std::string quoted(std::string_view s) {
    std::string out = "'";
    const size_t n = s.size() < 40 ? s.size() : 40;
    for (size_t i = 0; i < n; ++i) {
        const unsigned char c = static_cast<unsigned char>(s[i]);
        out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
    }
    if (s.size() > n) out += "...";
    out += "'";
    return out;
}

void PlyInput::fail_byte(size_t offset, const std::string& what) const {
    throw InputError(path + ": byte " + std::to_string(offset) + ": " + what);
}
void PlyInput::fail_line(size_t line, const std::string& what) const {
    throw InputError(path + ": line " + std::to_string(line) + ": " + what);
}
void PlyInput::fail_eof(size_t offset, const Element& el, uint64_t rec) const {
    fail_byte(offset, "unexpected end of file in " + record_text(el, rec));
}

std::string record_text(const Element& el, uint64_t rec) {
    return "element '" + el.name + "' record " + std::to_string(rec) + " of " + std::to_string(el.count);
}
std::string bad_index_text(int64_t v, uint64_t nv) {
    return "vertex index " + std::to_string(v) + " out of range (vertex count " + std::to_string(nv) + ")";
}

}  // namespace rt::ply_reader
