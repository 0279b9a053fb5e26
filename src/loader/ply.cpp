// Our own PLY reader; the contract is in rt/loader/ply.h.
//
// Strategy:
//   1. The whole file is in memory: regular files of 1 MiB or more are mapped
//      read-only, smaller ones and pipes are read into one buffer (FileBytes).
//   2. The header is parsed into elements and properties; the vertex x/y/z and the
//      face index list are located by name, everything else is marked "skip".
//   3. Before anything is allocated, every element count is checked against the
//      bytes that follow the header (count * smallest possible record), so a hostile
//      header cannot make us allocate or loop beyond what the file can hold.
//   4. The body is decoded in one pass. Binary bodies use memcpy loads (byte-swapped
//      when the file's endianness differs from the host's) with fast paths for the
//      usual layouts (fixed-size vertex records; "uchar 3 + three 32-bit indices"
//      faces). ASCII bodies are tokenised by hand and parsed with std::from_chars.
//
// Every error is an rt::InputError with one line "<path>: byte <offset>: <what>"
// (header and binary body; the offset is absolute in the file, for the header the
// start of the offending line) or "<path>: line <n>: <what>" (ascii body; lines
// are counted from the top of the file, header included).
#include "rt/loader/ply.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>
#include <memory>
#include <string_view>
#include <type_traits>

#include "rt/core/error.h"

#if defined(__GNUC__)
#define RT_PLY_COLD __attribute__((cold, noinline))
#else
#define RT_PLY_COLD
#endif

namespace rt {
namespace {

#if defined(__BYTE_ORDER__) && defined(__ORDER_BIG_ENDIAN__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
constexpr bool kHostLittleEndian = false;
#else
constexpr bool kHostLittleEndian = true;
#endif

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

// Both spellings of every PLY 1.0 scalar type.
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

// ---------------------------------------------------------------------------------
// Small helpers

std::string errno_text(int e) {
#if defined(__GLIBC__) && defined(_GNU_SOURCE)
    char buf[256];
    return strerror_r(e, buf, sizeof buf);  // GNU variant: returns the message
#else
    return std::strerror(e);
#endif
}

// A token from the file, quoted for a one-line message: at most 40 characters,
// anything unprintable shown as '?'.
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

constexpr bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f'; }

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

// Loads a T stored at p (any alignment), byte-swapping when Swap.
template <typename T, bool Swap>
inline T load(const unsigned char* p) {
    T v;
    if constexpr (!Swap || sizeof(T) == 1) {
        std::memcpy(&v, p, sizeof v);
    } else if constexpr (sizeof(T) == 2) {
        uint16_t u;
        std::memcpy(&u, p, 2);
        u = __builtin_bswap16(u);
        std::memcpy(&v, &u, 2);
    } else if constexpr (sizeof(T) == 4) {
        uint32_t u;
        std::memcpy(&u, p, 4);
        u = __builtin_bswap32(u);
        std::memcpy(&v, &u, 4);
    } else {
        static_assert(sizeof(T) == 8, "unsupported size");
        uint64_t u;
        std::memcpy(&u, p, 8);
        u = __builtin_bswap64(u);
        std::memcpy(&v, &u, 8);
    }
    return v;
}

// The value of type t at p as R: double for coordinates (any type), int64_t for list
// counts and indices (integer types only, checked when the header is read).
template <class R, bool Swap>
inline R load_as(const unsigned char* p, Type t) {
    switch (t) {
        case Type::I8:
            return load<int8_t, Swap>(p);
        case Type::U8:
            return load<uint8_t, Swap>(p);
        case Type::I16:
            return load<int16_t, Swap>(p);
        case Type::U16:
            return load<uint16_t, Swap>(p);
        case Type::I32:
            return load<int32_t, Swap>(p);
        case Type::U32:
            return load<uint32_t, Swap>(p);
        case Type::F32:
            if constexpr (std::is_floating_point_v<R>) return load<float, Swap>(p);
            break;
        case Type::F64:
            if constexpr (std::is_floating_point_v<R>) return load<double, Swap>(p);
            break;
    }
    return R(0);
}

template <bool Swap>
inline double load_real(const unsigned char* p, Type t) {
    return load_as<double, Swap>(p, t);
}

template <bool Swap>
inline int64_t load_int(const unsigned char* p, Type t) {
    return load_as<int64_t, Swap>(p, t);
}

// ---------------------------------------------------------------------------------
// The whole file in memory: a read-only mapping for regular files of some size
// (no copy; MAP_POPULATE maps the cached pages up front), else one heap buffer
// filled by read(). Caveat of the mapping: if another process truncates the file
// while we parse it, the access past the new end raises SIGBUS; scene inputs are
// not rewritten while being rendered, and mapping saves copying every byte.

class FileBytes {
public:
    FileBytes() = default;
    FileBytes(const FileBytes&) = delete;
    FileBytes& operator=(const FileBytes&) = delete;
    ~FileBytes() {
        if (map_) ::munmap(map_, size_);
    }
    const unsigned char* data() const { return map_ ? static_cast<const unsigned char*>(map_) : heap_.get(); }
    size_t size() const { return size_; }

    static constexpr size_t kMapThreshold = size_t(1) << 20;
    static constexpr size_t kMaxStreamBytes = size_t(1) << 32;

    void load(const std::string& path) {
        const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0) throw InputError(path + ": cannot open: " + errno_text(errno));
        struct Closer {
            int fd;
            ~Closer() { ::close(fd); }
        } closer{fd};

        struct stat st;
        if (::fstat(fd, &st) != 0) throw InputError(path + ": cannot open: " + errno_text(errno));
        if (S_ISDIR(st.st_mode)) throw InputError(path + ": cannot open: " + errno_text(EISDIR));
        // Devices are refused (/dev/zero would be read until memory runs out); pipes
        // are read, up to kMaxStreamBytes.
        if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) throw InputError(path + ": cannot open: not a regular file");

        if (S_ISREG(st.st_mode) && static_cast<uint64_t>(st.st_size) >= kMapThreshold) {
            void* m = ::mmap(nullptr, static_cast<size_t>(st.st_size), PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
            if (m != MAP_FAILED) {
                ::madvise(m, static_cast<size_t>(st.st_size), MADV_SEQUENTIAL);
                map_ = m;
                size_ = static_cast<size_t>(st.st_size);
                return;
            }
            // Fall through to read() (e.g. a file system without mmap support).
        }

        // Regular files: one read of the known size (+1 so that EOF is seen without
        // growing). Pipes and the like: grow as needed. Not zero-initialised.
        size_t cap = S_ISREG(st.st_mode) ? static_cast<size_t>(st.st_size) + 1 : size_t(1) << 16;
        heap_.reset(new unsigned char[cap]);
        for (;;) {
            if (size_ == cap) {
                if (cap >= kMaxStreamBytes)
                    throw InputError(path + ": cannot read: more than " + std::to_string(kMaxStreamBytes >> 20) +
                                     " MiB from a pipe");
                const size_t new_cap = cap * 2;
                std::unique_ptr<unsigned char[]> bigger(new unsigned char[new_cap]);
                std::memcpy(bigger.get(), heap_.get(), size_);
                heap_ = std::move(bigger);
                cap = new_cap;
            }
            const ssize_t got = ::read(fd, heap_.get() + size_, cap - size_);
            if (got < 0) {
                if (errno == EINTR) continue;
                throw InputError(path + ": cannot read: " + errno_text(errno));
            }
            if (got == 0) break;
            size_ += static_cast<size_t>(got);
        }
    }

private:
    void* map_ = nullptr;
    std::unique_ptr<unsigned char[]> heap_;
    size_t size_ = 0;
};

// ---------------------------------------------------------------------------------
// Triangle output. The index vector is sized up front for the expected triangles
// (resize, not reserve, so the hot loops store through a plain pointer); polygons
// that need more room grow it; finish() trims it to what was written.

class TriangleSink {
public:
    TriangleSink(std::vector<uint32_t>& v, size_t expected_indices) : v_(v) {
        v_.resize(expected_indices);
        cur_ = v_.data();
        end_ = cur_ + v_.size();
    }
    uint32_t* cursor() const { return cur_; }
    uint32_t* limit() const { return end_; }
    void set_cursor(uint32_t* c) { cur_ = c; }

    void put(uint32_t a, uint32_t b, uint32_t c) {
        if (end_ - cur_ < 3) grow();
        cur_[0] = a;
        cur_[1] = b;
        cur_[2] = c;
        cur_ += 3;
    }
    void finish() { v_.resize(static_cast<size_t>(cur_ - v_.data())); }

private:
    RT_PLY_COLD void grow() {
        const size_t used = static_cast<size_t>(cur_ - v_.data());
        v_.resize(v_.size() + v_.size() / 2 + 3);
        cur_ = v_.data() + used;
        end_ = v_.data() + v_.size();
    }

    std::vector<uint32_t>& v_;
    uint32_t* cur_;
    uint32_t* end_;
};

// Fan-splits one polygon as its vertex indices arrive: vertex k >= 2 makes the
// triangle (first, previous, k).
struct Fan {
    uint32_t first = 0, prev = 0;
    void add(int64_t k, uint32_t u, TriangleSink& tris) {
        if (k == 0) {
            first = u;
        } else if (k >= 2) {
            tris.put(first, prev, u);
        }
        prev = u;
    }
};

// ---------------------------------------------------------------------------------
// The parser. One instance per file; parse() is called once.

class PlyParser {
public:
    PlyParser(const std::string& path, const unsigned char* data, size_t size)
        : path_(path), data_(data), size_(size) {}

    PlyMesh parse() {
        parse_header();
        assign_roles();
        check_sizes();
        // Indices are 32-bit; vertices past that could not be addressed. (Only a file of
        // tens of GiB gets here.)
        const Element& ve = elements_[vertex_el_];
        if (ve.count > (uint64_t(1) << 32))
            fail_byte(ve.offset, "too many vertices (" + std::to_string(ve.count) + ") for 32-bit indices");

        PlyMesh mesh;
        // Sizes are bounded by the file size now (check_sizes), so these are safe.
        TriangleSink tris(mesh.indices, face_el_ == kNone ? 0 : 3 * static_cast<size_t>(elements_[face_el_].count));

        switch (format_) {
            case Format::Ascii:
                read_ascii(mesh, tris);
                break;
            case Format::BinaryLittle:
                if (kHostLittleEndian)
                    read_binary<false>(mesh, tris);
                else
                    read_binary<true>(mesh, tris);
                break;
            case Format::BinaryBig:
                if (kHostLittleEndian)
                    read_binary<true>(mesh, tris);
                else
                    read_binary<false>(mesh, tris);
                break;
        }
        tris.finish();
        return mesh;  // anything after the last element is ignored
    }

private:
    static constexpr size_t kNone = static_cast<size_t>(-1);

    const std::string& path_;
    const unsigned char* data_;
    size_t size_;

    Format format_ = Format::Ascii;
    std::vector<Element> elements_;
    size_t body_offset_ = 0;  // first byte after the end_header line
    size_t body_line_ = 0;    // 1-based line number of that byte (ascii)
    size_t header_end_ = 0;   // offset of the end_header line, for messages
    size_t vertex_el_ = kNone;
    size_t face_el_ = kNone;
    uint64_t vertex_count_ = 0;

    // -- errors --------------------------------------------------------------------

    [[noreturn]] RT_PLY_COLD void fail_byte(size_t offset, const std::string& what) const {
        throw InputError(path_ + ": byte " + std::to_string(offset) + ": " + what);
    }
    [[noreturn]] RT_PLY_COLD void fail_line(size_t line, const std::string& what) const {
        throw InputError(path_ + ": line " + std::to_string(line) + ": " + what);
    }
    static std::string record_text(const Element& el, uint64_t rec) {
        return "element '" + el.name + "' record " + std::to_string(rec) + " of " + std::to_string(el.count);
    }
    [[noreturn]] RT_PLY_COLD void fail_eof(size_t offset, const Element& el, uint64_t rec) const {
        fail_byte(offset, "unexpected end of file in " + record_text(el, rec));
    }
    static std::string bad_index_text(int64_t v, uint64_t nv) {
        return "vertex index " + std::to_string(v) + " out of range (vertex count " + std::to_string(nv) + ")";
    }

    // -- header --------------------------------------------------------------------

    void parse_header() {
        std::vector<std::string_view> w;
        size_t pos = 0;
        size_t line_no = 0;
        bool have_format = false;
        for (;;) {
            if (pos >= size_) {
                if (line_no == 0) fail_byte(0, "not a PLY file (empty file)");
                fail_byte(pos, "missing end_header (end of file inside the header)");
            }
            const void* nl = std::memchr(data_ + pos, '\n', size_ - pos);
            const size_t line_end = nl ? static_cast<size_t>(static_cast<const unsigned char*>(nl) - data_) : size_;
            const size_t next = nl ? line_end + 1 : size_;
            ++line_no;
            const std::string_view line(reinterpret_cast<const char*>(data_ + pos), line_end - pos);
            split_words(line, w);

            if (line_no == 1) {
                if (w.size() != 1 || w[0] != "ply") fail_byte(0, "not a PLY file (the first line is not 'ply')");
            } else if (w.empty()) {
                // Blank lines are tolerated.
            } else if (w[0] == "end_header") {
                if (w.size() != 1) fail_byte(pos, "malformed end_header line");
                if (!have_format) fail_byte(pos, "missing format line");
                header_end_ = pos;
                body_offset_ = next;
                body_line_ = line_no + 1;
                return;
            } else if (!nl) {
                // The header's last line is not end_header: it is truncated or absent.
                fail_byte(pos, "missing end_header (end of file inside the header)");
            } else if (w[0] == "comment" || w[0] == "obj_info") {
                // Free text.
            } else if (w[0] == "format") {
                if (have_format) fail_byte(pos, "duplicate format line");
                if (w.size() != 3) fail_byte(pos, "malformed format line");
                if (w[1] == "ascii")
                    format_ = Format::Ascii;
                else if (w[1] == "binary_little_endian")
                    format_ = Format::BinaryLittle;
                else if (w[1] == "binary_big_endian")
                    format_ = Format::BinaryBig;
                else
                    fail_byte(pos, "unknown format " + quoted(w[1]));
                if (w[2] != "1.0" && w[2] != "1")
                    fail_byte(pos, "unsupported PLY version " + quoted(w[2]) + " (expected 1.0)");
                have_format = true;
            } else if (w[0] == "element") {
                if (w.size() != 3) fail_byte(pos, "malformed element line");
                Element el;
                el.name = std::string(w[1]);
                el.offset = pos;
                const char* b = w[2].data();
                const char* e = b + w[2].size();
                const auto r = std::from_chars(b, e, el.count);
                if (r.ec != std::errc() || r.ptr != e) fail_byte(pos, "bad element count " + quoted(w[2]));
                for (const Element& other : elements_)
                    if (other.name == el.name) fail_byte(pos, "duplicate element " + quoted(w[1]));
                elements_.push_back(std::move(el));
            } else if (w[0] == "property") {
                if (elements_.empty()) fail_byte(pos, "property line before any element line");
                Property p;
                if (w.size() >= 2 && w[1] == "list") {
                    if (w.size() != 5) fail_byte(pos, "malformed list property line");
                    if (!parse_type(w[2], p.count_type)) fail_byte(pos, "unknown type " + quoted(w[2]));
                    if (!parse_type(w[3], p.type)) fail_byte(pos, "unknown type " + quoted(w[3]));
                    if (!is_integer(p.count_type))
                        fail_byte(pos, "list count type " + quoted(w[2]) + " is not an integer type");
                    p.is_list = true;
                    p.name = std::string(w[4]);
                } else {
                    if (w.size() != 3) fail_byte(pos, "malformed property line");
                    if (!parse_type(w[1], p.type)) fail_byte(pos, "unknown type " + quoted(w[1]));
                    p.name = std::string(w[2]);
                }
                elements_.back().props.push_back(std::move(p));
            } else {
                fail_byte(pos,
                          "unknown header keyword " + quoted(w[0]) + " (not a PLY header line; missing end_header?)");
            }
            pos = next;
        }
    }

    // Finds the vertex coordinates and the face index list; checks their types.
    void assign_roles() {
        for (size_t i = 0; i < elements_.size(); ++i) {
            if (elements_[i].name == "vertex") vertex_el_ = i;
            if (elements_[i].name == "face") face_el_ = i;
        }
        if (vertex_el_ == kNone) fail_byte(header_end_, "no 'vertex' element in the header");

        Element& ve = elements_[vertex_el_];
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
            if (p.is_list) fail_byte(ve.offset, "vertex property " + quoted(p.name) + " is a list");
            if (seen[axis]) fail_byte(ve.offset, "duplicate vertex property " + quoted(p.name));
            seen[axis] = true;
            p.role = axis == 0 ? Role::X : axis == 1 ? Role::Y : Role::Z;
        }
        static const char* const axis_names[3] = {"x", "y", "z"};
        for (int a = 0; a < 3; ++a)
            if (!seen[a]) fail_byte(ve.offset, std::string("element 'vertex' has no property '") + axis_names[a] + "'");
        vertex_count_ = ve.count;

        if (face_el_ == kNone) return;  // a point set: no triangles
        Element& fe = elements_[face_el_];
        Property* list = nullptr;
        for (Property& p : fe.props) {
            if (p.name != "vertex_indices" && p.name != "vertex_index") continue;
            if (!p.is_list) fail_byte(fe.offset, "face property " + quoted(p.name) + " is not a list");
            if (list) fail_byte(fe.offset, "element 'face' has more than one vertex index list");
            if (!is_integer(p.type))
                fail_byte(fe.offset, "face index type of " + quoted(p.name) + " is not an integer type");
            list = &p;
        }
        if (!list) fail_byte(fe.offset, "element 'face' has no 'vertex_indices' (or 'vertex_index') list");
        list->role = Role::Indices;
    }

    // Rejects element counts the body cannot hold, before anything is allocated or
    // looped over. A record's smallest size: binary, the scalars plus the list counts
    // (a face index list needs at least 3 indices); ascii, one character and one
    // separator per number (the last separator may be missing at end of file).
    void check_sizes() const {
        const uint64_t body = size_ - body_offset_;
        const uint64_t available = format_ == Format::Ascii ? body + 1 : body;
        uint64_t needed = 0;
        for (const Element& el : elements_) {
            uint64_t rec = 0;
            for (const Property& p : el.props) {
                if (format_ == Format::Ascii) {
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
                fail_byte(el.offset, "element '" + el.name + "' declares " + std::to_string(el.count) +
                                         " records, more than the file can hold (this and the elements"
                                         " before it need at least " +
                                         (needed == std::numeric_limits<uint64_t>::max() ? std::string("2^64")
                                                                                         : std::to_string(needed)) +
                                         " bytes, " + std::to_string(body) +
                                         " bytes follow the header; truncated file or bad count)");
        }
    }

    // -- binary body ---------------------------------------------------------------

    // The count of the list property `pr` whose record starts at p (el's record rec):
    // checked to fit before the end of the file and not to be negative.
    template <bool Swap>
    int64_t list_count(const Property& pr, const Element& el, uint64_t rec, const unsigned char* p) const {
        if (static_cast<size_t>(data_ + size_ - p) < type_size(pr.count_type)) fail_eof(p - data_, el, rec);
        const int64_t n = load_int<Swap>(p, pr.count_type);
        if (n < 0) fail_byte(p - data_, "negative list count " + std::to_string(n) + " in " + record_text(el, rec));
        return n;
    }

    // Steps over one property we do not use (a scalar or a whole list) at p; returns
    // the end of it. Fails if the file ends first.
    template <bool Swap>
    const unsigned char* skip_property(const Property& pr, const Element& el, uint64_t rec,
                                       const unsigned char* p) const {
        const unsigned char* const end = data_ + size_;
        if (!pr.is_list) {
            const size_t sz = type_size(pr.type);
            if (static_cast<size_t>(end - p) < sz) fail_eof(p - data_, el, rec);
            return p + sz;
        }
        const int64_t n = list_count<Swap>(pr, el, rec, p);
        p += type_size(pr.count_type);
        const uint64_t bytes = static_cast<uint64_t>(n) * type_size(pr.type);  // n < 2^32, no overflow
        if (static_cast<uint64_t>(end - p) < bytes) fail_eof(p - data_, el, rec);
        return p + bytes;
    }

    template <bool Swap>
    void read_binary(PlyMesh& mesh, TriangleSink& tris) {
        size_t pos = body_offset_;
        for (size_t e = 0; e < elements_.size(); ++e) {
            if (e == vertex_el_)
                pos = binary_vertices<Swap>(elements_[e], pos, mesh);
            else if (e == face_el_)
                pos = binary_faces<Swap>(elements_[e], pos, mesh, tris);
            else
                pos = binary_skip<Swap>(elements_[e], pos);
        }
    }

    [[noreturn]] RT_PLY_COLD void fail_nonfinite(size_t offset, const Element& el, uint64_t rec) const {
        fail_byte(offset, "non-finite coordinate (NaN or infinity) in " + record_text(el, rec));
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
            if (need > size_ - pos) fail_eof(pos + ((size_ - pos) / stride) * stride, el, (size_ - pos) / stride);
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
        const unsigned char* const end = data_ + size_;
        for (uint64_t i = 0; i < el.count; ++i, ++out) {
            for (const Property& pr : el.props) {
                if (pr.is_list) {
                    p = skip_property<Swap>(pr, el, i, p);
                    continue;
                }
                const size_t sz = type_size(pr.type);
                if (static_cast<size_t>(end - p) < sz) fail_eof(p - data_, el, i);
                if (pr.role != Role::Skip) {
                    const int a = static_cast<int>(pr.role) - static_cast<int>(Role::X);
                    const double v = load_real<Swap>(p, pr.type);
                    if (!std::isfinite(v)) fail_nonfinite(p - data_, el, i);
                    (*out)[a] = static_cast<Real>(v);
                }
                p += sz;
            }
        }
        return static_cast<size_t>(p - data_);
    }

    // One face record in any layout, starting at p; returns the end of the record.
    // Polygons are fan-split straight into the output.
    template <bool Swap>
    const unsigned char* binary_face_record(const Element& el, uint64_t rec, const unsigned char* p, PlyMesh& mesh,
                                            TriangleSink& tris) const {
        const unsigned char* const end = data_ + size_;
        for (const Property& pr : el.props) {
            if (pr.role != Role::Indices) {
                p = skip_property<Swap>(pr, el, rec, p);
                continue;
            }
            const int64_t n = list_count<Swap>(pr, el, rec, p);
            if (n < 3)
                fail_byte(p - data_, "face with " + std::to_string(n) + " vertices (at least 3 needed) in " +
                                         record_text(el, rec));
            p += type_size(pr.count_type);
            const size_t isz = type_size(pr.type);
            const uint64_t bytes = static_cast<uint64_t>(n) * isz;  // n < 2^32, no overflow
            if (static_cast<uint64_t>(end - p) < bytes) fail_eof(p - data_, el, rec);
            Fan fan;
            for (int64_t k = 0; k < n; ++k, p += isz) {
                const int64_t v = load_int<Swap>(p, pr.type);
                if (static_cast<uint64_t>(v) >= vertex_count_)  // negative -> huge
                    fail_byte(p - data_, bad_index_text(v, vertex_count_) + " in " + record_text(el, rec));
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
            if (need > size_ - pos) fail_eof(size_, el, (size_ - pos) / el.fixed_size());
            return pos + static_cast<size_t>(need);
        }
        const unsigned char* p = data_ + pos;
        for (uint64_t i = 0; i < el.count; ++i)
            for (const Property& pr : el.props) p = skip_property<Swap>(pr, el, i, p);
        return static_cast<size_t>(p - data_);
    }

    // -- ascii body ----------------------------------------------------------------
    // The body is a stream of whitespace-separated numbers; records need not be one
    // per line (line breaks only feed the line numbers in messages).

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
        if (c.p == c.end) fail_line(c.line, "unexpected end of file in " + record_text(el, rec));
        const char* b = c.p;
        while (c.p < c.end && !is_space(*c.p)) ++c.p;
        return std::string_view(b, static_cast<size_t>(c.p - b));
    }

    // A whole token as a real number (from_chars does not take a leading '+').
    double ascii_real(const AsciiCursor& c, std::string_view t, const Element& el, uint64_t rec) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b != e && *b == '+') ++b;
        double v = 0;
        const auto r = std::from_chars(b, e, v);
        if (r.ec == std::errc::result_out_of_range && r.ptr == e)
            fail_line(c.line, "number " + quoted(t) + " out of range in " + record_text(el, rec));
        if (r.ec != std::errc() || r.ptr != e)
            fail_line(c.line, "bad number " + quoted(t) + " in " + record_text(el, rec));
        return v;
    }

    // A whole token as an integer (list counts and indices).
    int64_t ascii_int(const AsciiCursor& c, std::string_view t, const Element& el, uint64_t rec) const {
        const char* b = t.data();
        const char* e = b + t.size();
        if (b != e && *b == '+') ++b;
        int64_t v = 0;
        const auto r = std::from_chars(b, e, v);
        if (r.ec != std::errc() || r.ptr != e)
            fail_line(c.line, "bad integer " + quoted(t) + " in " + record_text(el, rec));
        return v;
    }

    void read_ascii(PlyMesh& mesh, TriangleSink& tris) {
        AsciiCursor c{reinterpret_cast<const char*>(data_ + body_offset_), reinterpret_cast<const char*>(data_ + size_),
                      body_line_};
        for (size_t e = 0; e < elements_.size(); ++e) {
            const Element& el = elements_[e];
            // An element without properties has empty records: nothing to read, and
            // its count (which check_sizes cannot bound) must not drive a loop.
            if (el.props.empty()) continue;
            const bool is_vertex = e == vertex_el_;
            if (is_vertex) mesh.positions.resize(static_cast<size_t>(el.count));
            for (uint64_t i = 0; i < el.count; ++i) {
                for (const Property& pr : el.props) {
                    if (!pr.is_list) {
                        const std::string_view t = token(c, el, i);
                        if (pr.role == Role::Skip) continue;
                        const double v = ascii_real(c, t, el, i);
                        if (!std::isfinite(v))
                            fail_line(c.line, "non-finite coordinate " + quoted(t) + " in " + record_text(el, i));
                        const int a = static_cast<int>(pr.role) - static_cast<int>(Role::X);
                        mesh.positions[static_cast<size_t>(i)][a] = static_cast<Real>(v);
                        continue;
                    }
                    const int64_t n = ascii_int(c, token(c, el, i), el, i);
                    if (n < 0)
                        fail_line(c.line, "negative list count " + std::to_string(n) + " in " + record_text(el, i));
                    if (pr.role != Role::Indices) {
                        // Each token uses at least one byte, so this loop ends by EOF.
                        for (int64_t k = 0; k < n; ++k) token(c, el, i);
                        continue;
                    }
                    if (n < 3)
                        fail_line(c.line, "face with " + std::to_string(n) + " vertices (at least 3 needed) in " +
                                              record_text(el, i));
                    Fan fan;
                    for (int64_t k = 0; k < n; ++k) {
                        const int64_t v = ascii_int(c, token(c, el, i), el, i);
                        if (static_cast<uint64_t>(v) >= vertex_count_)
                            fail_line(c.line, bad_index_text(v, vertex_count_) + " in " + record_text(el, i));
                        fan.add(k, static_cast<uint32_t>(v), tris);
                    }
                    if (n > 3) ++mesh.polygons_split;
                }
            }
        }
    }
};

}  // namespace

PlyMesh read_ply(const std::string& path) {
    FileBytes f;
    f.load(path);
    PlyParser parser(path, f.data(), f.size());
    return parser.parse();
}

PlyMesh parse_ply(const char* data, size_t size, const std::string& path) {
    PlyParser parser(path, reinterpret_cast<const unsigned char*>(data), size);
    return parser.parse();
}

}  // namespace rt
