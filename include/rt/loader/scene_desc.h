// The scene as written in the file: plain typed structs, filled by the loader
// (src/loader) and consumed by the scene builder (src/scene_build/build_scene.cpp).
// Ids in the file are 1-based; everything here is 0-based and has been
// range-checked by the loader, so the builder never sees a bad index.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/core/affine.h"
#include "rt/core/math.h"
#include "rt/loader/camera_desc.h"
#include "rt/loader/material_desc.h"
#include "rt/loader/shape_descs.h"

namespace rt {

// Every number in a scene (and every PLY coordinate) must lie within +-1e30: the BVH
// keeps its boxes in float (max ~3.4e38), and squared distances must stay finite.
constexpr double kMaxMagnitude = 1e30;

// MaxRecursionDepth's bound: the loader's, and that of the overrides (--max-depth, the page's
// max_depth) and of the glTF import.
constexpr int kMaxRecursionDepth = 10000;

struct PointLightDesc {
    Vec3 position, intensity;
};

// Lights/AreaLight: a square emitter of side `size` about `position`, facing along
// `normal` (non-zero, as written: the build normalises it, so that a conversion writes
// back the file's own); `radiance` per unit area and solid angle (docs/conventions.md,
// "Assignment 3").
struct AreaLightDesc {
    Vec3 position, normal, radiance;
    Real size = 1;
};

enum class ShadingMode { Flat, Smooth };

struct MeshDesc {
    uint32_t material = 0;
    ShadingMode shading = ShadingMode::Flat;
    // Vertex positions used by this mesh and triangles indexing them (0-based, local).
    // Inline meshes copy the VertexData entries they use, so smooth normals are per mesh.
    std::vector<Vec3> positions;
    std::vector<uint32_t> indices;  // 3 per triangle
    std::string source;             // where the faces came from: a PLY file's path, or a JSON pointer
    // A PLY mesh's JSON pointer (/Scene/Objects/Mesh/0/Faces/_plyFile) while its file is
    // not read yet (rt/loader/scene_tree.h, read_mesh_files); empty once read, and for
    // inline faces.
    std::string ply_pointer;
    // What the scene file calls it (--trace): an Objects/Mesh, or an Objects/Triangle
    // (one face), and its _id as written (its 1-based position among its kind without one).
    bool triangle_object = false;
    std::string id;
    // Its Transformations: the positions above as written -> the world.
    Affine transform;
    // MotionBlur: the world-space translation it makes over the shutter (zero: still).
    Vec3 motion;
    // Drawn as an instance of itself (InstanceDesc), its positions kept as
    // written: shown by a MeshInstance, or moved by Transformations. Otherwise its
    // transform is the identity.
    bool instanced = false;
    // Read through a PlyCache (an animation's MeshCache): the PLY file's path and
    // content, under which its BVH is shared by every frame that reads the same file
    // (rt/scene_build/mesh_cache.h).
    std::string content_key;
};

struct SceneDesc {
    std::string path;  // the scene file, for messages
    Vec3 background;   // BackgroundColor, default 0 0 0
    Real shadow_ray_epsilon = Real(1e-3);
    Real intersection_test_epsilon = Real(1e-6);
    int max_recursion_depth = 6;
    Vec3 ambient_light;
    std::vector<CameraDesc> cameras;
    std::vector<PointLightDesc> point_lights;
    std::vector<AreaLightDesc> area_lights;
    std::vector<MaterialDesc> materials;
    std::vector<MeshDesc> meshes;       // Objects/Triangle entries become one-triangle flat meshes
    ShapeDescVectors shapes;            // the other kinds (rt/loader/shape_descs.h): all<SphereDesc>(), ...
    std::vector<std::string> warnings;  // unknown keys, skipped degenerate triangles, ...
    double ply_seconds = 0;             // spent reading PLY files, for --stats

    // The entries of desc kind D (rt/loader/shape_descs.h), in file order.
    template <class D>
    std::vector<D>& all() {
        return std::get<IndexIn<D, ShapeDescs>::value>(shapes);
    }
    template <class D>
    const std::vector<D>& all() const {
        return std::get<IndexIn<D, ShapeDescs>::value>(shapes);
    }
};

}  // namespace rt
