// What every kind of shape shares in the renderer: the surface it gives shading, what
// its build may use, and its polygons for export. One kind of shape is one file of
// include/rt/shapes/ (sphere.h, plane.h), built from its desc, which is what the scene
// file says of it (rt/loader/shape_descs.h); shapes.h lists them. Triangles, which meshes
// are made of, are the kind the BVH's leaves test in blocks (rt/geometry/geometry.h).
//
// A kind S provides, each used by exactly one stage:
//   S::Desc                               its desc (rt/loader/shape_descs.h): the loader's
//                                         keys, reading, nouns and transformation
//   S::kBounded                           true: in the BVH; false: tested by every ray
//   S::build(desc, inputs)                the render form, built from the desc
//   s.bounds(), s.intersect<kCull, kShadow>(ray, tmin, tmax, t, w, part),
//   s.surface(p, w, part)                 the BVH build, ray tests, shading; w and part
//                                         are what the test found besides t (a kind made
//                                         of triangles: which one, and where in it)
//   S::extent(desc, meshes, add), S::polygons(desc, frame)   the OBJ and glTF exports
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "rt/core/affine.h"
#include "rt/core/math.h"
#include "rt/loader/shape_descs.h"

namespace rt {

struct MeshDesc;  // rt/loader/scene_desc.h
struct Scene;     // rt/geometry/scene.h

// What shading needs to know about a hit point.
struct Surface {
    Vec3 ng;            // unit geometric normal, the outward (counter-clockwise) side
    Vec3 ns;            // unit shading normal, on ng's side
    uint32_t material;  // into SceneSetup::materials
};

// What build() may use besides its desc: the object-space scenes (triangles and their
// BVH) of the meshes that instances show, by SceneDesc::meshes index, null for others.
struct BuildInputs {
    std::vector<std::shared_ptr<const Scene>> mesh_scenes;
};

// A shape as polygons, for formats without spheres or planes (OBJ). Faces index
// `vertices` (0-based) counter-clockwise seen from outside.
struct Polygons {
    std::vector<Vec3> vertices;
    std::vector<std::vector<uint32_t>> faces;
    bool smooth = false;  // smooth-shaded in the export

    // Moves the polygons by m, reversing the faces where m mirrors (so they stay
    // counter-clockwise seen from outside).
    void move(const Affine& m) {
        if (m.is_identity()) return;
        for (Vec3& v : vertices) v = m.point(v);
        if (m.det() < 0)
            for (auto& f : faces) std::reverse(f.begin(), f.end());
    }
};

// What the export knows of the whole scene when it makes polygons: the segments of a
// tessellated curved surface, and the scene's centre and extent (the size of a quad
// that stands for an infinite plane).
struct ExportFrame {
    int segments = 128;
    Vec3 center;
    Real extent = 1;
    const std::vector<MeshDesc>* meshes = nullptr;  // the scene's, for instances
};

}  // namespace rt
