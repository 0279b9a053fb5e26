// The PLY header parser (read_header in ply_format.h): one pass over the header
// lines into elements and properties, then the roles of the properties the reader
// uses, then the element counts checked against the bytes that follow the header,
// so that a hostile header cannot make the body decoders allocate or loop beyond
// what the file can hold.
#include <charconv>
#include <cstring>
#include <limits>

#include "ply_format.h"

namespace rt::ply_reader {
namespace {

// Words of one header line (separated by blanks; the '\n' is already gone).
void split_words(std::string_view line, std::vector<std::string_view>& out) {
    out.clear();
    size_t i = 0;
    while (i < line.size()) {
        while (i < line.size() && is_space(line[i])) ++i;
        if (i == line.size()) break;
        size_t j = i;
        while (j < line.size() && !is_space(line[j])) ++j;
        out.push_back(line.substr(i, j - i));
        i = j;
    }
}

// a * b, saturating at UINT64_MAX.
uint64_t mul_sat(uint64_t a, uint64_t b) {
    if (a != 0 && b > std::numeric_limits<uint64_t>::max() / a) return std::numeric_limits<uint64_t>::max();
    return a * b;
}
uint64_t add_sat(uint64_t a, uint64_t b) {
    return (b > std::numeric_limits<uint64_t>::max() - a) ? std::numeric_limits<uint64_t>::max() : a + b;
}

class HeaderParser {
public:
    HeaderParser(const PlyInput& in, PlyHeader& h) : in_(in), h_(h) {}

    void parse_header() {
        std::vector<std::string_view> w;
        size_t pos = 0;
        size_t line_no = 0;
        bool have_format = false;
        for (;;) {
            if (pos >= in_.size) {
                if (line_no == 0) in_.fail_byte(0, "not a PLY file (empty file)");
                in_.fail_byte(pos, "missing end_header (end of file inside the header)");
            }
            const void* nl = std::memchr(in_.data + pos, '\n', in_.size - pos);
            const size_t line_end =
                nl ? static_cast<size_t>(static_cast<const unsigned char*>(nl) - in_.data) : in_.size;
            const size_t next = nl ? line_end + 1 : in_.size;
            ++line_no;
            const std::string_view line(reinterpret_cast<const char*>(in_.data + pos), line_end - pos);
            split_words(line, w);

            if (line_no == 1) {
                if (w.size() != 1 || w[0] != "ply") in_.fail_byte(0, "not a PLY file (the first line is not 'ply')");
            } else if (w.empty()) {
                // Blank lines are tolerated.
            } else if (w[0] == "end_header") {
                if (w.size() != 1) in_.fail_byte(pos, "malformed end_header line");
                if (!have_format) in_.fail_byte(pos, "missing format line");
                h_.header_end = pos;
                h_.body_offset = next;
                h_.body_line = line_no + 1;
                return;
            } else if (!nl) {
                // The header's last line is not end_header: it is truncated or absent.
                in_.fail_byte(pos, "missing end_header (end of file inside the header)");
            } else if (w[0] == "comment" || w[0] == "obj_info") {
                // Free text.
            } else if (w[0] == "format") {
                if (have_format) in_.fail_byte(pos, "duplicate format line");
                if (w.size() != 3) in_.fail_byte(pos, "malformed format line");
                if (w[1] == "ascii")
                    h_.format = Format::Ascii;
                else if (w[1] == "binary_little_endian")
                    h_.format = Format::BinaryLittle;
                else if (w[1] == "binary_big_endian")
                    h_.format = Format::BinaryBig;
                else
                    in_.fail_byte(pos, "unknown format " + quoted(w[1]));
                if (w[2] != "1.0" && w[2] != "1")
                    in_.fail_byte(pos, "unsupported PLY version " + quoted(w[2]) + " (expected 1.0)");
                have_format = true;
            } else if (w[0] == "element") {
                if (w.size() != 3) in_.fail_byte(pos, "malformed element line");
                Element el;
                el.name = std::string(w[1]);
                el.offset = pos;
                const char* b = w[2].data();
                const char* e = b + w[2].size();
                const auto r = std::from_chars(b, e, el.count);
                if (r.ec != std::errc() || r.ptr != e) in_.fail_byte(pos, "bad element count " + quoted(w[2]));
                for (const Element& other : h_.elements)
                    if (other.name == el.name) in_.fail_byte(pos, "duplicate element " + quoted(w[1]));
                h_.elements.push_back(std::move(el));
            } else if (w[0] == "property") {
                if (h_.elements.empty()) in_.fail_byte(pos, "property line before any element line");
                Property p;
                if (w.size() >= 2 && w[1] == "list") {
                    if (w.size() != 5) in_.fail_byte(pos, "malformed list property line");
                    if (!parse_type(w[2], p.count_type)) in_.fail_byte(pos, "unknown type " + quoted(w[2]));
                    if (!parse_type(w[3], p.type)) in_.fail_byte(pos, "unknown type " + quoted(w[3]));
                    if (!is_integer(p.count_type))
                        in_.fail_byte(pos, "list count type " + quoted(w[2]) + " is not an integer type");
                    p.is_list = true;
                    p.name = std::string(w[4]);
                } else {
                    if (w.size() != 3) in_.fail_byte(pos, "malformed property line");
                    if (!parse_type(w[1], p.type)) in_.fail_byte(pos, "unknown type " + quoted(w[1]));
                    p.name = std::string(w[2]);
                }
                h_.elements.back().props.push_back(std::move(p));
            } else {
                in_.fail_byte(
                    pos, "unknown header keyword " + quoted(w[0]) + " (not a PLY header line; missing end_header?)");
            }
            pos = next;
        }
    }

    // Finds the vertex coordinates and the face index list; checks their types.
    void assign_roles() {
        for (size_t i = 0; i < h_.elements.size(); ++i) {
            if (h_.elements[i].name == "vertex") h_.vertex_el = i;
            if (h_.elements[i].name == "face") h_.face_el = i;
        }
        if (h_.vertex_el == PlyHeader::kNone) in_.fail_byte(h_.header_end, "no 'vertex' element in the header");

        Element& ve = h_.elements[h_.vertex_el];
        bool seen[3] = {false, false, false};
        for (Property& p : ve.props) {
            int axis = -1;
            if (p.name == "x")
                axis = 0;
            else if (p.name == "y")
                axis = 1;
            else if (p.name == "z")
                axis = 2;
            if (axis < 0) continue;
            if (p.is_list) in_.fail_byte(ve.offset, "vertex property " + quoted(p.name) + " is a list");
            if (seen[axis]) in_.fail_byte(ve.offset, "duplicate vertex property " + quoted(p.name));
            seen[axis] = true;
            p.role = axis == 0 ? Role::X : axis == 1 ? Role::Y : Role::Z;
        }
        static const char* const axis_names[3] = {"x", "y", "z"};
        for (int a = 0; a < 3; ++a)
            if (!seen[a])
                in_.fail_byte(ve.offset, std::string("element 'vertex' has no property '") + axis_names[a] + "'");
        h_.vertex_count = ve.count;

        if (h_.face_el == PlyHeader::kNone) return;  // a point set: no triangles
        Element& fe = h_.elements[h_.face_el];
        Property* list = nullptr;
        for (Property& p : fe.props) {
            if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
            if (!p.is_list) in_.fail_byte(fe.offset, "face property " + quoted(p.name) + " is not a list");
            if (list) in_.fail_byte(fe.offset, "element 'face' has more than one vertex index list");
            if (!is_integer(p.type))
                in_.fail_byte(fe.offset, "face index type of " + quoted(p.name) + " is not an integer type");
            list = &p;
        }
        if (!list) in_.fail_byte(fe.offset, "element 'face' has no 'vertex_indices' (or 'vertex_index') list");
        list->role = Role::Indices;
    }

    // Rejects element counts the body cannot hold, before anything is allocated or
    // looped over. A record's smallest size: binary, the scalars plus the list counts
    // (a face index list needs at least 3 indices); ascii, one character and one
    // separator per number (the last separator may be missing at end of file).
    void check_sizes() const {
        const uint64_t body = in_.size - h_.body_offset;
        const uint64_t available = h_.format == Format::Ascii ? body + 1 : body;
        uint64_t needed = 0;
        for (const Element& el : h_.elements) {
            uint64_t rec = 0;
            for (const Property& p : el.props) {
                if (h_.format == Format::Ascii) {
                    rec += p.role == Role::Indices ? 2 * 4 : 2;
                } else if (p.is_list) {
                    rec += type_size(p.count_type);
                    if (p.role == Role::Indices) rec += 3 * type_size(p.type);
                } else {
                    rec += type_size(p.type);
                }
            }
            needed = add_sat(needed, mul_sat(el.count, rec));
            if (needed > available)
                in_.fail_byte(el.offset, "element '" + el.name + "' declares " + std::to_string(el.count) +
                                             " records, more than the file can hold (this and the elements"
                                             " before it need at least " +
                                             (needed == std::numeric_limits<uint64_t>::max() ? std::string("2^64")
                                                                                             : std::to_string(needed)) +
                                             " bytes, " + std::to_string(body) +
                                             " bytes follow the header; truncated file or bad count)");
        }
    }

private:
    const PlyInput& in_;
    PlyHeader& h_;
};

}  // namespace

PlyHeader read_header(const PlyInput& in) {
    PlyHeader h;
    HeaderParser parser(in, h);
    parser.parse_header();
    parser.assign_roles();
    parser.check_sizes();
    // Indices are 32-bit; vertices past that could not be addressed. (Only a file of
    // tens of GiB gets here.)
    const Element& ve = h.elements[h.vertex_el];
    if (ve.count > (uint64_t(1) << 32))
        in.fail_byte(ve.offset, "too many vertices (" + std::to_string(ve.count) + ") for 32-bit indices");
    return h;
}

}  // namespace rt::ply_reader
