// Render data, built once from a SceneDesc (build_scene); constructors never see
// JSON. A Scene has four parts:
//   setup     what the scene says besides its shapes: settings, cameras, lights, materials
//   geometry  the shapes (rt/geometry/geometry.h)
//   accel     the acceleration structure over the bounded shapes (BVH, leaf-order vertices)
//   report    what the build measured and skipped
// and the names the file gives its shapes. The queries are in rt/bvh/traverse.h.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/camera/camera.h"
#include "rt/core/uninit_vector.h"
#include "rt/geometry/geometry.h"
#include "rt/geometry/leaf_vertices.h"
#include "rt/geometry/shape_names.h"
#include "rt/loader/mesh_cache.h"
#include "rt/loader/scene_desc.h"

namespace rt {

// The materials and lights are rendered as loaded. (A Plain material's
// MirrorReflectance is never read: reference-conventions.md, "Shading".)
using Material = MaterialDesc;
using PointLight = PointLightDesc;

// What the scene file says, apart from its shapes.
struct SceneSetup {
    Vec3 background, ambient_light;
    Real shadow_ray_epsilon = Real(1e-3);
    int max_recursion_depth = 6;
    std::vector<Camera> cameras;
    std::vector<PointLight> lights;
    std::vector<Material> materials;
};

// Over primitive ids [0, geometry.bounded_count()).
struct Acceleration {
    Bvh bvh;
    LeafVertices leaf_vertices;
};

// What building the scene measured and skipped, for messages and --stats.
struct BuildReport {
    double build_seconds = 0;         // BVH build (and leaf-order copy) time
    size_t degenerate_triangles = 0;  // skipped (spec 2.10)
};

struct Scene {
    SceneSetup setup;
    Geometry geometry;
    Acceleration accel;
    BuildReport report;
    ShapeNames names;
};

// Float bounds, rounded outwards, of every bounded primitive (the BVH's ids).
UninitVector<BuildBox> primitive_boxes(const Geometry& g);

// Builds render data: gathers the meshes' vertices into one array, computes
// area-weighted vertex normals of smooth meshes, skips degenerate triangles
// (spec 2.10) and builds the BVH (`bvh`: build quality knobs, for measurements).
// Takes the vertices of the first mesh and releases each mesh of `desc` as soon
// as it is copied (lower peak memory).
// `meshes`: the cache the scene was loaded with (load_scene), which holds the BVHs of the
// meshes it read from PLY files, built here the first time.
Scene build_scene(SceneDesc&& desc, const BvhBuildOptions& bvh = {}, MeshCache* meshes = nullptr);
// The same on a copy of `desc`.
Scene build_scene(const SceneDesc& desc, const BvhBuildOptions& bvh = {}, MeshCache* meshes = nullptr);

}  // namespace rt
