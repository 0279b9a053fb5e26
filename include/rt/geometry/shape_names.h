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
    std::vector<std::string> labels[kShapeKindCount];  // by ShapeKind ("Sphere 3"); none for triangles

    // "Mesh 3, face 1207" (the face's 0-based index in the mesh's PLY or _data, skipped
    // faces counted), "Triangle 4", "Sphere 2" (its kind's key); "triangle #i" (etc.) for a
    // primitive without a name (scenes built in code).
    std::string name(ShapeRef s) const;
};

}  // namespace rt
