// What the scene file calls each primitive, for --trace (src/geometry/shape_names.cpp).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/geometry/geometry.h"

namespace rt {

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
    // By ShapeKind, none for triangles: each primitive's _id, and the Objects/<key> it was
    // written under when that is not its kind's (ShapeDescBase::key), else null.
    std::vector<std::string> ids[kShapeKindCount];
    std::vector<const char*> keys[kShapeKindCount];

    // "Mesh 3, face 1207" (the face's 0-based index in the mesh's PLY or _data, skipped
    // faces counted), "Triangle 4", "Sphere 2" (its kind's key); "triangle #i" (etc.) for a
    // primitive without a name (scenes built in code).
    std::string name(ShapeRef s) const;
};

}  // namespace rt
