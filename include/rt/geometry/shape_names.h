// What the scene file calls each primitive, for --trace (src/geometry/shape_names.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rt/geometry/geometry.h"

namespace rt {

// The names of one kind's primitives, in one buffer: a name costs its characters and four
// bytes, not a std::string each (a scene of many instances keeps them all for --trace).
class NameList {
public:
    void reserve(size_t n) { ends_.reserve(n); }
    // Appends a primitive's _id and the Objects/<key> it was written under when that is
    // not its kind's (ShapeDescBase::key), else null.
    void push_back(std::string_view id, const char* key);
    size_t size() const { return ends_.size(); }
    std::string_view id(size_t i) const {
        const uint32_t begin = i ? ends_[i - 1] : 0;
        return std::string_view(chars_).substr(begin, ends_[i] - begin);
    }
    const char* key(size_t i) const;

private:
    std::string chars_;
    std::vector<uint32_t> ends_;                          // where each id ends in chars_
    std::vector<std::pair<uint32_t, const char*>> keys_;  // (index, key) of the non-null keys, ascending
};

// What the scene file calls each primitive (--trace names hits by it): one entry per
// Objects/Mesh or Objects/Triangle in triangle order, and the other kinds' names.
struct ShapeNames {
    struct Mesh {
        uint32_t first_triangle = 0;    // its first triangle in Geometry::triangles
        bool triangle_object = false;   // an Objects/Triangle (one face)
        std::string id;                 // MeshDesc::id
        std::vector<uint32_t> skipped;  // its degenerate faces, not in Geometry (spec 2.10), ascending
    };
    std::vector<Mesh> meshes;
    // By ShapeKind, none for triangles: each primitive's _id and key.
    NameList ids[kShapeKindCount];

    // "Mesh 3, face 1207" (the face's 0-based index in the mesh's PLY or _data, skipped
    // faces counted), "Triangle 4", "Sphere 2" (its kind's key); "triangle #i" (etc.) for a
    // primitive without a name (scenes built in code).
    std::string name(ShapeRef s) const;
};

}  // namespace rt
