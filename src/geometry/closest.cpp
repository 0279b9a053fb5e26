// Closest hit: the BVH traversal for the nearest primitive along a ray (near child
// first, fixed stack), for one ray or a packet of neighbouring rays (rt/geometry/traverse.h).
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "rt/bvh/box_test.h"
#include "rt/bvh/intersect.h"
#include "rt/bvh/node_stack.h"
#include "rt/geometry/leaf_test.h"
#include "rt/geometry/traverse.h"

namespace rt {

using namespace traversal;

namespace {

// The slack of the box limit over the best hit so far (ClosestSearch::box_limit).
constexpr Real kTieSlack = 1 + 64 * std::numeric_limits<Real>::epsilon();

// A child to visit: on the closest-hit traversals' stacks, and the one they visit next.
struct StackEntry {
    int32_t child;   // node index, or ~first for a leaf
    uint16_t count;  // leaf size
    uint16_t rays;   // packet traversal only: the rays that entered it (bit r: ray r)
    BoxReal t;       // entry distance (a packet's: the least of its rays'), to skip entries beyond the best hit
};

// The closest-hit search of one ray: its best hit so far and the limits that
// follow from it. The single-ray traversal and the packet traversal drive it; the
// answer is the hit of least t, ties to the lower id, whichever leaves are tested
// in whichever order, so both give the same hit.
template <bool kCull>
struct ClosestSearch {
    const Scene* s = nullptr;
    RayPre p;
    BoxRay br;
    Real tmin = 0;
    bool found = false;
    Real best_t = 0;
    uint32_t best_id = ~0u;  // primitive id (Geometry::shape_of)
    Real w[3] = {0, 0, 0};   // the last primitive test's weights; spheres leave them untouched
    Real best_w[3] = {0, 0, 0};
    uint32_t part = 0, best_part = 0;  // the last test's instance triangle, and the best hit's
    // Primitive tests accept t <= best_t, so ties reach consider() and are settled by
    // id: their range ends at next_up(best_t), kept here as best_t changes rather than
    // computed for every primitive test.
    Real prim_limit = 0;
    BoxReal box_lim = 0;  // box_limit(), kept here as best_t changes
    const float* best_corners = nullptr;
    uint32_t best_stride = 0;

    void start(const Scene& scene, const Ray& ray, Real t0, Real t1) {
        s = &scene;
        p = prepare(ray);
        tmin = t0;
        best_t = prim_limit = t1;
        box_lim = BoxReal(t1);
        if (!scene.accel.bvh.nodes.empty()) box_ray_into(p, scene.accel.bvh, t0, br);
    }
    [[gnu::always_inline]] void consider(uint32_t gid, Real t, const float* corners, uint32_t stride) {
        // Ties in t go to the lower id, so the answer does not depend on the BVH.
        if (t < best_t || (t == best_t && gid < best_id)) {
            if (t != best_t) prim_limit = next_up(t);
            best_t = t;
            box_lim = BoxReal(t * kTieSlack);
            best_id = gid;
            best_corners = corners;
            best_stride = stride;
            // Shading reads the triangle's record: start loading it while the
            // traversal goes on.
            if (corners) __builtin_prefetch(&s->geometry.triangles[gid]);
            best_w[0] = w[0];
            best_w[1] = w[1];
            best_w[2] = w[2];
            best_part = part;
            found = true;
        }
    }
    // Boxes get more slack: the entry distance of a flat box around a primitive hit at
    // exactly best_t can round a few ulps above it (kTieSlack covers the error of both
    // the slab distances and the triangle's t).
    BoxReal box_limit() const { return box_lim; }
    [[gnu::always_inline]] int test_node(const BvhNode& n, BoxReal t[kWidth]) const {
        return test_boxes(n, br, BoxReal(tmin), box_limit(), t);
    }
    [[gnu::always_inline]] void test_leaf_at(uint32_t first, uint16_t count) {
        test_leaf<kCull, false>(
            *s, p, first, count, tmin, [this] { return prim_limit; }, w, part,
            [this, count](uint32_t id, Real t, const float* corners) {
                consider(id, t, corners, BvhNode::leaf_size_of(count));
                return false;
            });
    }
    // The unbounded shapes, outside the BVH; then the answer into `hit`.
    [[gnu::always_inline]] bool finish(Hit& hit) {
        for_each_shape([&](auto k) {
            using S = decltype(k);
            if constexpr (!S::kBounded) {
                const std::vector<S>& shapes = s->geometry.all<S>();
                const uint32_t base = s->geometry.first_id(kind_of<S>);
                for (size_t i = 0; i < shapes.size(); ++i) {
                    Real t;
                    if (shapes[i].template intersect<kCull, false>(p.ray, tmin, prim_limit, t, w, part))
                        consider(base + static_cast<uint32_t>(i), t, nullptr, 0);
                }
            }
        });
        if (!found) return false;
        hit.t = best_t;
        const ShapeRef shape = s->geometry.shape_of(best_id);
        hit.kind = shape.kind;
        hit.index = shape.index;
        hit.w[0] = best_w[0];
        hit.w[1] = best_w[1];
        hit.w[2] = best_w[2];
        hit.part = best_part;
        hit.corners = best_corners;
        hit.stride = best_stride;
        return true;
    }
};

// The hit children of a node, farthest first, by entry distance t: their count.
inline int order_far_to_near(int mask, const BoxReal t[kWidth], int order[kWidth]) {
    int k = 0;
    while (mask) {
        const int i = __builtin_ctz(mask);
        mask &= mask - 1;
        int j = k++;
        while (j > 0 && t[order[j - 1]] < t[i]) {
            order[j] = order[j - 1];
            --j;
        }
        order[j] = i;
    }
    return k;
}

template <bool kCull>
bool closest(const Scene& s, const Ray& ray, Real tmin, Real tmax, Hit& hit) {
    ClosestSearch<kCull> q;
    q.start(s, ray, tmin, tmax);
    if (!s.accel.bvh.nodes.empty()) {
        StackEntry stack[kStackSize];
        int sp = 0;
        // The nearest hit child is visited next without a trip through the stack;
        // the others are pushed far to near.
        StackEntry e{0, 0, 0, BoxReal(tmin)};
        for (;;) {
            if (e.child < 0) {
                q.test_leaf_at(~static_cast<uint32_t>(e.child), e.count);
            } else {
                const BvhNode& n = s.accel.bvh.nodes[e.child];
                const NodeLinks links(n);
                alignas(kBoxesAlign) BoxReal t[kWidth];
                int order[kWidth];
                const int k = order_far_to_near(q.test_node(n, t), t, order);
                if (k > 0) {
                    for (int j = 0; j + 1 < k; ++j) {
                        const int i = order[j];
                        stack[sp++] = {links.child[i], links.count[i], 0, t[i]};
                        prefetch_node(s.accel.bvh, links.child[i]);
                    }
                    const int i = order[k - 1];
                    e = {links.child[i], links.count[i], 0, t[i]};
                    continue;
                }
            }
            // Next from the stack, skipping entries beyond the best hit so far.
            while (sp > 0 && stack[sp - 1].t > q.box_limit()) --sp;
            if (sp == 0) break;
            e = stack[--sp];
        }
    }
    return q.finish(hit);
}

// The packet traversal: up to kPacket rays walk the tree together, each node and
// leaf loaded once for all of them. Each ray tests a node's boxes itself, enters
// only the children its own test enters and tests only those leaves, so its hit is
// the one closest() finds; the packet visits a child when any of its rays enters it,
// nearest first by the least entry distance among them.
template <bool kCull>
void closest_packet(const Scene& s, const Ray* rays, int n_rays, Real tmin, Real tmax, Hit* hits, bool* found) {
    ClosestSearch<kCull> q[kPacket];
    for (int r = 0; r < n_rays; ++r) q[r].start(s, rays[r], tmin, tmax);
    if (!s.accel.bvh.nodes.empty()) {
        StackEntry stack[kStackSize];
        int sp = 0;
        StackEntry e{0, 0, static_cast<uint16_t>((1u << n_rays) - 1), BoxReal(tmin)};
        for (;;) {
            if (e.child < 0) {
                for (unsigned m = e.rays; m; m &= m - 1)
                    q[__builtin_ctz(m)].test_leaf_at(~static_cast<uint32_t>(e.child), e.count);
            } else {
                const BvhNode& n = s.accel.bvh.nodes[e.child];
                const NodeLinks links(n);
                unsigned child_rays[kWidth] = {};
                BoxReal tc[kWidth];
                int any = 0;
                for (unsigned m = e.rays; m; m &= m - 1) {
                    const int r = __builtin_ctz(m);
                    alignas(kBoxesAlign) BoxReal t[kWidth];
                    const int hit = q[r].test_node(n, t);
                    for (int h = hit; h; h &= h - 1) {
                        const int i = __builtin_ctz(h);
                        tc[i] = (any >> i & 1) ? std::min(tc[i], t[i]) : t[i];
                        child_rays[i] |= 1u << r;
                    }
                    any |= hit;
                }
                int order[kWidth];
                const int k = order_far_to_near(any, tc, order);
                if (k > 0) {
                    for (int j = 0; j + 1 < k; ++j) {
                        const int i = order[j];
                        stack[sp++] = {links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i]), tc[i]};
                        prefetch_node(s.accel.bvh, links.child[i]);
                    }
                    const int i = order[k - 1];
                    e = {links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i]), tc[i]};
                    continue;
                }
            }
            // Next from the stack, with the rays whose best hit so far is not nearer.
            e.rays = 0;
            while (!e.rays && sp > 0) {
                e = stack[--sp];
                unsigned live = 0;
                for (unsigned m = e.rays; m; m &= m - 1) {
                    const int r = __builtin_ctz(m);
                    if (!(e.t > q[r].box_limit())) live |= 1u << r;
                }
                e.rays = static_cast<uint16_t>(live);
            }
            if (!e.rays) break;
        }
    }
    for (int r = 0; r < n_rays; ++r) found[r] = q[r].finish(hits[r]);
}

}  // namespace

bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit) {
    return cull ? closest<true>(scene, ray, tmin, tmax, hit) : closest<false>(scene, ray, tmin, tmax, hit);
}

void closest_hits(const Scene& scene, const Ray* rays, int n, Real tmin, Real tmax, bool cull, Hit* hits, bool* found) {
    if (cull)
        closest_packet<true>(scene, rays, n, tmin, tmax, hits, found);
    else
        closest_packet<false>(scene, rays, n, tmin, tmax, hits, found);
}

}  // namespace rt
