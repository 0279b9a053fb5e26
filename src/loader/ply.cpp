// Our own PLY reader; the contract is in rt/loader/ply.h.
//
// Strategy:
//   1. The whole file is in memory: regular files of 1 MiB or more are mapped
//      read-only, smaller ones and pipes are read into one buffer (FileBytes,
//      file_bytes.cpp).
//   2. The header is parsed into elements and properties; the vertex x/y/z and the
//      face index list are located by name, everything else is marked "skip"
//      (ply_header.cpp).
//   3. Before anything is allocated, every element count is checked against the
//      bytes that follow the header (count * smallest possible record), so a hostile
//      header cannot make us allocate or loop beyond what the file can hold
//      (ply_header.cpp).
//   4. The body is decoded in one pass into the triangle output (triangle_sink.h).
//      Binary bodies (ply_binary.cpp) use memcpy loads (ply_byte_order.h) with fast
//      paths for the usual layouts; ASCII bodies (ply_ascii.cpp) are tokenised by
//      hand and parsed with std::from_chars.
//
// What the parts share, and the form of every error message, is in ply_format.h.
#include "rt/loader/ply.h"

#include "file_bytes.h"
#include "ply_format.h"

namespace rt {
namespace {

PlyMesh parse(const ply_reader::PlyInput& in) {
    using namespace ply_reader;
    const PlyHeader h = read_header(in);
    PlyMesh mesh;
    // Sizes are bounded by the file size now (read_header), so this is safe.
    TriangleSink tris(mesh.indices,
                      h.face_el == PlyHeader::kNone ? 0 : 3 * static_cast<size_t>(h.elements[h.face_el].count));
    if (h.format == Format::Ascii)
        read_ascii_body(in, h, mesh, tris);
    else
        read_binary_body(in, h, mesh, tris);
    tris.finish();
    return mesh;  // anything after the last element is ignored
}

}  // namespace

PlyMesh read_ply(const std::string& path) {
    ply_reader::FileBytes f;
    f.load(path);
    return parse({path, f.data(), f.size()});
}

PlyMesh parse_ply(const char* data, size_t size, const std::string& path) {
    return parse({path, reinterpret_cast<const unsigned char*>(data), size});
}

}  // namespace rt
