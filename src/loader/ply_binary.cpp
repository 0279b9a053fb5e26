// The binary PLY body (read_binary_body in ply_format.h), decoded in one pass with
// memcpy loads (ply_byte_order.h), byte-swapped when the file's byte order differs
// from the host's. Fast paths for the usual layouts: fixed-size vertex records, and
// faces of "uchar 3 + three 32-bit indices"; every other layout goes through the
// general record walk, which also reports the errors.
#include <cmath>
#include <string>

#include "ply_byte_order.h"
#include "ply_format.h"

namespace rt::ply_reader {
namespace {

class BinaryBody {
public:
    BinaryBody(const PlyInput& in, const PlyHeader& h)
        : in_(in), h_(h), data_(in.data), size_(in.size), vertex_count_(h.vertex_count) {}

    // The count of the list property `pr` whose record starts at p (el's record rec):
    // checked to fit before the end of the file and not to be negative.
    template <bool Swap>
    int64_t list_count(const Property& pr, const Element& el, uint64_t rec, const unsigned char* p) const {
        if (static_cast<size_t>(data_ + size_ - p) < type_size(pr.count_type)) in_.fail_eof(p - data_, el, rec);
        const int64_t n = load_int<Swap>(p, pr.count_type);
        if (n < 0) in_.fail_byte(p - data_, "negative list count " + std::to_string(n) + " in " + record_text(el, rec));
        return n;
    }

    // The end of the list property `pr` whose count, n (from list_count), is at p.
    // Fails if the file ends before it.
    const unsigned char* list_end(const Property& pr, const Element& el, uint64_t rec, const unsigned char* p,
                                  int64_t n) const {
        p += type_size(pr.count_type);
        const uint64_t bytes = static_cast<uint64_t>(n) * type_size(pr.type);  // n < 2^32, no overflow
        if (static_cast<uint64_t>(data_ + size_ - p) < bytes) in_.fail_eof(p - data_, el, rec);
        return p + bytes;
    }

    // Steps over one property (a scalar or a whole list) at p; returns the end of
    // it. Fails if the file ends first. Every record walk below steps with this.
    template <bool Swap>
    const unsigned char* skip_property(const Property& pr, const Element& el, uint64_t rec,
                                       const unsigned char* p) const {
        if (!pr.is_list) {
            const size_t sz = type_size(pr.type);
            if (static_cast<size_t>(data_ + size_ - p) < sz) in_.fail_eof(p - data_, el, rec);
            return p + sz;
        }
        return list_end(pr, el, rec, p, list_count<Swap>(pr, el, rec, p));
    }

    template <bool Swap>
    void read(PlyMesh& mesh, TriangleSink& tris) {
        size_t pos = h_.body_offset;
        for (size_t e = 0; e < h_.elements.size(); ++e) {
            if (e == h_.vertex_el)
                pos = binary_vertices<Swap>(h_.elements[e], pos, mesh);
            else if (e == h_.face_el)
                pos = binary_faces<Swap>(h_.elements[e], pos, mesh, tris);
            else
                pos = binary_skip<Swap>(h_.elements[e], pos);
        }
    }

    [[noreturn]] RT_PLY_COLD void fail_nonfinite(size_t offset, const Element& el, uint64_t rec) const {
        in_.fail_byte(offset, "non-finite coordinate (NaN or infinity) in " + record_text(el, rec));
    }

    // Fixed-size vertex records with x, y, z of type T (the common float case).
    template <bool Swap, typename T>
    void vertices_same_type(const Element& el, size_t pos, size_t stride, const size_t off[3], Vec3* out) const {
        const unsigned char* p = data_ + pos;
        for (uint64_t i = 0; i < el.count; ++i, p += stride, ++out) {
            const double x = static_cast<double>(load<T, Swap>(p + off[0]));
            const double y = static_cast<double>(load<T, Swap>(p + off[1]));
            const double z = static_cast<double>(load<T, Swap>(p + off[2]));
            if (!(std::isfinite(x) && std::isfinite(y) && std::isfinite(z))) {
                const int bad = !std::isfinite(x) ? 0 : !std::isfinite(y) ? 1 : 2;
                fail_nonfinite(static_cast<size_t>(p - data_) + off[bad], el, i);
            }
            *out = {static_cast<Real>(x), static_cast<Real>(y), static_cast<Real>(z)};
        }
    }

    template <bool Swap>
    size_t binary_vertices(const Element& el, size_t pos, PlyMesh& mesh) const {
        mesh.positions.resize(static_cast<size_t>(el.count));
        Vec3* out = mesh.positions.data();

        if (!el.has_lists()) {
            // Fixed-size records: one bounds check, then a tight loop.
            const size_t stride = el.fixed_size();
            const uint64_t need = el.count * stride;  // bounded by check_sizes
            if (need > size_ - pos) in_.fail_eof(pos + ((size_ - pos) / stride) * stride, el, (size_ - pos) / stride);
            size_t off[3] = {0, 0, 0};
            Type types[3] = {Type::F32, Type::F32, Type::F32};
            size_t o = 0;
            for (const Property& p : el.props) {
                if (p.role == Role::X || p.role == Role::Y || p.role == Role::Z) {
                    const int a = static_cast<int>(p.role) - static_cast<int>(Role::X);
                    off[a] = o;
                    types[a] = p.type;
                }
                o += type_size(p.type);
            }
            if (types[0] == types[1] && types[1] == types[2] && types[0] == Type::F32) {
                vertices_same_type<Swap, float>(el, pos, stride, off, out);
            } else if (types[0] == types[1] && types[1] == types[2] && types[0] == Type::F64) {
                vertices_same_type<Swap, double>(el, pos, stride, off, out);
            } else {
                const unsigned char* p = data_ + pos;
                for (uint64_t i = 0; i < el.count; ++i, p += stride, ++out) {
                    for (int a = 0; a < 3; ++a) {
                        const double v = load_real<Swap>(p + off[a], types[a]);
                        if (!std::isfinite(v)) fail_nonfinite(static_cast<size_t>(p - data_) + off[a], el, i);
                        (*out)[a] = static_cast<Real>(v);
                    }
                }
            }
            return pos + static_cast<size_t>(need);
        }

        // General layout (lists inside vertex records): walk each record.
        const unsigned char* p = data_ + pos;
        for (uint64_t i = 0; i < el.count; ++i, ++out) {
            for (const Property& pr : el.props) {
                const unsigned char* const next = skip_property<Swap>(pr, el, i, p);
                if (pr.role != Role::Skip) {  // x, y or z: a scalar (read_header checked)
                    const int a = static_cast<int>(pr.role) - static_cast<int>(Role::X);
                    const double v = load_real<Swap>(p, pr.type);
                    if (!std::isfinite(v)) fail_nonfinite(p - data_, el, i);
                    (*out)[a] = static_cast<Real>(v);
                }
                p = next;
            }
        }
        return static_cast<size_t>(p - data_);
    }

    // One face record in any layout, starting at p; returns the end of the record.
    // Polygons are fan-split straight into the output.
    template <bool Swap>
    const unsigned char* binary_face_record(const Element& el, uint64_t rec, const unsigned char* p, PlyMesh& mesh,
                                            TriangleSink& tris) const {
        for (const Property& pr : el.props) {
            if (pr.role != Role::Indices) {
                p = skip_property<Swap>(pr, el, rec, p);
                continue;
            }
            const int64_t n = list_count<Swap>(pr, el, rec, p);
            if (n < 3)
                in_.fail_byte(p - data_, "face with " + std::to_string(n) + " vertices (at least 3 needed) in " +
                                             record_text(el, rec));
            const unsigned char* item = p + type_size(pr.count_type);
            p = list_end(pr, el, rec, p, n);  // fails unless all n indices are in the file
            const size_t isz = type_size(pr.type);
            Fan fan;
            for (int64_t k = 0; k < n; ++k, item += isz) {
                const int64_t v = load_int<Swap>(item, pr.type);
                if (static_cast<uint64_t>(v) >= vertex_count_)  // negative -> huge
                    in_.fail_byte(item - data_, bad_index_text(v, vertex_count_) + " in " + record_text(el, rec));
                fan.add(k, static_cast<uint32_t>(v), tris);
            }
            if (n > 3) ++mesh.polygons_split;
        }
        return p;
    }

    // The common face layout: the index list is the only property, with a 1-byte
    // count and 32-bit indices. Triangles take the fast path; anything else in the
    // same file (quads, errors) goes through binary_face_record.
    template <bool Swap, typename Index>
    size_t faces_u8_count(const Element& el, size_t pos, PlyMesh& mesh, TriangleSink& tris) const {
        const unsigned char* p = data_ + pos;
        const unsigned char* const end = data_ + size_;
        constexpr size_t kTri = 1 + 3 * sizeof(Index);
        const uint64_t nv = vertex_count_;
        uint32_t* out = tris.cursor();
        uint32_t* out_end = tris.limit();
        for (uint64_t f = 0; f < el.count; ++f) {
            if (static_cast<size_t>(end - p) >= kTri && p[0] == 3 && out_end - out >= 3) {
                const int64_t a = load<Index, Swap>(p + 1);
                const int64_t b = load<Index, Swap>(p + 1 + sizeof(Index));
                const int64_t c = load<Index, Swap>(p + 1 + 2 * sizeof(Index));
                if (static_cast<uint64_t>(a) < nv && static_cast<uint64_t>(b) < nv && static_cast<uint64_t>(c) < nv) {
                    out[0] = static_cast<uint32_t>(a);
                    out[1] = static_cast<uint32_t>(b);
                    out[2] = static_cast<uint32_t>(c);
                    out += 3;
                    p += kTri;
                    continue;
                }
            }
            // Anything else (polygons, full output, errors) takes the general path.
            tris.set_cursor(out);
            p = binary_face_record<Swap>(el, f, p, mesh, tris);
            out = tris.cursor();
            out_end = tris.limit();
        }
        tris.set_cursor(out);
        return static_cast<size_t>(p - data_);
    }

    template <bool Swap>
    size_t binary_faces(const Element& el, size_t pos, PlyMesh& mesh, TriangleSink& tris) const {
        if (el.props.size() == 1 && el.props[0].count_type == Type::U8) {
            if (el.props[0].type == Type::I32) return faces_u8_count<Swap, int32_t>(el, pos, mesh, tris);
            if (el.props[0].type == Type::U32) return faces_u8_count<Swap, uint32_t>(el, pos, mesh, tris);
        }
        const unsigned char* p = data_ + pos;
        for (uint64_t f = 0; f < el.count; ++f) p = binary_face_record<Swap>(el, f, p, mesh, tris);
        return static_cast<size_t>(p - data_);
    }

    // Skips an element we do not use; list counts are read to find record ends.
    template <bool Swap>
    size_t binary_skip(const Element& el, size_t pos) const {
        if (!el.has_lists()) {
            const uint64_t need = el.count * el.fixed_size();  // bounded by check_sizes
            if (need > size_ - pos) in_.fail_eof(size_, el, (size_ - pos) / el.fixed_size());
            return pos + static_cast<size_t>(need);
        }
        const unsigned char* p = data_ + pos;
        for (uint64_t i = 0; i < el.count; ++i)
            for (const Property& pr : el.props) p = skip_property<Swap>(pr, el, i, p);
        return static_cast<size_t>(p - data_);
    }

private:
    const PlyInput& in_;
    const PlyHeader& h_;
    const unsigned char* data_;
    size_t size_;
    uint64_t vertex_count_;
};

}  // namespace

void read_binary_body(const PlyInput& in, const PlyHeader& h, PlyMesh& mesh, TriangleSink& tris) {
    BinaryBody body(in, h);
    const bool file_little = h.format == Format::BinaryLittle;
    if (file_little == kHostLittleEndian)
        body.read<false>(mesh, tris);
    else
        body.read<true>(mesh, tris);
}

}  // namespace rt::ply_reader
