// The BVH tests' shared helpers (bvh_test_support.h): the brute force, the structural
// check of a tree, and the rays shot from around a scene.
#include "bvh_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"
#include "rt/geometry/scene.h"
#include "rt/geometry/traverse.h"

namespace bvh_test {

Vec3 random_unit(Rng& rng) {
    for (;;) {
        const Vec3 v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        const Real l = rt::length(v);
        if (l > Real(0.1) && l <= 1) return v / l;
    }
}

uint32_t global_id(const rt::Scene& s, const rt::Hit& h) {
    uint32_t id = static_cast<uint32_t>(s.geometry.triangles.size()), found = h.index;
    rt::for_each_shape([&](auto k) {
        using S = decltype(k);
        if (h.kind == rt::kind_of<S>) found = id + h.index;
        id += static_cast<uint32_t>(s.geometry.all<S>().size());
    });
    return found;
}

namespace {

// Whether the brute force takes the renderer's own predicates for culling and for
// shadow rays. In double it does not: it culls by the sign of dot(dir, normal) and
// counts every hit, and the renderer must agree. In float, grazing rays (the tests'
// rays through vertices, along edges and from a triangle's centre) make both
// differences real: dot(dir, normal) and the edge functions that cull
// (inside_edges) are each within float rounding of 0 and may disagree in sign, and
// a shadow ray's t may lie within its own rounding bound, which any_hit ignores by
// design (intersect.h, triangle_hit). The brute force then asks the same
// questions, so the comparison still tests that the BVH finds what they find.
constexpr bool kSamePredicates = std::is_same_v<Real, float>;

bool brute_triangle(const rt::Scene& s, const rt::RayPre& p, size_t i, bool cull, Real tmin, Real tmax, Real& t,
                    Real w[3]) {
    const rt::Triangle& tri = s.geometry.triangles[i];
    const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]],
               c = s.geometry.positions[tri.v[2]];
    if constexpr (kSamePredicates) {
        return cull ? rt::intersect_triangle<true>(p, a, b, c, tmin, tmax, t, w)
                    : rt::intersect_triangle(p, a, b, c, tmin, tmax, t, w);
    }
    if (cull && rt::dot(p.ray.dir, s.geometry.face_normal(static_cast<uint32_t>(i))) > 0) return false;
    return rt::intersect_triangle(p, a, b, c, tmin, tmax, t, w);
}

}  // namespace

Answer brute_closest(const rt::Scene& s, const rt::Ray& r, Real tmin, Real tmax, bool cull) {
    Answer a;
    const rt::RayPre p = rt::prepare(r);
    uint32_t gid = 0;
    for (size_t i = 0; i < s.geometry.triangles.size(); ++i, ++gid) {
        Real t, w[3];
        if (brute_triangle(s, p, i, cull, tmin, tmax, t, w) && t < a.t) {
            a.found = true;
            a.t = t;
            a.gid = gid;
            std::copy(w, w + 3, a.w);
        }
    }
    // Every other kind of the registry, by its own ray test, in id order.
    rt::for_each_shape([&](auto k) {
        using S = decltype(k);
        for (const S& shape : s.geometry.all<S>()) {
            Real t, w[3];
            uint32_t part = 0;
            const bool hit = cull ? shape.template intersect<true, false>(r, tmin, tmax, t, w, part)
                                  : shape.template intersect<false, false>(r, tmin, tmax, t, w, part);
            if (hit && t < a.t) {
                a.found = true;
                a.t = t;
                a.gid = gid;
            }
            ++gid;
        }
    });
    return a;
}

bool brute_any(const rt::Scene& s, const rt::Ray& r, Real tmin, Real tmax) {
    const rt::RayPre p = rt::prepare(r);
    Real t, w[3];
    for (const rt::Triangle& tri : s.geometry.triangles) {
        const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]],
                   c = s.geometry.positions[tri.v[2]];
        if (kSamePredicates ? rt::intersect_triangle<false, true>(p, a, b, c, tmin, tmax, t, w)
                            : rt::intersect_triangle(p, a, b, c, tmin, tmax, t, w))
            return true;
    }
    bool any = false;
    rt::for_each_shape([&](auto k) {
        for (const auto& shape : s.geometry.all<decltype(k)>()) {
            uint32_t part = 0;
            any = any || shape.template intersect<false, true>(r, tmin, tmax, t, w, part);
        }
    });
    return any;
}

std::string describe(const rt::Ray& r, Real tmin, Real tmax) {
    std::ostringstream o;
    o.precision(17);
    o << "ray org (" << r.org.x << ", " << r.org.y << ", " << r.org.z << ") dir (" << r.dir.x << ", " << r.dir.y << ", "
      << r.dir.z << ") t in (" << tmin << ", " << tmax << ")";
    return o.str();
}

// --- structure -----------------------------------------------------------------------

namespace {

// The smallest float box around Real points (a float bound below or above a Real
// coordinate is also one below or above this box's).
struct PointBox {
    rt::Box box;
    void extend(Vec3 p) { box.extend(rt::Box::around(p, p)); }
};

rt::Box prim_bounds(const rt::Scene& s, uint32_t id) {
    PointBox b;
    if (id < s.geometry.triangles.size()) {
        for (uint32_t v : s.geometry.triangles[id].v) b.extend(s.geometry.positions[v]);
        return b.box;
    }
    // The bounded kinds follow the triangles in id order; each kind's own bounds.
    size_t first = s.geometry.triangles.size();
    rt::Box box;
    rt::for_each_shape([&](auto k) {
        using S = decltype(k);
        if constexpr (S::kBounded) {
            const std::vector<S>& all = s.geometry.all<S>();
            if (id >= first && id - first < all.size()) box = all[id - first].bounds();
            first += all.size();
        }
    });
    return box;
}

}  // namespace

void check_structure(const rt::Scene& s) {
    const rt::Bvh& bvh = s.accel.bvh;
    size_t n = s.geometry.triangles.size();
    rt::for_each_shape([&](auto k) {
        if constexpr (decltype(k)::kBounded) n += s.geometry.all<decltype(k)>().size();
    });
    ASSERT_EQ(bvh.prims.size(), n);
    if (n == 0) {
        EXPECT_TRUE(bvh.nodes.empty());
        return;
    }
    ASSERT_FALSE(bvh.nodes.empty());
    // Every primitive id appears exactly once.
    std::vector<int> seen(n, 0);
    for (uint32_t id : bvh.prims) {
        ASSERT_LT(id, n);
        ++seen[id];
    }
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i], 1) << "primitive " << i;

    // Walk the tree: each node reached once, leaves cover bvh.prims exactly once,
    // each slot's box contains its primitives or its child node's slot boxes.
    std::vector<int> reached(bvh.nodes.size(), 0), covered(n, 0);
    struct Item {
        uint32_t node;
        int level;
    };
    std::vector<Item> stack{{0, 1}};
    int levels = 0;
    size_t bad_boxes = 0;
    while (!stack.empty()) {
        const Item it = stack.back();
        stack.pop_back();
        ASSERT_LT(it.node, bvh.nodes.size());
        ASSERT_EQ(reached[it.node]++, 0) << "node " << it.node << " reached twice";
        levels = std::max(levels, it.level);
        ASSERT_LE(it.level, 64) << "tree too deep";
        const rt::BvhNode& nd = bvh.nodes[it.node];
        int used = 0;
        for (int k = 0; k < rt::BvhNode::kWidth; ++k) {
            if (nd.child[k] == rt::BvhNode::kEmpty) {
                EXPECT_EQ(nd.count[k], 0) << "empty slot with primitives at node " << it.node;
                continue;
            }
            ++used;
            for (int a = 0; a < 3; ++a) ASSERT_LE(nd.lo[a][k], nd.hi[a][k]) << "inverted box at node " << it.node;
            if (nd.is_leaf(k)) {
                const uint32_t first = ~static_cast<uint32_t>(nd.child[k]);
                ASSERT_GT(nd.leaf_size(k), 0u) << "empty leaf at node " << it.node;
                ASSERT_LE(size_t(first) + nd.leaf_size(k), n);
                for (uint32_t i = first; i < first + nd.leaf_size(k); ++i) {
                    ++covered[i];
                    const rt::Box b = prim_bounds(s, bvh.prims[i]);
                    for (int a = 0; a < 3; ++a)
                        if (!(Real(nd.lo[a][k]) <= b.lo[a] && b.hi[a] <= Real(nd.hi[a][k]))) ++bad_boxes;
                }
            } else {
                const uint32_t c = static_cast<uint32_t>(nd.child[k]);
                ASSERT_LT(c, bvh.nodes.size()) << "child index out of range at node " << it.node;
                const rt::BvhNode& ch = bvh.nodes[c];
                for (int j = 0; j < rt::BvhNode::kWidth; ++j) {
                    if (ch.child[j] == rt::BvhNode::kEmpty) continue;
                    for (int a = 0; a < 3; ++a)
                        if (!(nd.lo[a][k] <= ch.lo[a][j] && ch.hi[a][j] <= nd.hi[a][k])) ++bad_boxes;
                }
                stack.push_back({c, it.level + 1});
            }
        }
        EXPECT_GE(used, it.node == 0 ? 1 : 2) << "node " << it.node << " has too few children";
    }
    EXPECT_EQ(bad_boxes, 0u) << "boxes that do not contain their children or primitives";
    for (size_t i = 0; i < n; ++i) ASSERT_EQ(covered[i], 1) << "bvh.prims[" << i << "] in " << covered[i] << " leaves";
    for (size_t i = 0; i < bvh.nodes.size(); ++i) EXPECT_EQ(reached[i], 1) << "node " << i << " unreachable";
    EXPECT_LE(levels, 64);
    EXPECT_LE(bvh.depth, 64) << "the recorded depth";
}

void shoot(const rt::Scene& s, Checker& ck, Rng& rng, int rays, Real extent) {
    const Real far = extent * 3;
    for (int k = 0; k < rays; ++k) {
        Vec3 org{uniform(rng, -far, far), uniform(rng, -far, far), uniform(rng, -far, far)};
        if (k % 7 == 0) org = org * Real(0.2);  // often inside the crowd
        Vec3 dir;
        // 0: random direction; 1-3: aimed at a triangle's vertex, edge or interior (at a sphere
        // when there are no triangles); 4: at a sphere's surface (a triangle when there are no
        // spheres); 5: axis-aligned.
        int mode = k % 6;
        if (s.geometry.triangles.empty() && s.geometry.all<rt::Sphere>().empty())
            mode = (mode == 5) ? 5 : 0;
        else if (mode >= 1 && mode <= 3 && s.geometry.triangles.empty())
            mode = 4;
        else if (mode == 4 && s.geometry.all<rt::Sphere>().empty())
            mode = 3;
        if (mode == 0) {
            dir = random_unit(rng);
        } else if (mode <= 3) {
            const rt::Triangle& tri = s.geometry.triangles[pick(rng, s.geometry.triangles.size())];
            const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]],
                       c = s.geometry.positions[tri.v[2]];
            Vec3 target;
            if (mode == 1) {
                target = (rng() % 2) ? a : b;  // vertex
            } else if (mode == 2) {
                target = a + (b - a) * uniform(rng, 0, 1);  // edge
            } else {
                Real u = uniform(rng, 0, 1), v = uniform(rng, 0, 1);
                if (u + v > 1) u = 1 - u, v = 1 - v;
                target = a + (b - a) * u + (c - a) * v;  // interior
            }
            dir = target - org;
        } else if (mode == 4) {
            const rt::Sphere& sp = s.geometry.all<rt::Sphere>()[pick(rng, s.geometry.all<rt::Sphere>().size())];
            dir = sp.center + random_unit(rng) * sp.radius - org;
        } else {
            // Axis-aligned (two zero components; sometimes negative zeros).
            const int ax = static_cast<int>(rng() % 3);
            dir = {(rng() % 2) ? Real(0) : Real(-0.0), (rng() % 2) ? Real(0) : Real(-0.0),
                   (rng() % 2) ? Real(0) : Real(-0.0)};
            dir[ax] = (rng() % 2) ? 1 : -1;
        }
        const Real len = rt::length(dir);
        if (!(len > 0)) continue;
        const rt::Ray r{org, dir / len};
        ck.closest(r, 0, HUGE_VAL);
        ck.collect(r);
        // Random intervals, for both queries.
        const Real tmin = (rng() % 3 == 0) ? Real(0) : uniform(rng, 0, far);
        const Real tmax = (rng() % 4 == 0) ? Real(HUGE_VAL) : tmin + uniform(rng, 0, far);
        ck.closest(r, tmin, tmax);
        ck.any(r, 0, HUGE_VAL);
        ck.any(r, tmin, tmax);
        // Shadow-ray style: from a surface point towards a random point, the interval ending there.
        if (!s.geometry.triangles.empty() && k % 2 == 0) {
            const rt::Triangle& tri = s.geometry.triangles[pick(rng, s.geometry.triangles.size())];
            const Vec3 p =
                (s.geometry.positions[tri.v[0]] + s.geometry.positions[tri.v[1]] + s.geometry.positions[tri.v[2]]) /
                Real(3);
            const Vec3 to = org - p;
            const Real d = rt::length(to);
            if (d > 0) ck.any({p, to / d}, Real(1e-3), d);
        }
    }
}

}  // namespace bvh_test
