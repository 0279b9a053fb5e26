// A mesh instance (Objects/MeshInstance): the triangles of a mesh shown again under a
// transformation of their own, without a copy. The mesh is kept once, in its own
// (object) space, with a BVH of its own; the scene's BVH holds each instance as one
// box, and a ray that enters it is carried into object space by the inverse matrix
// and traced through the mesh's BVH (the two-level scheme of pbrt and Embree). The
// direction is not renormalised, so t is the same in both spaces.
//
// A mesh that any instance shows is itself drawn as an instance of its object-space
// triangles (an InstanceDesc with key "Mesh", rt/loader/shape_descs.h), so its triangles
// exist once. The ray test and surface, a query of the mesh's scene, are defined beside
// the traversal (src/geometry/instance.cpp).
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/core/affine.h"
#include "rt/shapes/shape.h"

namespace rt {

struct Instance {
    using Desc = InstanceDesc;
    static constexpr bool kBounded = true;

    const Scene* mesh = nullptr;  // the mesh's triangles and BVH, in object space
    Affine to_object;             // world -> object
    uint32_t material = 0;
    Vec3 motion;  // MotionBlur: at time t of a ray the whole instance is moved by motion * t
    bool moving = false;

    static Instance build(const Desc& d, const BuildInputs& in);

    // The world box around the mesh's box (its BVH root's), moved, and swept along its
    // motion; empty for an empty mesh.
    Box bounds() const;
    template <bool kCull, bool kShadow>
    bool intersect(const Ray& ray, Real tmin, Real tmax, Real& t, Real w[3], uint32_t& part) const {
        return trace(ray, tmin, tmax, kCull, kShadow, t, w, part);
    }
    // The mesh's triangle `part` at barycentric weights w, its normals carried to the
    // world by the inverse transpose.
    Surface surface(Vec3 p, const Real w[3], uint32_t part) const;

    // Extent and polygons: the mesh's, moved.
    template <class Add>
    static void extent(const Desc& d, const std::vector<MeshDesc>& meshes, Add&& add) {
        for (Vec3 p : mesh_positions(d, meshes)) add(d.transform.point(p));
    }
    static Polygons polygons(const Desc& d, const ExportFrame& f);

private:
    bool trace(const Ray& ray, Real tmin, Real tmax, bool cull, bool shadow, Real& t, Real w[3], uint32_t& part) const;
    static const std::vector<Vec3>& mesh_positions(const Desc& d, const std::vector<MeshDesc>& meshes);
};

// A mesh's triangles as polygons, moved by `to_world` (the OBJ export).
Polygons mesh_polygons(const MeshDesc& m, const Affine& to_world);

}  // namespace rt
