// A binary BVH in one flat array of 32-byte nodes, built with binned SAH.
// Bounds are stored as float, rounded outwards, so every box contains its
// primitives exactly even when Real is double.
#pragma once
#include <cstdint>
#include <vector>

#include "rt/math.h"

namespace rt {

struct Aabb {
    Vec3 lo{Real(HUGE_VAL), Real(HUGE_VAL), Real(HUGE_VAL)}, hi{-Real(HUGE_VAL), -Real(HUGE_VAL), -Real(HUGE_VAL)};
    void extend(Vec3 p) { lo = vmin(lo, p); hi = vmax(hi, p); }
    void extend(const Aabb& b) { lo = vmin(lo, b.lo); hi = vmax(hi, b.hi); }
    Vec3 centre() const { return (lo + hi) * Real(0.5); }
    Real area() const {
        Vec3 e = hi - lo;
        return e.x < 0 ? 0 : 2 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

struct BvhNode {
    float lo[3];
    uint32_t first;  // leaf: first index into Bvh::prims; interior: index of left child (right = first + 1)
    float hi[3];
    uint16_t count;  // leaf: number of primitives (> 0); interior: 0
    uint16_t axis;   // interior: split axis, for near-child-first traversal
};
static_assert(sizeof(BvhNode) == 32, "BvhNode must stay 32 bytes");

struct Bvh {
    std::vector<BvhNode> nodes;   // nodes[0] is the root (absent when there are no primitives)
    std::vector<uint32_t> prims;  // primitive ids in leaf order
    int depth = 0;

    // Builds over `bounds[i]` (one box per primitive id i).
    void build(const std::vector<Aabb>& bounds);
};

}  // namespace rt
