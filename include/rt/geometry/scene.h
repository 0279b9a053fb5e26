// Render data, built once from a SceneDesc (build_scene, rt/scene_build/build_scene.h);
// constructors never see JSON. A Scene has four parts:
//   setup     what the scene says besides its shapes: settings, cameras, lights, materials
//   geometry  the shapes (rt/geometry/geometry.h)
//   accel     the acceleration structure over the bounded shapes (BVH, leaf-order vertices)
//   report    what the build measured and skipped
// and the names the file gives its shapes. The queries are in rt/geometry/traverse.h.
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
#include "rt/geometry/light.h"
#include "rt/geometry/shape_names.h"
#include "rt/materials/material.h"

namespace rt {

// What the scene file says, apart from its shapes.
struct SceneSetup {
    Vec3 background, ambient_light;
    Real shadow_ray_epsilon = Real(1e-3);
    int max_recursion_depth = 6;
    std::vector<Camera> cameras;
    std::vector<Light> lights;  // point lights, then area lights, each in file order
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

}  // namespace rt
