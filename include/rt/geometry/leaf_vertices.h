// Triangle vertices in BVH leaf order, for the leaf kernels (rt/geometry/leaf_test.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "rt/bvh/bvh.h"
#include "rt/core/uninit_vector.h"

namespace rt {

// Each BVH leaf triangle's vertices a, b, c as 9 coordinates, in leaf order
// (entry i is triangle bvh.prims[i]), so that a leaf's triangles are one block of
// memory instead of a chain of loads (prims, triangles, positions). Within a leaf
// of n triangles the coordinates are grouped (at(), below), so that four
// triangles' x of vertex a, say, are one plain load, not a gather. build_scene
// makes them when leaves test several triangles at once (kLeafBlock), in one of two
// precisions, and only where they change no number the tests see (with Real =
// float: always in float, serving every leaf of triangles):
//  - doubles, for scenes of at most BvhBuildOptions::double_copy_max primitives
//    (the official scenes, whose JSON coordinates are seldom floats): every leaf
//    of triangles;
//  - floats, for larger ones: the leaves of triangles whose every coordinate is a
//    float exactly (PLY meshes are), at 36 bytes a triangle, in the storage the
//    BVH build's boxes were in (ReusableStorage: its pages are already touched,
//    and a fresh page's first-touch fault can cost more than the copy into it).
// Every other leaf (a sphere, a coordinate that is not a float) is marked
// BvhNode::kIndexedLeaf and reads its primitives through their ids.
class LeafVertices {
public:
    // Coordinates for n triangles: loads of kLeafBlock lanes from the last leaf's
    // last triangle read up to kLeafBlock - 1 past its end.
    static constexpr size_t coordinates_for(size_t n) { return 9 * n + kLeafBlock - 1; }
    // Index of coordinate `axis` of vertex `k` of the triangle at leaf position
    // first + j, in the leaf at prims[first, first + n).
    static size_t at(uint32_t first, uint32_t n, uint32_t j, int k, int axis) {
        return 9 * size_t(first) + size_t(3 * k + axis) * n + j;
    }

    LeafVertices() = default;
    // `coordinates` (coordinates_for(the BVH's primitive count) of them, float or
    // double) is the array `storage` holds.
    template <class T>
    LeafVertices(ReusableStorage&& storage, const T* coordinates) : storage_(std::move(storage)) {
        static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>);
        if constexpr (std::is_same_v<T, float>)
            floats_ = coordinates;
        else
            doubles_ = coordinates;
    }
    // The copy in its precision; null when it is in the other one, or there is none.
    const float* floats() const { return floats_; }
    const double* doubles() const { return doubles_; }

private:
    ReusableStorage storage_;
    const float* floats_ = nullptr;
    const double* doubles_ = nullptr;
};

}  // namespace rt
