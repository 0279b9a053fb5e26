// What every kind of shape shares: the fields of its scene-file entry, the surface
// it gives shading, and its polygons for export. One kind of shape is one file of
// include/rt/shapes/ (sphere.h, plane.h); shapes.h lists them. Triangles, which meshes
// are made of, are the kind the BVH's leaves test in blocks (rt/geometry/geometry.h).
//
// A kind S provides, each used by exactly one stage:
//   S::Desc, S::kKey, S::kKeys, S::read   loader: Objects/<kKey> entries, the keys each
//                                         may carry, and the reading of its own fields
//   S::kNoun, S::kNouns                   counts in messages and --stats ("3 spheres")
//   S::kBounded                           true: in the BVH; false: tested by every ray
//   S::build(desc)                        the render form, built from the desc
//   s.bounds(), s.intersect(...), s.surface(p)   the BVH build, ray tests, shading
//   S::extent(desc, add), S::polygons(desc, frame) the OBJ export (rtconvert)
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/core/math.h"

namespace rt {

// The fields the loader reads for every kind: Material (a 1-based id in the file) and
// _id, as written (its 1-based position among its kind when it has none).
struct ShapeDescBase {
    uint32_t material = 0;  // into SceneDesc::materials
    std::string id;
};

// What shading needs to know about a hit point.
struct Surface {
    Vec3 ng;            // unit geometric normal, the outward (counter-clockwise) side
    Vec3 ns;            // unit shading normal, on ng's side
    uint32_t material;  // into SceneSetup::materials
};

// A shape as polygons, for formats without spheres or planes (OBJ). Faces index
// `vertices` (0-based) counter-clockwise seen from outside.
struct Polygons {
    std::vector<Vec3> vertices;
    std::vector<std::vector<uint32_t>> faces;
    bool smooth = false;  // smooth-shaded in the export
};

// What the export knows of the whole scene when it makes polygons: the segments of a
// tessellated curved surface, and the scene's centre and extent (the size of a quad
// that stands for an infinite plane).
struct ExportFrame {
    int segments = 48;
    Vec3 center;
    Real extent = 1;
};

}  // namespace rt
