// The build step: a scene as the file says it (SceneDesc, rt/loader/scene_desc.h) made
// into render data (Scene, rt/geometry/scene.h): cameras, materials and lights in the
// renderer's form, the shapes' flat arrays, the BVH.
#pragma once
#include "rt/bvh/bvh.h"
#include "rt/core/uninit_vector.h"
#include "rt/geometry/scene.h"
#include "rt/loader/scene_desc.h"
#include "rt/scene_build/mesh_cache.h"

namespace rt {

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
