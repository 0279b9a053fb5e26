// Render data: flat arrays built once from a SceneDesc. Constructors never see JSON.
// Triangles share one vertex array; spheres and triangles sit under one BVH,
// infinite planes are tested separately (they have no finite bounds).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/bvh.h"
#include "rt/camera.h"
#include "rt/scene_desc.h"

namespace rt {

struct Material {
    MaterialType type = MaterialType::Plain;
    Vec3 ambient, diffuse, specular;
    Real phong_exponent = 1;
    Vec3 mirror;
    Real refraction_index = 1, absorption_index = 0;
    Vec3 absorption_coefficient;
};

struct Triangle {
    uint32_t v[3];            // into Scene::positions (and Scene::vertex_normals when smooth)
    uint32_t material : 31;
    uint32_t smooth : 1;      // 1: interpolate vertex normals; 0: flat
};
static_assert(sizeof(Triangle) == 16, "Triangle must stay 16 bytes");

struct Sphere {
    Vec3 center;
    Real radius;
    uint32_t material;
};

struct Plane {
    Vec3 point, normal;  // normal has unit length
    uint32_t material;
};

struct PointLight {
    Vec3 position, intensity;
};

struct Scene {
    std::string path;
    Vec3 background, ambient_light;
    Real shadow_ray_epsilon = Real(1e-3);
    int max_recursion_depth = 6;

    std::vector<Camera> cameras;
    std::vector<PointLight> lights;
    std::vector<Material> materials;

    std::vector<Vec3> positions;
    std::vector<Vec3> vertex_normals;  // area-weighted, per mesh; unit length or zero
    UninitVector<Triangle> triangles;
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;

    // Over primitive ids: [0, triangles.size()) are triangles, the rest spheres.
    Bvh bvh;
    // Each triangle's vertices a, b, c as 9 floats, in BVH leaf order (entry i is
    // triangle bvh.prims[i]), so that a leaf's triangles are one block of memory
    // instead of a chain of loads (prims, triangles, positions). Present only when
    // it changes no number the tests see: every vertex coordinate is a float
    // exactly (PLY meshes are), there are no spheres, and leaves test four
    // triangles at once (kLeafBlock); null otherwise. The storage is the BVH
    // build's box array, reused (its pages are already touched: on this VM a
    // fresh page costs more than the copy into it).
    UninitVector<BuildBox> leaf_storage;
    const float* leaf_vertices() const {
        return leaf_storage.empty() ? nullptr : reinterpret_cast<const float*>(leaf_storage.data());
    }
    size_t degenerate_triangles = 0;  // skipped at build time

    Real build_seconds = 0;  // BVH build time, for the per-image report line

    // Unit geometric normal of triangle i, counter-clockwise front (spec 3, "Triangle").
    Vec3 face_normal(uint32_t i) const {
        const Triangle& t = triangles[i];
        const Vec3 a = positions[t.v[0]];
        return normalize(cross(positions[t.v[1]] - a, positions[t.v[2]] - a));
    }
};

// Float bounds, rounded outwards, of every triangle then every sphere (the BVH's
// primitive ids).
UninitVector<BuildBox> primitive_boxes(const Scene& s);

// Builds render data: gathers the meshes' vertices into one array, computes
// area-weighted vertex normals of smooth meshes, skips degenerate triangles
// (spec 2.10) and builds the BVH (`bvh`: build quality knobs, for measurements).
// Takes the vertices of the first mesh and releases each mesh of `desc` as soon
// as it is copied (lower peak memory).
Scene build_scene(SceneDesc&& desc, const BvhBuildOptions& bvh = {});
// The same on a copy of `desc`.
Scene build_scene(const SceneDesc& desc, const BvhBuildOptions& bvh = {});

}  // namespace rt
