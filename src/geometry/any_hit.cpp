// Any hit: the BVH traversal for shadow rays, which stops at the first primitive
// found, for one ray or a packet of neighbouring rays (rt/geometry/traverse.h).
#include <cstdint>

#include "rt/bvh/box_test.h"
#include "rt/bvh/intersect.h"
#include "rt/bvh/node_stack.h"
#include "rt/geometry/leaf_test.h"
#include "rt/geometry/traverse.h"

namespace rt {

using namespace traversal;

namespace {

// What any_hit and any_hits know of a shadow ray before the traversal.
enum class BeforeTree {
    Blocked,   // by an unbounded shape (outside the BVH) or by the hint
    Clear,     // and the tree is empty
    Traverse,  // the tree decides: p and br are set
};

inline BeforeTree any_hit_before_tree(const Scene& s, const Ray& ray, Real tmin, Real tmax, const uint32_t* occluder,
                                      RayPre& p, BoxRay& br) {
    bool blocked = false;
    for_each_shape([&](auto k) {
        using S = decltype(k);
        if constexpr (!S::kBounded) {
            for (const S& shape : s.geometry.all<S>()) {
                Real t, w[3];
                uint32_t part;
                if (!blocked && shape.template intersect<false, true>(ray, tmin, tmax, t, w, part)) blocked = true;
            }
        }
    });
    if (blocked) return BeforeTree::Blocked;
    if (s.accel.bvh.nodes.empty()) return BeforeTree::Clear;
    p = prepare(ray);
    if (occluder && *occluder != kNoOccluder) {
        Real t, w[3];
        uint32_t part;
        if (hit_prim<false, true>(s, p, *occluder, tmin, tmax, t, w, part)) return BeforeTree::Blocked;
    }
    box_ray_into(p, s.accel.bvh, tmin, br);
    return BeforeTree::Traverse;
}

}  // namespace

// Both traversals are flattened: everything they call is inlined, as the kernels in
// their inner loops must be. In a translation unit of its own, without the closest-hit
// code, GCC's size limits would leave the shadow rays' primitive test and
// any_hit_before_tree out of line. any_hit stays a call where any_hits uses it.
[[gnu::flatten, gnu::noinline]] bool any_hit(const Scene& s, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder) {
    RayPre p;
    BoxRay br;
    const BeforeTree before = any_hit_before_tree(s, ray, tmin, tmax, occluder, p, br);
    if (before != BeforeTree::Traverse) return before == BeforeTree::Blocked;
    Real w[3];
    uint32_t part;
    int32_t stack[kStackSize];
    uint16_t counts[kStackSize];
    int sp = 0;
    // One hit child is visited next without a trip through the stack.
    int32_t child = 0;
    uint16_t count = 0;
    for (;;) {
        if (child < 0) {
            const uint32_t first = ~static_cast<uint32_t>(child);
            if (test_leaf<false, true>(
                    s, p, first, count, tmin, [&] { return tmax; }, w, part,
                    [&](uint32_t id, Real, const float*) {
                        if (occluder) *occluder = id;
                        return true;
                    }))
                return true;
        } else {
            const BvhNode& n = s.accel.bvh.nodes[child];
            const NodeLinks links(n);
            alignas(kBoxesAlign) BoxReal t[kWidth];
            int mask = test_boxes(n, br, BoxReal(tmin), BoxReal(tmax), t);
            if (mask) {
                for (;;) {
                    const int i = __builtin_ctz(mask);
                    mask &= mask - 1;
                    if (!mask) {
                        child = links.child[i];
                        count = links.count[i];
                        break;
                    }
                    stack[sp] = links.child[i];
                    counts[sp++] = links.count[i];
                    prefetch_node(s.accel.bvh, links.child[i]);
                }
                continue;
            }
        }
        if (sp == 0) return false;
        --sp;
        child = stack[sp];
        count = counts[sp];
    }
}

// The packet traversal of any_hit: the queries' rays walk the tree together, each
// node and leaf loaded once for all of them. Each ray tests a node's boxes itself and
// enters only the children its own test enters, and a ray leaves the packet once it
// is blocked, so each answer is any_hit's. Children are visited in any_hit's order.
[[gnu::flatten]] void any_hits(const Scene& s, const ShadowQuery* queries, int n, bool* hit) {
    if (n == 1) {
        hit[0] = any_hit(s, queries[0].ray, queries[0].tmin, queries[0].tmax, queries[0].occluder);
        return;
    }
    RayPre p[kPacket];
    BoxRay br[kPacket];
    unsigned live = 0;  // bit r: query r is still open
    for (int r = 0; r < n; ++r) {
        const ShadowQuery& q = queries[r];
        const BeforeTree before = any_hit_before_tree(s, q.ray, q.tmin, q.tmax, q.occluder, p[r], br[r]);
        hit[r] = before == BeforeTree::Blocked;
        if (before == BeforeTree::Traverse) live |= 1u << r;
    }
    if (!live) return;
    struct Entry {
        int32_t child;
        uint16_t count;
        uint16_t rays;  // the rays that entered it (bit r: query r)
    };
    Entry stack[kStackSize];
    int sp = 0;
    Entry e{0, 0, static_cast<uint16_t>(live)};
    for (;;) {
        if (e.child < 0) {
            const uint32_t first = ~static_cast<uint32_t>(e.child);
            for (unsigned m = e.rays; m; m &= m - 1) {
                const int r = __builtin_ctz(m);
                const ShadowQuery& q = queries[r];
                Real w[3];
                uint32_t part;
                if (test_leaf<false, true>(
                        s, p[r], first, e.count, q.tmin, [&q] { return q.tmax; }, w, part,
                        [&q](uint32_t id, Real, const float*) {
                            if (q.occluder) *q.occluder = id;
                            return true;
                        })) {
                    hit[r] = true;
                    live &= ~(1u << r);
                }
            }
            if (!live) return;
        } else {
            const BvhNode& node = s.accel.bvh.nodes[e.child];
            const NodeLinks links(node);
            unsigned child_rays[kWidth] = {};
            int any = 0;
            for (unsigned m = e.rays; m; m &= m - 1) {
                const int r = __builtin_ctz(m);
                alignas(kBoxesAlign) BoxReal t[kWidth];
                const int mask = test_boxes(node, br[r], BoxReal(queries[r].tmin), BoxReal(queries[r].tmax), t);
                for (int h = mask; h; h &= h - 1) child_rays[__builtin_ctz(h)] |= 1u << r;
                any |= mask;
            }
            if (any) {
                for (;;) {
                    const int i = __builtin_ctz(any);
                    any &= any - 1;
                    const Entry c{links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i])};
                    if (!any) {
                        e = c;
                        break;
                    }
                    stack[sp++] = c;
                    prefetch_node(s.accel.bvh, c.child);
                }
                continue;
            }
        }
        // Next from the stack, with the rays not blocked since it was pushed.
        e.rays = 0;
        while (!e.rays && sp > 0) {
            e = stack[--sp];
            e.rays &= live;
        }
        if (!e.rays) return;
    }
}

}  // namespace rt
