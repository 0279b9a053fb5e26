// The ascii PLY body (read_ascii_body in ply_format.h). The body is a stream of
// whitespace-separated numbers, tokenised by hand and parsed with std::from_chars;
// records need not be one per line (line breaks only feed the line numbers in
// messages).
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <type_traits>

#include "ply_format.h"
#include "rt/core/parse_number.h"

namespace rt::ply_reader {
namespace {

class AsciiBody {
public:
    AsciiBody(const PlyInput& in, const PlyHeader& h) : in_(in), h_(h) {}

    struct AsciiCursor {
        const char* p;
        const char* end;
        size_t line;
    };

    // The next token; fails with "unexpected end of file" when there is none.
    std::string_view token(AsciiCursor& c, const Element& el, uint64_t rec) const {
        while (c.p < c.end && is_space(*c.p)) {
            if (*c.p == '\n') ++c.line;
            ++c.p;
        }
        if (c.p == c.end) in_.fail_line(c.line, "unexpected end of file in " + record_text(el, rec));
        const char* b = c.p;
        while (c.p < c.end && !is_space(*c.p)) ++c.p;
        return std::string_view(b, static_cast<size_t>(c.p - b));
    }

    // A whole token as a number: double for coordinates, int64_t for list counts and
    // indices (from_chars does not take a leading '+').
    template <typename T>
    T ascii_number(const AsciiCursor& c, std::string_view t, const Element& el, uint64_t rec) const {
        constexpr bool real = std::is_floating_point_v<T>;
        const char* b = t.data();
        const char* e = b + t.size();
        if (b != e && *b == '+') ++b;
        T v = 0;
        const auto r = parse_number(b, e, v);
        if (real && r.ec == std::errc::result_out_of_range && r.ptr == e)
            in_.fail_line(c.line, "number " + quoted(t) + " out of range in " + record_text(el, rec));
        if (r.ec != std::errc() || r.ptr != e)
            in_.fail_line(c.line, (real ? "bad number " : "bad integer ") + quoted(t) + " in " + record_text(el, rec));
        return v;
    }

    void read(PlyMesh& mesh, TriangleSink& tris) const {
        AsciiCursor c{reinterpret_cast<const char*>(in_.data + h_.body_offset),
                      reinterpret_cast<const char*>(in_.data + in_.size), h_.body_line};
        for (size_t e = 0; e < h_.elements.size(); ++e) {
            const Element& el = h_.elements[e];
            // An element without properties has empty records: nothing to read, and
            // its count (which check_sizes cannot bound) must not drive a loop.
            if (el.props.empty()) continue;
            const bool is_vertex = e == h_.vertex_el;
            if (is_vertex) mesh.positions.resize(static_cast<size_t>(el.count));
            for (uint64_t i = 0; i < el.count; ++i) {
                for (const Property& pr : el.props) {
                    if (!pr.is_list) {
                        const std::string_view t = token(c, el, i);
                        if (pr.role == Role::Skip) continue;
                        const double v = ascii_number<double>(c, t, el, i);
                        if (!std::isfinite(v))
                            in_.fail_line(c.line, "non-finite coordinate " + quoted(t) + " in " + record_text(el, i));
                        const int a = static_cast<int>(pr.role) - static_cast<int>(Role::X);
                        mesh.positions[static_cast<size_t>(i)][a] = static_cast<Real>(v);
                        continue;
                    }
                    const int64_t n = ascii_number<int64_t>(c, token(c, el, i), el, i);
                    if (n < 0)
                        in_.fail_line(c.line, "negative list count " + std::to_string(n) + " in " + record_text(el, i));
                    if (pr.role != Role::Indices) {
                        // Each token uses at least one byte, so this loop ends by EOF.
                        for (int64_t k = 0; k < n; ++k) token(c, el, i);
                        continue;
                    }
                    if (n < 3)
                        in_.fail_line(c.line, "face with " + std::to_string(n) + " vertices (at least 3 needed) in " +
                                                  record_text(el, i));
                    Fan fan;
                    for (int64_t k = 0; k < n; ++k) {
                        const int64_t v = ascii_number<int64_t>(c, token(c, el, i), el, i);
                        if (static_cast<uint64_t>(v) >= h_.vertex_count)
                            in_.fail_line(c.line, bad_index_text(v, h_.vertex_count) + " in " + record_text(el, i));
                        fan.add(k, static_cast<uint32_t>(v), tris);
                    }
                    if (n > 3) ++mesh.polygons_split;
                }
            }
        }
    }

private:
    const PlyInput& in_;
    const PlyHeader& h_;
};

}  // namespace

void read_ascii_body(const PlyInput& in, const PlyHeader& h, PlyMesh& mesh, TriangleSink& tris) {
    AsciiBody(in, h).read(mesh, tris);
}

}  // namespace rt::ply_reader
