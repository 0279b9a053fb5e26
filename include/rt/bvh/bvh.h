// An 8-wide BVH in one flat array of 256-byte nodes, built directly by binned
// SAH and then collapsed into fuller nodes (src/bvh/bvh_build.cpp, bvh_collapse.cpp):
// one SIMD box test serves eight children. Rays through large
// meshes mostly wait for node loads; a wider node means fewer levels, so fewer
// dependent loads per ray, and the eight float boxes fill one AVX register as
// Embree's 8-wide nodes do (docs/performance.md). Bounds are stored as float,
// rounded outwards, so every box contains its primitives exactly even when
// Real is double; the box test itself runs in Real (box_test.h). Leaves hold
// up to kDefaultMaxLeaf primitives, tested kLeafBlock at a time (one SIMD register: four doubles
// with AVX2, eight with AVX-512, eight floats), and the SAH prices them that way
// (BvhBuildOptions::block).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <vector>

#include "rt/core/math.h"
#include "rt/core/uninit_vector.h"

namespace rt {

// Rounds a Real bound outwards to float.
float round_down_to_float(Real x);
float round_up_to_float(Real x);

// The box types: Box (below) for every box the code handles as a whole; a
// BuildBox for each primitive the builder sorts (a Box's corners around its id);
// BvhNode's child slots (kWidth boxes, structure of arrays, for the SIMD slab
// test); and, inside the builder only, Box8, a box held in one AVX register as
// (lo, -hi) so that one min instruction extends both corners (box8.h).

// An axis-aligned box in float: bounds rounded outwards contain Real geometry
// exactly. The default box is empty (lo = +inf, hi = -inf).
struct Box {
    float lo[3] = {HUGE_VALF, HUGE_VALF, HUGE_VALF};
    float hi[3] = {-HUGE_VALF, -HUGE_VALF, -HUGE_VALF};

    // The smallest float box around the Real box [lo, hi].
    static Box around(Vec3 lo, Vec3 hi) {
        Box b;
        for (int a = 0; a < 3; ++a) {
            b.lo[a] = round_down_to_float(lo[a]);
            b.hi[a] = round_up_to_float(hi[a]);
        }
        return b;
    }
    void extend(const float l[3], const float h[3]) {
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::min(lo[a], l[a]);
            hi[a] = std::max(hi[a], h[a]);
        }
    }
    void extend(const Box& b) { extend(b.lo, b.hi); }
    // Surface area; 0 for an empty box.
    float area() const {
        const float x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
        return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
    }
};

// Box b and b moved by `motion`, and everything between: where a shape that moves by
// `motion` over the shutter (MotionBlur) can be.
inline Box swept(const Box& b, Vec3 motion) {
    if (!(b.lo[0] <= b.hi[0])) return b;  // empty
    Box out = b;
    out.extend(Box::around(Vec3{b.lo[0], b.lo[1], b.lo[2]} + motion, Vec3{b.hi[0], b.hi[1], b.hi[2]} + motion));
    return out;
}

// A primitive's bounds handed to the builder, laid out as the builder's SIMD
// loads want them (lo in floats 0..2, hi in 4..6). The builder sorts these in
// place; `id` is set by Bvh::build. `alone` is 1 for a primitive that leaves
// test one at a time (spheres), 0 for one they test in blocks of kLeafBlock
// (triangles): the SAH prices leaves that way.
struct BuildBox {
    float lo[3];
    uint32_t id;
    float hi[3];
    uint32_t alone;

    static BuildBox of(const Box& b, bool alone = false) {
        return {{b.lo[0], b.lo[1], b.lo[2]}, 0, {b.hi[0], b.hi[1], b.hi[2]}, alone ? 1u : 0u};
    }
};

struct alignas(64) BvhNode {
    static constexpr int kWidth = 8;  // children per node
    // Child boxes, structure of arrays: lo[axis][child], hi[axis][child].
    // Empty slots hold lo = +inf, hi = -inf and are never entered.
    float lo[3][kWidth];
    float hi[3][kWidth];
    // child[i] >= 0: index of an inner node. child[i] < 0: a leaf holding
    // prims[first .. first + count) with first = ~child[i] and count = count[i].
    int32_t child[kWidth];
    uint16_t count[kWidth];
    uint8_t pad[2 * kWidth];  // to kWidth / 2 whole cache lines

    static constexpr int32_t kEmpty = INT32_MIN;  // an unused slot (count 0)
    // Set in a leaf's count when its primitives are read through their ids, not
    // from the leaf-order vertices (build_scene.cpp); the low bits hold its size.
    static constexpr uint16_t kIndexedLeaf = 0x8000;
    bool is_leaf(int i) const { return child[i] < 0; }
    static uint32_t leaf_size_of(uint16_t c) { return c & ~uint32_t(kIndexedLeaf); }
    uint32_t leaf_size(int i) const { return leaf_size_of(count[i]); }
};
static_assert(sizeof(BvhNode) == 32 * BvhNode::kWidth, "BvhNode must stay kWidth / 2 cache lines");

// Fixed-capacity node storage: the builder reserves an upper bound of nodes
// without touching the pages (so unused capacity costs no memory) and fills
// them from several threads through an atomic counter.
class NodeArray {
public:
    size_t size() const { return size_; }
    bool empty() const { return size_ == 0; }
    const BvhNode& operator[](size_t i) const { return data_[i]; }
    BvhNode& operator[](size_t i) { return data_[i]; }
    const BvhNode* begin() const { return data_.get(); }
    const BvhNode* end() const { return data_.get() + size_; }
    void clear() {
        data_.reset();
        size_ = 0;
        bytes_ = 0;
    }
    // Storage for `capacity` nodes, uninitialised; then set_size(n) with n <= capacity.
    // Large arrays ask for transparent huge pages (allocate_bytes, rt/io/memory.h).
    void allocate(size_t capacity);
    void set_size(size_t n) { size_ = n; }
    // Gives the whole pages past size() back to the system (after nodes were
    // removed); the capacity stays, and pages read again read as zeros.
    void release_unused();

private:
    struct Free {
        void operator()(BvhNode* p) const;
    };
    std::unique_ptr<BvhNode[], Free> data_;
    size_t size_ = 0;
    size_t bytes_ = 0;  // allocated
};

// Primitives a leaf tests at once (leaf_test.h): one SIMD register of Real
// lanes, four triangles in double with AVX2 and eight with AVX-512, eight in
// float; one without AVX2.
#if defined(__AVX512F__)
inline constexpr uint32_t kLeafBlock = 8;
#elif defined(__AVX2__)
inline constexpr uint32_t kLeafBlock = std::is_same_v<Real, float> ? 8 : 4;
#else
inline constexpr uint32_t kLeafBlock = 1;
#endif

// The largest leaf by default: 8 in double, 16 in float (two blocks of eight). In
// float, leaves of 16 render as fast and take a third fewer nodes (docs/performance.md).
inline constexpr uint32_t kDefaultMaxLeaf = std::is_same_v<Real, float> ? 16 : 8;

// Build quality knobs (the raytracer's hidden --bvh-* options, for measurements);
// the defaults are what every render uses.
struct BvhBuildOptions {
    uint32_t max_leaf = kDefaultMaxLeaf;  // a leaf never holds more primitives, whatever SAH says (1..1024)
    float traversal_cost = 1;             // SAH cost of one traversal step, relative to one leaf block test
    // The SAH counts a leaf's triangles in blocks of this many (1..16), other shapes one by
    // one; 0: block_for() chooses.
    uint32_t block = 0;
    int bins = 16;         // SAH bins per axis for large ranges (2..16; small ranges use fewer)
    bool sah = true;       // false: object-median splits only (fastest build, slower rays)
    bool collapse = true;  // false: keep the top-down tree's sparse bottom nodes (bvh_collapse.cpp)
    // Leaf-order vertices (rt/geometry/leaf_vertices.h) in double for scenes of up to
    // this many primitives (72 bytes a triangle, at most 9 MiB: a copy that stays
    // in cache), in float above (docs/performance.md); 0: never double. Double builds
    // only: with Real = float the copy is always in float.
    size_t double_copy_max = size_t(1) << 17;

    // Whether leaves of a tree over n primitives read their vertices from the double copy.
    bool double_copies(size_t n) const { return std::is_same_v<Real, double> && n <= double_copy_max; }
    // The block the SAH prices leaves in, for n primitives: `block` when set, else as
    // many triangles as one leaf test takes (kLeafBlock), but at most four where they
    // come from the double copy: eight doubles a coordinate fill a 64-byte line, twice
    // the bytes of eight floats, and leaves priced as if they held four made the small
    // scenes' secondary rays faster (docs/performance.md).
    uint32_t block_for(size_t n) const {
        if (block != 0) return std::min<uint32_t>(block, 16);
        return double_copies(n) ? std::min<uint32_t>(kLeafBlock, 4) : kLeafBlock;
    }
};

struct Bvh {
    NodeArray nodes;              // nodes[0] is the root (absent when there are no primitives)
    std::vector<uint32_t> prims;  // primitive ids in leaf order
    int depth = 0;                // in nodes, root = 1
    uint32_t block = 0;           // the leaf block the SAH priced leaves in (BvhBuildOptions::block_for)
    float extent = 0;             // largest magnitude of the root's bounds (0 when empty)
    Box bounds;                   // the root's bounds (empty when there are no primitives)

    // Builds over `boxes[i]` (one box per primitive id i, n of them), sorting them
    // in place: their contents are unspecified afterwards, their storage the
    // caller's to free or reuse (build_scene reuses it for the leaf-order vertices).
    void build(BuildBox* boxes, size_t n, const BvhBuildOptions& options = {});
    void build(UninitVector<BuildBox>& boxes, const BvhBuildOptions& options = {}) {
        build(boxes.data(), boxes.size(), options);
    }
};

// The traversal's box test (box_test.h, box_test.cpp), exposed for the tests. It must accept
// every child box of `node` that the exact ray org + t dir, t in [tmin, tmax],
// enters once the box is grown by box_padding(bvh, ray) on every side (tmin >= 0);
// it never accepts an empty slot, but for float rays outside the float test's
// domain (box_test.h, box_ray_into<float>), which enter every slot. Returns the mask of
// accepted children and their entry distances in t (for accepted ones: in float at
// most the exact entry rounded up to a float; in double at most a factor 1 + 2^-50
// above it, three roundings, give or take a few subnormals where it underflows).
// `scalar` runs the lane-by-lane kernel instead of the SIMD one, which gives the
// same bits.
int test_node_boxes(const Bvh& bvh, const BvhNode& node, const Ray& ray, Real tmin, Real tmax, Real t[BvhNode::kWidth],
                    bool scalar);
// How far the box test pads every box for `ray`: 0 in double; in float, the rounding
// of the float primitive tests (box_test.h, box_pad).
double box_padding(const Bvh& bvh, const Ray& ray);

}  // namespace rt
