// BVH tests (include/rt/bvh/bvh.h, src/bvh): the scene queries rt::closest_hit and
// rt::any_hit must give exactly the answer of a brute-force loop over every primitive
// (same t to the last bit, same primitive, ties in t going to the lowest primitive id:
// triangles first, then spheres, then planes), and the tree must be well formed.
//
// Scenes: random triangle soups and sphere sets of several sizes and seeds, including
// coincident and overlapping primitives, needles and slivers, exactly degenerate
// triangles and axis-aligned ones; plus the course's official meshes when the shared
// folder is present (shared_dir(): $RT_SHARED_DIR or ../shared).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/bvh/traverse.h"
#include "rt/geometry/intersect.h"
#include "rt/geometry/scene.h"
#include "rt/loader/load_scene.h"
#include "test_support.h"

namespace {

using rt::Real;
using rt::Vec3;
using Rng = std::mt19937_64;

Real uniform(Rng& rng, Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }
size_t pick(Rng& rng, size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }

Vec3 random_unit(Rng& rng) {
    for (;;) {
        const Vec3 v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        const Real l = rt::length(v);
        if (l > Real(0.1) && l <= 1) return v / l;
    }
}

// --- brute force -------------------------------------------------------------------

struct Answer {
    bool found = false;
    Real t = HUGE_VAL;
    uint32_t gid = 0;  // triangles, then spheres, then planes
    Real w[3] = {0, 0, 0};
};

uint32_t global_id(const rt::Scene& s, const rt::Hit& h) {
    switch (h.kind) {
        case rt::ShapeKind::Triangle:
            return h.index;
        case rt::ShapeKind::Sphere:
            return static_cast<uint32_t>(s.geometry.triangles.size()) + h.index;
        case rt::ShapeKind::Plane:
            return static_cast<uint32_t>(s.geometry.triangles.size() + s.geometry.all<rt::Sphere>().size()) + h.index;
    }
    return ~0u;
}

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
    for (size_t i = 0; i < s.geometry.all<rt::Sphere>().size(); ++i, ++gid) {
        Real t;
        if (rt::intersect_sphere(r, s.geometry.all<rt::Sphere>()[i].center, s.geometry.all<rt::Sphere>()[i].radius,
                                 tmin, tmax, t) &&
            t < a.t) {
            a.found = true;
            a.t = t;
            a.gid = gid;
        }
    }
    for (size_t i = 0; i < s.geometry.all<rt::Plane>().size(); ++i, ++gid) {
        Real t;
        if (rt::intersect_plane(r, s.geometry.all<rt::Plane>()[i].point, s.geometry.all<rt::Plane>()[i].normal, tmin,
                                tmax, t) &&
            t < a.t) {
            a.found = true;
            a.t = t;
            a.gid = gid;
        }
    }
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
    for (const rt::Sphere& sp : s.geometry.all<rt::Sphere>())
        if (rt::intersect_sphere(r, sp.center, sp.radius, tmin, tmax, t)) return true;
    for (const rt::Plane& pl : s.geometry.all<rt::Plane>())
        if (rt::intersect_plane(r, pl.point, pl.normal, tmin, tmax, t)) return true;
    return false;
}

std::string describe(const rt::Ray& r, Real tmin, Real tmax) {
    std::ostringstream o;
    o.precision(17);
    o << "ray org (" << r.org.x << ", " << r.org.y << ", " << r.org.z << ") dir (" << r.dir.x << ", " << r.dir.y << ", "
      << r.dir.z << ") t in (" << tmin << ", " << tmax << ")";
    return o.str();
}

// Compares closest_hit (cull on and off) and any_hit with brute force for one ray.
// Returns the number of mismatches (reporting the first few through gtest).
struct Checker {
    const rt::Scene& s;
    int mismatches = 0;
    int hits = 0, queries = 0, closest_queries = 0;

    void fail(const std::string& msg) {
        if (++mismatches <= 8) ADD_FAILURE() << msg;
    }

    void closest(const rt::Ray& r, Real tmin, Real tmax) {
        for (bool cull : {false, true}) {
            ++queries;
            ++closest_queries;
            const Answer want = brute_closest(s, r, tmin, tmax, cull);
            rt::Hit got;
            const bool found = rt::closest_hit(s, r, tmin, tmax, cull, got);
            if (found != want.found) {
                fail(describe(r, tmin, tmax) + (cull ? " cull" : " no cull") + ": closest_hit says " +
                     (found ? "hit" : "miss") + ", brute force says " + (want.found ? "hit" : "miss") +
                     (want.found ? " (id " + std::to_string(want.gid) + ")" : std::string()));
                continue;
            }
            if (!found) continue;
            ++hits;
            const uint32_t gid = global_id(s, got);
            if (got.t != want.t || gid != want.gid) {
                std::ostringstream o;
                o.precision(17);
                o << describe(r, tmin, tmax) << (cull ? " cull" : " no cull") << ": closest_hit id " << gid << " t "
                  << got.t << ", brute force id " << want.gid << " t " << want.t;
                fail(o.str());
                continue;
            }
            if (got.kind == rt::ShapeKind::Triangle &&
                (got.w[0] != want.w[0] || got.w[1] != want.w[1] || got.w[2] != want.w[2]))
                fail(describe(r, tmin, tmax) + ": barycentric weights differ");
        }
    }

    // closest_hits (the packet traversal) against closest_hit, ray by ray, for the
    // rays of one packet: the same answer to the last bit (hit, t, primitive,
    // leaf-order corners, and a triangle's weights: other shapes have none). Rays from random places make packets whose
    // rays part at once; neighbouring camera rays, packets that part at silhouettes.
    void packet(const rt::Ray* rays, int n, Real tmin, Real tmax) {
        for (bool cull : {false, true}) {
            ++queries;
            rt::Hit got[rt::kPacket];
            bool found[rt::kPacket];
            rt::closest_hits(s, rays, n, tmin, tmax, cull, got, found);
            for (int i = 0; i < n; ++i) {
                rt::Hit want;
                const bool want_found = rt::closest_hit(s, rays[i], tmin, tmax, cull, want);
                const std::string where = describe(rays[i], tmin, tmax) + (cull ? " cull" : " no cull") + ", ray " +
                                          std::to_string(i) + " of a packet of " + std::to_string(n);
                if (found[i] != want_found) {
                    fail(where + ": closest_hits says " + (found[i] ? "hit" : "miss") + ", closest_hit " +
                         (want_found ? "hit" : "miss"));
                } else if (want_found &&
                           (got[i].t != want.t || got[i].kind != want.kind || got[i].index != want.index ||
                            got[i].corners != want.corners || got[i].stride != want.stride ||
                            (want.kind == rt::ShapeKind::Triangle &&
                             (got[i].w[0] != want.w[0] || got[i].w[1] != want.w[1] || got[i].w[2] != want.w[2])))) {
                    fail(where + ": closest_hits and closest_hit differ");
                }
            }
        }
    }

    // Closest-hit queries over (0, inf) are also collected into packets of 1, 2, ..
    // kPacket rays in turn (pending), checked by packet(); finish() checks the last one.
    std::vector<rt::Ray> pending = {};
    int next_packet = 1;
    void collect(const rt::Ray& r) {
        pending.push_back(r);
        if (static_cast<int>(pending.size()) == next_packet) finish();
    }
    void finish() {
        if (!pending.empty()) packet(pending.data(), static_cast<int>(pending.size()), 0, HUGE_VAL);
        pending.clear();
        next_packet = next_packet % rt::kPacket + 1;
        finish_any();
    }

    void any(const rt::Ray& r, Real tmin, Real tmax) {
        ++queries;
        const bool want = brute_any(s, r, tmin, tmax);
        if (rt::any_hit(s, r, tmin, tmax) != want)
            fail(describe(r, tmin, tmax) + ": any_hit says " + (want ? "miss" : "hit") + ", brute force says " +
                 (want ? "hit" : "miss"));
        collect_any({r, tmin, tmax, nullptr});
    }

    // any_hits (the packet any-hit traversal) against any_hit, query by query, for one
    // packet of queries. Every other packet's queries share one hint, as the
    // integrator's shadow rays towards one light do: absent at first (kNoOccluder) or a
    // random primitive, then whatever the traversal writes into it.
    uint32_t shared_hint = rt::kNoOccluder;
    int any_packets = 0;
    void any_packet(rt::ShadowQuery* q, int n, Rng& rng) {
        ++queries;
        const size_t prims = s.accel.bvh.prims.size();
        shared_hint = (prims == 0 || pick(rng, 2)) ? rt::kNoOccluder : static_cast<uint32_t>(pick(rng, prims));
        const bool hinted = ++any_packets % 2 == 0;
        for (int i = 0; i < n; ++i) q[i].occluder = hinted ? &shared_hint : nullptr;
        bool got[rt::kPacket];
        rt::any_hits(s, q, n, got);
        for (int i = 0; i < n; ++i) {
            const bool want = rt::any_hit(s, q[i].ray, q[i].tmin, q[i].tmax);
            if (got[i] != want)
                fail(describe(q[i].ray, q[i].tmin, q[i].tmax) + ", query " + std::to_string(i) + " of a packet of " +
                     std::to_string(n) + (hinted ? " (hinted)" : "") + ": any_hits says " + (got[i] ? "hit" : "miss") +
                     ", any_hit " + (want ? "hit" : "miss"));
        }
    }

    // The points where `rays` (a camera packet) first hit the scene, without culling.
    std::vector<Vec3> hit_points(const rt::Ray* rays, int n) const {
        std::vector<Vec3> points;
        for (int i = 0; i < n; ++i) {
            rt::Hit h;
            if (rt::closest_hit(s, rays[i], 0, HUGE_VAL, false, h)) points.push_back(rays[i].org + rays[i].dir * h.t);
        }
        return points;
    }

    // The shadow rays from `points` (at most kPacket) towards `light`, from just off
    // each point: one packet for any_packet.
    void shadow_packet(const std::vector<Vec3>& points, Vec3 light, Rng& rng) {
        rt::ShadowQuery q[rt::kPacket];
        int m = 0;
        for (const Vec3& p : points) {
            const Real d = rt::length(light - p);
            if (d > 0) q[m++] = {{p, (light - p) / d}, Real(1e-4) * d, d, nullptr};
        }
        any_packet(q, m, rng);
    }

    // any() queries are also collected into packets of 1, 2, .. kPacket queries in turn
    // (pending_any), checked by any_packet(); finish() checks the last one.
    std::vector<rt::ShadowQuery> pending_any = {};
    int next_any_packet = 1;
    Rng any_rng{4242};
    void collect_any(const rt::ShadowQuery& q) {
        pending_any.push_back(q);
        if (static_cast<int>(pending_any.size()) == next_any_packet) finish_any();
    }
    void finish_any() {
        if (!pending_any.empty()) any_packet(pending_any.data(), static_cast<int>(pending_any.size()), any_rng);
        pending_any.clear();
        next_any_packet = next_any_packet % rt::kPacket + 1;
    }
};

// --- structure -----------------------------------------------------------------------

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
    } else {
        const rt::Sphere& sp = s.geometry.all<rt::Sphere>()[id - s.geometry.triangles.size()];
        b.extend(sp.center - Vec3{sp.radius, sp.radius, sp.radius});
        b.extend(sp.center + Vec3{sp.radius, sp.radius, sp.radius});
    }
    return b.box;
}

void check_structure(const rt::Scene& s) {
    const rt::Bvh& bvh = s.accel.bvh;
    const size_t n = s.geometry.triangles.size() + s.geometry.all<rt::Sphere>().size();
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

// --- random scenes ---------------------------------------------------------------------

struct SoupSpec {
    uint64_t seed;
    int triangles;
    int spheres;
    int planes;
    Real extent;     // primitives live in [-extent, extent]^3
    Real size;       // typical triangle edge / sphere radius
    bool clustered;  // pile many primitives on top of each other
};

rt::SceneDesc random_scene(const SoupSpec& spec, Rng& rng) {
    rt::SceneDesc d;
    d.path = "/nonexistent/bvh_test.json";
    d.materials.push_back({});
    rt::MeshDesc m;
    auto point = [&]() {
        if (spec.clustered && rng() % 2) {
            // Half the primitives crowd into a small cube, or onto the plane z = 0.
            Vec3 p{uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5), uniform(rng, -0.5, 0.5)};
            if (rng() % 2) p.z = 0;
            return p;
        }
        return Vec3{uniform(rng, -spec.extent, spec.extent), uniform(rng, -spec.extent, spec.extent),
                    uniform(rng, -spec.extent, spec.extent)};
    };
    auto add_tri = [&](Vec3 a, Vec3 b, Vec3 c) {
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), {a, b, c});
        m.indices.insert(m.indices.end(), {base, base + 1, base + 2});
    };
    for (int i = 0; i < spec.triangles; ++i) {
        const int kind = static_cast<int>(rng() % 20);
        const size_t ntri = m.indices.size() / 3;
        if (kind == 0 && ntri > 0) {
            // Exact copy of an earlier triangle (same vertices, same order): an exact tie.
            const size_t j = pick(rng, ntri);
            const Vec3 a = m.positions[m.indices[3 * j]], b = m.positions[m.indices[3 * j + 1]],
                       c = m.positions[m.indices[3 * j + 2]];
            add_tri(a, b, c);
        } else if (kind == 1 && ntri > 0) {
            // Same triangle with its vertices rotated or reversed: same surface, t computed differently.
            const size_t j = pick(rng, ntri);
            const Vec3 a = m.positions[m.indices[3 * j]], b = m.positions[m.indices[3 * j + 1]],
                       c = m.positions[m.indices[3 * j + 2]];
            if (rng() % 2)
                add_tri(b, c, a);
            else
                add_tri(a, c, b);
        } else if (kind == 2) {
            // Needle: two vertices very close.
            const Vec3 a = point(), b = a + random_unit(rng) * spec.size;
            add_tri(a, b, a + random_unit(rng) * (spec.size * Real(1e-7)));
        } else if (kind == 3) {
            // Sliver: the third vertex almost on the line through the other two.
            const Vec3 a = point(), b = a + random_unit(rng) * spec.size;
            add_tri(a, b, a + (b - a) * uniform(rng, 0, 1) + random_unit(rng) * (spec.size * Real(1e-9)));
        } else if (kind == 4) {
            // Exactly degenerate (two equal vertices, or collinear): build_scene drops them.
            const Vec3 a = point(), b = a + random_unit(rng) * spec.size;
            if (rng() % 2)
                add_tri(a, b, a);
            else
                add_tri(a, b, a + (b - a) * Real(2));
        } else if (kind == 5) {
            // Axis-aligned triangle (flat bounding box).
            const Vec3 a = point();
            const int ax = static_cast<int>(rng() % 3);
            Vec3 b = a + random_unit(rng) * spec.size, c = a + random_unit(rng) * spec.size;
            b[ax] = a[ax];
            c[ax] = a[ax];
            add_tri(a, b, c);
        } else if (kind == 6) {
            // Large triangle overlapping many others.
            add_tri(point() * 2, point() * 2, point() * 2);
        } else {
            const Vec3 a = point();
            add_tri(a, a + random_unit(rng) * (spec.size * uniform(rng, 0.1, 1)),
                    a + random_unit(rng) * (spec.size * uniform(rng, 0.1, 1)));
        }
    }
    if (!m.indices.empty()) d.meshes.push_back(m);
    for (int i = 0; i < spec.spheres; ++i) {
        if (i > 0 && rng() % 8 == 0) {
            d.all<rt::Sphere>().push_back(
                d.all<rt::Sphere>()[pick(rng, d.all<rt::Sphere>().size())]);  // coincident: exact tie
        } else {
            rt::SphereDesc sp;
            sp.center = point();
            sp.radius = spec.size * uniform(rng, 0.01, 1);
            d.all<rt::Sphere>().push_back(sp);
        }
    }
    for (int i = 0; i < spec.planes; ++i) {
        rt::PlaneDesc pl;
        pl.point = point() * Real(1.5);
        pl.normal = (i == 0) ? Vec3{0, 0, 1} : random_unit(rng);
        if (i == 0) pl.point = {0, 0, 0};  // coincides with the clustered triangles at z = 0
        d.all<rt::Plane>().push_back(pl);
    }
    return d;
}

// Rays from around the scene: random directions, rays aimed at vertices, edge points,
// interior points and sphere surfaces, axis-aligned rays, and random t intervals.
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

// x rounded to float. Out of line: GCC 12 at -O2 dropped two of three such round
// trips written side by side in one braced assignment (build_scene.cpp, is_float).
[[gnu::noinline]] Real to_float(Real x) { return Real(float(x)); }

// How run_soup's mesh positions are given: as random doubles; rounded to float,
// as a PLY mesh's are, so that leaves read them from Acceleration::leaf_vertices;
// or rounded but for one coordinate in every fourth triangle, so that some leaves
// read the copy and the others (BvhNode::kIndexedLeaf) their triangles' positions.
enum class Vertices { kDouble, kFloat, kMixed };

// Whether the leaf's primitives (prims[first, first + size)) are all triangles,
// and whether all their coordinates are floats exactly as well.
struct LeafKind {
    bool triangles = true, floats = true;
};
LeafKind leaf_kind(const rt::Scene& s, uint32_t first, uint32_t size) {
    LeafKind kind;
    for (uint32_t i = first; i < first + size; ++i) {
        const rt::ShapeRef shape = s.geometry.shape_of(s.accel.bvh.prims[i]);
        if (shape.kind != rt::ShapeKind::Triangle) return {false, false};
        for (uint32_t v : s.geometry.triangles[shape.index].v) {
            const Vec3 p = s.geometry.positions[v];
            if (to_float(p.x) != p.x || to_float(p.y) != p.y || to_float(p.z) != p.z) kind.floats = false;
        }
    }
    return kind;
}

// Coordinate `axis` of vertex k of leaf position first + j in the copy, as a Real.
template <class T>
Real copied(const T* copy, uint32_t first, uint32_t n, uint32_t j, int k, int axis) {
    return Real(copy[rt::LeafVertices::at(first, n, j, k, axis)]);
}

// The leaf-order copy (scene.h, LeafVertices) is in double for scenes of up to
// options.double_copy_max primitives and serves every leaf of triangles, in float
// above and serves exactly the leaves of float triangles; it holds their vertices,
// and exists when it serves some leaf. Returns how many leaves it serves and how
// many there are.
std::pair<size_t, size_t> check_leaf_vertices(const rt::Scene& s, const rt::BvhBuildOptions& options) {
    const float* floats = s.accel.leaf_vertices.floats();
    const double* doubles = s.accel.leaf_vertices.doubles();
    const bool want_doubles = std::is_same_v<Real, double> && s.accel.bvh.prims.size() <= options.double_copy_max;
    size_t servable = 0, leaves = 0;
    for (const rt::BvhNode& nd : s.accel.bvh.nodes)
        for (int k = 0; k < rt::BvhNode::kWidth; ++k) {
            if (!nd.is_leaf(k) || nd.child[k] == rt::BvhNode::kEmpty) continue;
            ++leaves;
            const uint32_t first = ~static_cast<uint32_t>(nd.child[k]), n = nd.leaf_size(k);
            const LeafKind kind = leaf_kind(s, first, n);
            const bool serve = want_doubles ? kind.triangles : kind.floats;
            servable += serve;
            if (!floats && !doubles) continue;
            EXPECT_EQ(!(nd.count[k] & rt::BvhNode::kIndexedLeaf), serve) << "leaf at prims[" << first << "]";
            if (!serve) continue;
            for (uint32_t j = 0; j < n; ++j) {
                const rt::Triangle& t = s.geometry.triangles[s.accel.bvh.prims[first + j]];
                for (int v = 0; v < 3; ++v)
                    for (int a = 0; a < 3; ++a)
                        EXPECT_EQ(doubles ? copied(doubles, first, n, j, v, a) : copied(floats, first, n, j, v, a),
                                  s.geometry.positions[t.v[v]][a])
                            << "prims[" << first + j << "]";
            }
        }
    const bool want_copy = rt::kLeafBlock > 1 && servable > 0;
    EXPECT_EQ(doubles != nullptr, want_copy && want_doubles) << servable << " of " << leaves << " leaves servable";
    EXPECT_EQ(floats != nullptr, want_copy && !want_doubles) << servable << " of " << leaves << " leaves servable";
    return {servable, leaves};
}

// Which leaf-order copy run_soup's scene gets: the default (double for these small
// soups), or float (where the vertices allow).
enum class Copy { kDefault, kFloat };

void run_soup(const SoupSpec& spec, int rays, Vertices vertices = Vertices::kDouble, Copy copy = Copy::kDefault) {
    const char* names[] = {"", ", float vertices", ", float vertices but one coordinate in 4 triangles"};
    SCOPED_TRACE("seed " + std::to_string(spec.seed) + ", " + std::to_string(spec.triangles) + " triangles, " +
                 std::to_string(spec.spheres) + " spheres" + names[int(vertices)] +
                 (copy == Copy::kFloat ? ", float copy" : ""));
    Rng rng(spec.seed);
    rt::SceneDesc d = random_scene(spec, rng);
    if (vertices != Vertices::kDouble)
        for (rt::MeshDesc& m : d.meshes)
            for (size_t i = 0; i < m.indices.size(); ++i) {
                Vec3& p = m.positions[m.indices[i]];
                // kMixed: every fourth triangle keeps one coordinate of one vertex as
                // it is (x, y or z in turn), so that a check skipping one axis shows.
                const size_t tri = i / 3;
                const int keep = vertices == Vertices::kMixed && tri % 4 == 0 && i % 3 == tri / 4 % 3
                                     ? static_cast<int>(tri / 12 % 3)
                                     : -1;
                for (int a = 0; a < 3; ++a)
                    if (a != keep) p[a] = to_float(p[a]);
            }
    rt::BvhBuildOptions options;
    if (copy == Copy::kFloat) options.double_copy_max = 0;
    const rt::Scene s = rt::build_scene(std::move(d), options);
    check_structure(s);
    const auto [served, leaves] = check_leaf_vertices(s, options);
    if (vertices == Vertices::kMixed && copy == Copy::kFloat) {  // both kinds of leaves, or the test says little
        EXPECT_GT(served, 0u);
        // With Real = float every coordinate is a float, so every leaf of triangles only
        // is a float leaf; only double has leaves of non-float triangles to mix in.
        if constexpr (!std::is_same_v<Real, float>) {
            EXPECT_LT(served, leaves);
        }
    }
    Checker ck{s};
    shoot(s, ck, rng, rays, spec.extent);
    ck.finish();
    EXPECT_EQ(ck.mismatches, 0) << "of " << ck.queries << " queries";
    // The rays must actually hit things, or the comparison says little.
    if (!s.geometry.triangles.empty() || !s.geometry.all<rt::Sphere>().empty()) {
        EXPECT_GT(ck.hits, ck.closest_queries / 20);
    }
}

TEST(BvhProperty, TinyScenes) {
    for (uint64_t seed = 1; seed <= 6; ++seed) {
        run_soup({seed, 1, 0, 0, 2, 1, false}, 300);
        run_soup({seed + 100, 0, 1, 0, 2, 1, false}, 300);
        run_soup({seed + 200, 2, 1, 1, 2, 1, false}, 300);
        run_soup({seed + 300, 9, 3, 0, 2, 1, true}, 300);
    }
}

// The SAH prices a leaf as its test goes: triangles in blocks of `block`, other
// shapes (BuildBox::alone) one by one. Four unit boxes 10 apart along x, block 4:
// as triangles a leaf of four costs one block test, less than any split (at least
// the traversal cost 1 plus the children's share), so they stay one leaf; as
// spheres it costs 4, and the split 2 | 2 costs 1 + (46 * 2 + 46 * 2) / 126 = 2.46
// (box areas: both halves 2 (11 + 1 + 11) = 46, all four 2 (31 + 1 + 31) = 126).
TEST(BvhBuild, LeavesPriceSpheresOneByOne) {
    for (const bool alone : {false, true}) {
        SCOPED_TRACE(alone ? "spheres" : "triangles");
        std::vector<rt::BuildBox> boxes;
        for (int i = 0; i < 4; ++i) {
            rt::Box b;
            b.lo[0] = float(10 * i), b.lo[1] = 0, b.lo[2] = 0;
            b.hi[0] = float(10 * i + 1), b.hi[1] = 1, b.hi[2] = 1;
            boxes.push_back(rt::BuildBox::of(b, alone));
        }
        rt::BvhBuildOptions options;
        options.block = 4;
        rt::Bvh bvh;
        bvh.build(boxes.data(), boxes.size(), options);
        ASSERT_EQ(bvh.nodes.size(), 1u);
        uint32_t largest = 0;
        int slots = 0;
        for (int k = 0; k < rt::BvhNode::kWidth; ++k)
            if (bvh.nodes[0].child[k] != rt::BvhNode::kEmpty) {
                ++slots;
                ASSERT_TRUE(bvh.nodes[0].is_leaf(k));
                largest = std::max(largest, bvh.nodes[0].leaf_size(k));
            }
        EXPECT_EQ(slots, alone ? 4 : 1);
        EXPECT_EQ(largest, alone ? 1u : 4u);
    }
}

// The collapse (bvh_build.cpp) merges and takes in nodes but never changes a leaf:
// with and without it the same leaves (range, size, box) over the same primitive
// order; fewer nodes; the node visits the SAH counts (inner slots' areas) no
// more; and no node is left with a child node whose slots would fit in its own.
struct TreeSummary {
    std::vector<std::tuple<uint32_t, uint32_t, std::vector<float>>> leaves;
    double inner_area = 0;
};
TreeSummary summarise(const rt::Bvh& bvh) {
    TreeSummary t;
    for (const rt::BvhNode& n : bvh.nodes)
        for (int k = 0; k < rt::BvhNode::kWidth; ++k) {
            if (n.child[k] == rt::BvhNode::kEmpty) continue;
            rt::Box b;
            for (int a = 0; a < 3; ++a) b.lo[a] = n.lo[a][k], b.hi[a] = n.hi[a][k];
            if (n.is_leaf(k))
                t.leaves.emplace_back(~static_cast<uint32_t>(n.child[k]), n.leaf_size(k),
                                      std::vector<float>{b.lo[0], b.lo[1], b.lo[2], b.hi[0], b.hi[1], b.hi[2]});
            else
                t.inner_area += b.area();
        }
    std::sort(t.leaves.begin(), t.leaves.end());
    return t;
}
int used_slots(const rt::BvhNode& n) {
    int k = 0;
    while (k < rt::BvhNode::kWidth && n.child[k] != rt::BvhNode::kEmpty) ++k;
    return k;
}

TEST(BvhBuild, CollapseKeepsTheLeavesAndFillsTheNodes) {
    for (const bool clustered : {false, true})
        for (const int n : {40, 3000, 40000}) {
            SCOPED_TRACE(std::to_string(n) + (clustered ? " clustered boxes" : " boxes"));
            Rng rng(uint64_t(n) * 7 + clustered);
            std::vector<rt::BuildBox> boxes;
            for (int i = 0; i < n; ++i) {
                const Real c = clustered ? Real(pick(rng, 20)) : 0;
                Vec3 lo{uniform(rng, c, c + 10), uniform(rng, c, c + 10), uniform(rng, -10, 10)};
                const Vec3 hi = lo + Vec3{uniform(rng, 0, 0.5), uniform(rng, 0, 0.5), uniform(rng, 0, 0.5)};
                boxes.push_back(rt::BuildBox::of(rt::Box::around(lo, hi), i % 17 == 0));
            }
            rt::Bvh plain, collapsed;
            rt::BvhBuildOptions off, on;
            off.collapse = false;
            std::vector<rt::BuildBox> copy = boxes;
            plain.build(copy.data(), copy.size(), off);
            copy = boxes;
            collapsed.build(copy.data(), copy.size(), on);

            EXPECT_EQ(collapsed.prims, plain.prims);
            const TreeSummary a = summarise(plain), b = summarise(collapsed);
            EXPECT_TRUE(a.leaves == b.leaves) << a.leaves.size() << " leaves without, " << b.leaves.size() << " with";
            EXPECT_LE(b.inner_area, a.inner_area);
            EXPECT_LE(collapsed.depth, plain.depth);
            if (n >= 3000) {
                EXPECT_LT(collapsed.nodes.size(), plain.nodes.size());
            }
            size_t fits = 0;
            for (const rt::BvhNode& nd : collapsed.nodes)
                for (int k = 0; k < rt::BvhNode::kWidth; ++k)
                    if (nd.child[k] >= 0 &&
                        used_slots(nd) - 1 + used_slots(collapsed.nodes[nd.child[k]]) <= rt::BvhNode::kWidth)
                        ++fits;
            EXPECT_EQ(fits, 0u) << "child nodes that fit in their parent";
        }
}

TEST(BvhProperty, EmptyScene) {
    rt::SceneDesc d;
    d.materials.push_back({});
    const rt::Scene s = rt::build_scene(d);
    check_structure(s);
    rt::Hit h;
    EXPECT_FALSE(rt::closest_hit(s, {{0, 0, 0}, {0, 0, 1}}, 0, HUGE_VAL, false, h));
    EXPECT_FALSE(rt::any_hit(s, {{0, 0, 0}, {0, 0, 1}}, 0, HUGE_VAL));
}

TEST(BvhProperty, MediumSoups) {
    run_soup({11, 100, 20, 1, 5, 1, false}, 2000);
    run_soup({12, 300, 0, 0, 5, 2, true}, 2000);
    run_soup({13, 0, 300, 0, 5, 1, true}, 2000);
    run_soup({14, 500, 100, 2, 3, 1.5, true}, 2000);
}

TEST(BvhProperty, LargeSoups) {
    run_soup({21, 3000, 200, 1, 10, 1, false}, 400);
    run_soup({22, 3000, 500, 2, 10, 0.5, true}, 400);
    run_soup({23, 2000, 0, 0, 1, 0.05, false}, 500);  // small triangles, dense
}

// The same checks with float vertices: leaves read the leaf-order copy.
TEST(BvhProperty, FloatVertexSoups) {
    for (uint64_t seed = 1; seed <= 4; ++seed)
        run_soup({seed + 400, 9, 0, 0, 2, 1, true}, 300, Vertices::kFloat, Copy::kFloat);
    run_soup({31, 500, 0, 2, 3, 1.5, true}, 2000, Vertices::kFloat, Copy::kFloat);
    run_soup({32, 3000, 0, 1, 10, 1, false}, 400, Vertices::kFloat, Copy::kFloat);
    run_soup({33, 2000, 0, 0, 1, 0.05, false}, 500, Vertices::kFloat, Copy::kFloat);
    run_soup({34, 300, 20, 0, 5, 2, false}, 500, Vertices::kFloat, Copy::kFloat);  // spheres' leaves read their ids
}

// With the float copy some leaves read it, the others their primitives' ids; with
// the double copy every leaf of triangles reads it. The same answers.
TEST(BvhProperty, MixedVertexSoups) {
    for (uint64_t seed = 1; seed <= 4; ++seed)
        run_soup({seed + 500, 40, 2, 0, 2, 1, true}, 300, Vertices::kMixed, Copy::kFloat);
    run_soup({41, 3000, 50, 1, 10, 1, false}, 400, Vertices::kMixed, Copy::kFloat);
    run_soup({42, 2000, 0, 0, 1, 0.05, true}, 500, Vertices::kMixed, Copy::kFloat);
    run_soup({43, 3000, 50, 1, 10, 1, false}, 400, Vertices::kMixed);
}

// A jittered height field of float vertices: every inner edge shared by two
// triangles and every inner vertex by six, most leaves full. Leaves test a block of
// triangles at once (kLeafBlock lanes of Real; eight in float with AVX2) from the
// leaf-order copy; the answers must be the scalar test's to the bit (Checker), and
// rays from above through the shared edges and vertices must hit (watertightness).
TEST(BvhProperty, LeafBlocksOnSharedEdges) {
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        SCOPED_TRACE("seed " + std::to_string(seed));
        Rng rng(seed + 900);
        const int n = 12 + 4 * static_cast<int>(seed);  // quads per side
        rt::SceneDesc d;
        d.materials.push_back({});
        rt::MeshDesc m;
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j)
                m.positions.push_back({to_float(i + uniform(rng, Real(-0.3), Real(0.3))),
                                       to_float(uniform(rng, Real(-0.5), Real(0.5))),
                                       to_float(j + uniform(rng, Real(-0.3), Real(0.3)))});
        auto vid = [n](int i, int j) { return static_cast<uint32_t>(i * (n + 1) + j); };
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const uint32_t a = vid(i, j), b = vid(i + 1, j), c = vid(i + 1, j + 1), e = vid(i, j + 1);
                if ((i + j) % 2)
                    m.indices.insert(m.indices.end(), {a, e, c, a, c, b});
                else
                    m.indices.insert(m.indices.end(), {a, e, b, b, e, c});
            }
        d.meshes.push_back(m);
        const rt::Scene s = rt::build_scene(d);
        check_structure(s);
        if (rt::kLeafBlock > 1) {
            EXPECT_TRUE(s.accel.leaf_vertices.floats() != nullptr || s.accel.leaf_vertices.doubles() != nullptr)
                << "the leaves read the leaf-order copy";
        }
        Checker ck{s};
        shoot(s, ck, rng, 3000, Real(n));
        // From above and below, straight and slanted, through shared vertices, through
        // points of shared edges and through the triangles' centres.
        int through = 0, missed = 0;
        for (int k = 0; k < 3000; ++k) {
            const rt::Triangle& tri = s.geometry.triangles[pick(rng, s.geometry.triangles.size())];
            const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]],
                       c = s.geometry.positions[tri.v[2]];
            Vec3 target = k % 3 == 0 ? a : k % 3 == 1 ? a + (b - a) * uniform(rng, 0, 1) : (a + b + c) / Real(3);
            const Vec3 from =
                target + Vec3{uniform(rng, -1, 1), (k % 2 ? 1 : -1) * uniform(rng, 2, 6), uniform(rng, -1, 1)};
            const Vec3 to = target - from;
            const Real dist = rt::length(to);
            const rt::Ray r{from, to / dist};
            ck.closest(r, 0, HUGE_VAL);
            ck.collect(r);
            ck.any(r, 0, HUGE_VAL);
            // Inner vertices and edges only: the border ones may be grazed from outside.
            const Real lim = Real(n) - 1;
            if (target.x > 1 && target.x < lim && target.z > 1 && target.z < lim) {
                ++through;
                rt::Hit h;
                if (!rt::closest_hit(s, r, 0, HUGE_VAL, false, h)) ++missed;
            }
        }
        ck.finish();
        EXPECT_EQ(ck.mismatches, 0) << "of " << ck.queries << " queries";
        EXPECT_GT(ck.hits, ck.closest_queries / 4);
        EXPECT_GT(through, 1000);
        EXPECT_EQ(missed, 0) << "rays through inner edges and vertices that hit nothing, of " << through;
    }
}

TEST(BvhProperty, AllCoincident) {
    // Many copies of one triangle and one sphere: every centroid equal, every hit a tie.
    // The tree must stay shallow and the lowest id must win.
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int i = 0; i < 3000; ++i) m.indices.insert(m.indices.end(), {0, 1, 2});
    d.meshes.push_back(m);
    for (int i = 0; i < 500; ++i) d.all<rt::Sphere>().push_back({{0, "1"}, {0, 0, 5}, 1});
    const rt::Scene s = rt::build_scene(d);
    check_structure(s);
    EXPECT_LE(s.accel.bvh.depth, 64);
    rt::Hit h;
    ASSERT_TRUE(rt::closest_hit(s, {{0, 0, -5}, {0, 0, 1}}, 0, HUGE_VAL, false, h));
    EXPECT_EQ(h.kind, rt::ShapeKind::Triangle);
    EXPECT_EQ(h.index, 0u) << "ties go to the lowest id";
    EXPECT_EQ(h.t, 5);
    ASSERT_TRUE(rt::closest_hit(s, {{0, 0, 10}, {0, 0, -1}}, 0, HUGE_VAL, false, h));
    EXPECT_EQ(h.kind, rt::ShapeKind::Sphere);
    EXPECT_EQ(h.index, 0u) << "ties go to the lowest id";
    EXPECT_EQ(h.t, 4);
    // With culling the triangle seen from below (normal +z, ray going +z) is skipped: sphere.
    ASSERT_TRUE(rt::closest_hit(s, {{0, 0, -5}, {0, 0, 1}}, 0, HUGE_VAL, true, h));
    EXPECT_EQ(h.kind, rt::ShapeKind::Sphere);
    EXPECT_EQ(h.index, 0u);
    Rng rng(5);
    Checker ck{s};
    shoot(s, ck, rng, 300, 2);
    ck.finish();
    EXPECT_EQ(ck.mismatches, 0);
}

TEST(BvhProperty, TiesAcrossKinds) {
    // A triangle, a sphere and a plane meeting the same ray at the same t = 5: the triangle
    // (lowest id) wins; without it the sphere wins; a plane only wins alone.
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc m;
    m.positions = {{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}};
    m.indices = {0, 1, 2};
    d.meshes.push_back(m);
    d.all<rt::Sphere>().push_back({{0, "1"}, {0, 0, 6}, 1});  // near root at z = 5
    d.all<rt::Plane>().push_back({{0, "1"}, {0, 0, 5}, {0, 0, -1}});
    const rt::Ray r{{0, 0, 0}, {0, 0, 1}};
    rt::Hit h;
    {
        const rt::Scene s = rt::build_scene(d);
        ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, false, h));
        EXPECT_EQ(h.kind, rt::ShapeKind::Triangle);
        EXPECT_EQ(h.t, 5);
    }
    d.meshes.clear();
    {
        const rt::Scene s = rt::build_scene(d);
        ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, false, h));
        EXPECT_EQ(h.kind, rt::ShapeKind::Sphere);
        EXPECT_EQ(h.t, 5);
    }
    d.all<rt::Sphere>().clear();
    {
        const rt::Scene s = rt::build_scene(d);
        ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, false, h));
        EXPECT_EQ(h.kind, rt::ShapeKind::Plane);
        EXPECT_EQ(h.t, 5);
    }
}

TEST(BvhProperty, DegenerateTrianglesAreDroppedAndCounted) {
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    m.indices = {0, 1, 2,   // fine
                 0, 1, 1,   // two equal vertices
                 0, 1, 3,   // collinear
                 2, 2, 2};  // a point
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    EXPECT_EQ(s.geometry.triangles.size(), 1u);
    EXPECT_EQ(s.report.degenerate_triangles, 3u);
    check_structure(s);
}

// --- the primitive test's range check, which the traversal's tie-break relies on ------------

// closest_hit finds ties by re-testing primitives with tmax = nextafter(best t), assuming a
// primitive whose computed t equals best t is accepted under that bound. intersect_triangle
// returns t = tz * (1/det) but range-checks tz against tmax * det, and the two roundings can
// disagree: a triangle reporting t is then rejected for tmax = nextafter(t) > t.
TEST(BvhTies, TriangleHitAcceptedJustAboveItsOwnT) {
    // Found by BvhProperty.MediumSoups (seed 11): a ray through a vertex of this triangle.
    const Vec3 a{-1.2331311436806365, 2.1360898993408792, 2.8096520765039621};
    const Vec3 b{-1.6037138142475595, 1.4337523528168155, 2.2327187931589827};
    const Vec3 c{-1.574878894130729, 1.672252642585927, 2.8829608839910494};
    const rt::RayPre p = rt::prepare({{-7.7294426136347125, 13.941085934543516, 8.5342155978832039},
                                      {0.40073682417672546, -0.81821270621081132, -0.41223532738465418}});
    Real t = -1, w[3];
    ASSERT_TRUE(rt::intersect_triangle(p, a, b, c, 0, HUGE_VAL, t, w));
    Real t2 = -1;
    EXPECT_TRUE(rt::intersect_triangle(p, a, b, c, 0, std::nextafter(t, Real(HUGE_VAL)), t2, w))
        << "t = " << t << " lies in (0, nextafter(t)) but the hit is rejected";

    // The same over random triangles and rays aimed at vertices, edges and interiors.
    Rng rng(2024);
    int hits = 0, rejected = 0;
    for (int k = 0; k < 200000; ++k) {
        const Vec3 v0{uniform(rng, -5, 5), uniform(rng, -5, 5), uniform(rng, -5, 5)};
        const Vec3 v1 = v0 + random_unit(rng) * uniform(rng, 0.1, 2), v2 = v0 + random_unit(rng) * uniform(rng, 0.1, 2);
        const Real u = uniform(rng, 0, 1), v = uniform(rng, 0, 1 - u);
        const Vec3 target = (k % 3 == 0) ? v1 : (k % 3 == 1) ? v0 + (v2 - v0) * u : v0 + (v1 - v0) * u + (v2 - v0) * v;
        const Vec3 org = target + random_unit(rng) * uniform(rng, 1, 30);
        const rt::RayPre rp = rt::prepare({org, rt::normalize(target - org)});
        Real th, wh[3];
        if (!rt::intersect_triangle(rp, v0, v1, v2, 0, HUGE_VAL, th, wh)) continue;
        ++hits;
        if (!rt::intersect_triangle(rp, v0, v1, v2, 0, std::nextafter(th, Real(HUGE_VAL)), th, wh)) ++rejected;
    }
    EXPECT_GT(hits, 100000);
    EXPECT_EQ(rejected, 0) << "of " << hits << " hits, rejected with tmax = nextafter(their own t)";
}

// --- the box test: never rejects a box the exact ray enters -----------------------------

// Exact arithmetic for the reference: every product of two doubles (or floats) is exact in
// binary128 (106 of its 113 bits), and the sign of a sum of such products is exact through
// an expansion (Shewchuk's two-sum, error-free in any binary floating point that rounds to
// nearest).
__extension__ typedef __float128 Quad;

int exact_sign(std::initializer_list<Quad> terms) {
    std::vector<Quad> e;  // nonoverlapping, increasing magnitude, no zeros
    for (Quad q : terms) {
        std::vector<Quad> h;
        for (const Quad x : e) {
            const Quad s = q + x, bv = s - q, err = (q - (s - bv)) + (x - bv);
            if (err != 0) h.push_back(err);
            q = s;
        }
        if (q != 0) h.push_back(q);
        e = std::move(h);
    }
    return e.empty() ? 0 : e.back() > 0 ? 1 : -1;
}

// A box (float bounds, as in a node) and a ray with its t range.
struct SlabCase {
    float lo[3], hi[3];
    Vec3 org, dir;
    Real tmin, tmax;
};

// A slab distance (bound - org) / dir, kept as a fraction; bound is exact in binary128
// (a float bound moved by the padding).
struct Frac {
    Quad bound, org, dir;
};

// sign((n.bound - n.org) / n.dir - (f.bound - f.org) / f.dir), exactly. Each bound is a
// float plus or minus the padding, so it is a sum of two terms: split, every product is
// exact.
int compare(const Frac& n, const Frac& f) {
    const int s = (n.dir > 0) == (f.dir > 0) ? 1 : -1;
    return s * exact_sign({n.bound * f.dir, -n.org * f.dir, -f.bound * n.dir, f.org * n.dir});
}
// sign((x.bound - x.org) / x.dir - t), exactly (t finite).
int compare(const Frac& x, Quad t) { return (x.dir > 0 ? 1 : -1) * exact_sign({x.bound, -x.org, -t * x.dir}); }

// Whether the exact ray org + t dir, t in [tmin, tmax], meets the closed box [lo, hi]
// grown by `pad` on every side; `entry` gets the near fractions (the entry is their
// maximum and tmin).
bool exact_enters(const SlabCase& c, Quad pad, std::vector<Frac>* entry = nullptr) {
    std::vector<Frac> nears, fars;
    for (int a = 0; a < 3; ++a) {
        const Quad lo = Quad(c.lo[a]) - pad, hi = Quad(c.hi[a]) + pad;
        if (c.dir[a] == 0) {
            if (!(lo <= Quad(c.org[a]) && Quad(c.org[a]) <= hi)) return false;
            continue;
        }
        const bool pos = c.dir[a] > 0;
        nears.push_back({pos ? lo : hi, Quad(c.org[a]), Quad(c.dir[a])});
        fars.push_back({pos ? hi : lo, Quad(c.org[a]), Quad(c.dir[a])});
    }
    if (c.tmin > c.tmax) return false;
    for (const Frac& f : fars)
        if (compare(f, Quad(c.tmin)) < 0) return false;
    for (const Frac& n : nears) {
        if (std::isfinite(c.tmax) && compare(n, Quad(c.tmax)) > 0) return false;
        for (const Frac& f : fars)
            if (compare(n, f) > 0) return false;
    }
    if (entry) *entry = nears;
    return true;
}

// A value of magnitude around 10^e, either sign.
Real around(Rng& rng, int e) { return (pick(rng, 2) ? 1 : -1) * uniform(rng, 0.5, 2) * std::pow(Real(10), Real(e)); }

// Boxes (flat ones, one float wide ones) near and far from the world origin; rays that
// graze the faces, edges and corners of the box as the test pads it, run along the walls
// of flat boxes, or just miss; zero, tiny and huge direction components; t limits on and
// around the entry. `bvh` gets the box's extent, as for a scene of this one box.
SlabCase random_slab_case(Rng& rng, rt::Bvh& bvh);

// random_slab_case, drawn again until the ray's origin is finite (a tiny direction and a
// long distance can overflow it; the renderer's rays never have such origins).
SlabCase finite_slab_case(Rng& rng, rt::Bvh& bvh) {
    for (;;) {
        const SlabCase c = random_slab_case(rng, bvh);
        if (std::isfinite(c.org.x) && std::isfinite(c.org.y) && std::isfinite(c.org.z)) return c;
    }
}

SlabCase random_slab_case(Rng& rng, rt::Bvh& bvh) {
    SlabCase c;
    const int scale_exp = static_cast<int>(pick(rng, 7)) - 3;  // box sizes 1e-3 .. 1e3
    const int centre_exp = std::vector<int>{0, 0, 3, 6, 10}[pick(rng, 5)];
    for (int a = 0; a < 3; ++a) {
        const Real centre = pick(rng, 4) == 0 ? 0 : around(rng, centre_exp);
        c.lo[a] = rt::round_down_to_float(centre);
        const size_t kind = pick(rng, 4);  // flat, one ulp, sized, sized
        const Real extent = kind <= 1 ? 0 : std::fabs(around(rng, scale_exp));
        c.hi[a] = kind == 1 ? std::nextafter(c.lo[a], HUGE_VALF) : rt::round_up_to_float(c.lo[a] + extent);
    }
    bvh.extent = 0;
    for (int a = 0; a < 3; ++a) bvh.extent = std::max({bvh.extent, std::fabs(c.lo[a]), std::fabs(c.hi[a])});
    Vec3 d = random_unit(rng);
    const size_t dir_kind = pick(rng, 8);
    const int on_boundary = static_cast<int>(pick(rng, 4));  // axes on a bound: 0 inside .. 3 corner
    if (dir_kind == 0) {                                     // along a wall: zero components on bound axes
        for (int a = 0; a < on_boundary && a < 2; ++a) d[a] = pick(rng, 2) ? Real(0) : Real(-0.0);
    } else if (dir_kind == 1) {  // axis-aligned
        const int keep = static_cast<int>(pick(rng, 3));
        for (int a = 0; a < 3; ++a)
            if (a != keep) d[a] = 0;
    } else if (dir_kind == 2) {  // tiny or huge components
        for (int a = 0; a < 3; ++a) {
            const size_t k = pick(rng, 5);
            d[a] *= k == 0 ? Real(1e-30) : k == 1 ? Real(1e30) : k == 2 ? Real(1e-45) : k == 3 ? Real(3e38) : 1;
        }
    } else if (dir_kind == 3) {  // tiny or huge as a whole
        d = d * (pick(rng, 3) == 0 ? Real(1e-30) : pick(rng, 2) ? Real(1e30) : Real(2e38));
    }
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) d[2] = 1;
    // The origin is picked first, some distance back from the box; the padding the test
    // applies for it is known then, and the target point is chosen on the padded box:
    // on a face, an edge, a corner, inside, or a few ulps off a bound.
    const Real len = rt::length(d);
    const Real dist =
        pick(rng, 6) == 0 ? 0 : std::fabs(around(rng, std::vector<int>{-30, -10, -2, 0, 1, 3, 6, 10}[pick(rng, 8)]));
    const Real s = dist / len;
    Vec3 centre;
    for (int a = 0; a < 3; ++a) centre[a] = (Real(c.lo[a]) + Real(c.hi[a])) / 2;
    const Quad pad = Quad(rt::box_padding(bvh, {centre - d * s, d}));
    Vec3 target;
    for (int a = 0; a < 3; ++a) {
        const bool bound = a < on_boundary;
        const bool hi_side = pick(rng, 2);
        Real v = bound ? Real(hi_side ? Quad(c.hi[a]) + pad : Quad(c.lo[a]) - pad) : uniform(rng, c.lo[a], c.hi[a]);
        if (bound && pick(rng, 4) == 0) {  // just outside (or inside) by a few ulps
            for (int k = 1 + static_cast<int>(pick(rng, 3)); k > 0; --k)
                v = std::nextafter(v, pick(rng, 2) ? Real(HUGE_VAL) : Real(-HUGE_VAL));
        }
        target[a] = v;
    }
    // (rounded: the ray passes within rounding of the target, on either side)
    c.org = target - d * s;
    c.dir = d;
    c.tmin = pick(rng, 3) == 0 ? s * uniform(rng, 0, 1) : 0;
    const size_t tk = pick(rng, 5);
    c.tmax = tk == 0   ? Real(HUGE_VAL)
             : tk == 1 ? s
             : tk == 2 ? std::nextafter(s, Real(0))
             : tk == 3 ? s * uniform(rng, 1, 2)
                       : std::nextafter(s, Real(HUGE_VAL));
    if (c.tmax < c.tmin) c.tmax = c.tmin;
    return c;
}

TEST(BvhBoxTest, NeverRejectsABoxTheExactRayEnters) {
    Rng rng(13);
    int entered = 0, rejected = 0, late_entry = 0, lane_mismatch = 0;
    std::string first_failure;
    for (int k = 0; k < 200000; ++k) {
        rt::Bvh bvh;
        const SlabCase c = finite_slab_case(rng, bvh);
        constexpr int kWidth = rt::BvhNode::kWidth;
        rt::BvhNode n;
        for (int i = 0; i < kWidth; ++i) {  // the case's box in every slot but the last (empty)
            for (int a = 0; a < 3; ++a) {
                n.lo[a][i] = i < kWidth - 1 ? c.lo[a] : HUGE_VALF;
                n.hi[a][i] = i < kWidth - 1 ? c.hi[a] : -HUGE_VALF;
            }
            n.child[i] = rt::BvhNode::kEmpty;
            n.count[i] = 0;
        }
        const rt::Ray ray{c.org, c.dir};
        Real t[kWidth], ts[kWidth];
        const int mask = rt::test_node_boxes(bvh, n, ray, c.tmin, c.tmax, t, false);
        const int mask_scalar = rt::test_node_boxes(bvh, n, ray, c.tmin, c.tmax, ts, true);
        if (mask != mask_scalar) ++lane_mismatch;
        for (int i = 0; i < kWidth; ++i)
            if ((mask >> i & 1) && std::memcmp(&t[i], &ts[i], sizeof(Real)) != 0) ++lane_mismatch;
        // Float rays with a direction component above 2^100 are outside the float box
        // test's domain (traverse.cpp, kDirDomain): they enter every slot, empty ones too.
        const Real largest = std::max({std::fabs(c.dir[0]), std::fabs(c.dir[1]), std::fabs(c.dir[2])});
        if (!(std::is_same_v<Real, float> && largest > Real(0x1p100))) {
            EXPECT_EQ(mask >> (kWidth - 1), 0) << "an empty slot was entered";
        }
        std::vector<Frac> nears;
        if (!exact_enters(c, Quad(rt::box_padding(bvh, ray)), &nears)) continue;
        ++entered;
        if (!(mask & 1)) {
            ++rejected;
            if (first_failure.empty()) {
                std::ostringstream os;
                os.precision(17);
                os << "box lo " << c.lo[0] << ' ' << c.lo[1] << ' ' << c.lo[2] << " hi " << c.hi[0] << ' ' << c.hi[1]
                   << ' ' << c.hi[2] << " org " << c.org[0] << ' ' << c.org[1] << ' ' << c.org[2] << " dir " << c.dir[0]
                   << ' ' << c.dir[1] << ' ' << c.dir[2] << " t " << c.tmin << ' ' << c.tmax;
                first_failure = os.str();
            }
            continue;
        }
        // The entry bound: in float at most the exact entry rounded up to a float (the
        // exact entry lies above the float below t); in double at most a factor 1 + 2^-50
        // above it (three roundings), give or take a few subnormals where they underflow.
        constexpr bool kFloat = std::is_same_v<Real, float>;
        const Quad below_t =
            kFloat ? Quad(std::nextafter(float(t[0]), -HUGE_VALF)) : Quad(t[0]) * (1 - Quad(0x1p-50)) - Quad(0x1p-1070);
        const int least = kFloat ? 1 : 0;  // the sign that (entry - below_t) must reach
        bool on_time = (Quad(c.tmin) > below_t) - (Quad(c.tmin) < below_t) >= least;
        for (const Frac& f : nears) on_time = on_time || compare(f, below_t) >= least;
        if (!on_time) ++late_entry;
    }
    EXPECT_GT(entered, 50000) << "too few cases enter their box to test anything";
    EXPECT_EQ(rejected, 0) << "of " << entered << " boxes the exact ray enters; first: " << first_failure;
    EXPECT_EQ(late_entry, 0) << "entry distances above the exact entry";
    EXPECT_EQ(lane_mismatch, 0) << "the SIMD and scalar box tests disagree";
}

// --- official meshes -------------------------------------------------------------------

void check_official(const std::string& rel, int rays, size_t min_triangles) {
    SKIP_UNLESS_SHARED(rel);
    const std::string path = shared_dir() + "/scenes/hw1/" + rel;
    ASSERT_TRUE(file_exists(path)) << path << " is missing from the course's shared folder";
    const rt::Scene s = rt::build_scene(rt::load_scene(path));
    ASSERT_GE(s.geometry.triangles.size(), min_triangles) << path;
    check_structure(s);

    Rng rng(99);
    Checker ck{s};
    // Scene bounds, from the mesh vertices.
    const Real inf = std::numeric_limits<Real>::infinity();
    Vec3 lo{inf, inf, inf}, hi = -lo;
    for (const Vec3& p : s.geometry.positions) {
        lo = rt::vmin(lo, p);
        hi = rt::vmax(hi, p);
    }
    const Vec3 size = hi - lo;
    for (int k = 0; k < rays; ++k) {
        rt::Ray r;
        if (k % 3 == 0) {
            // Camera rays through random pixels.
            const rt::Camera& cam = s.setup.cameras[pick(rng, s.setup.cameras.size())];
            r = cam.primary_ray(static_cast<int>(pick(rng, size_t(cam.width))),
                                static_cast<int>(pick(rng, size_t(cam.height))));
        } else {
            const Vec3 org{lo.x + size.x * uniform(rng, -0.5, 1.5), lo.y + size.y * uniform(rng, -0.5, 1.5),
                           lo.z + size.z * uniform(rng, -0.5, 1.5)};
            Vec3 target;
            if (k % 3 == 1) {
                target = s.geometry.positions[pick(rng, s.geometry.positions.size())];  // through a vertex
            } else {
                const rt::Triangle& tri = s.geometry.triangles[pick(rng, s.geometry.triangles.size())];
                const Vec3 a = s.geometry.positions[tri.v[0]], b = s.geometry.positions[tri.v[1]];
                target = a + (b - a) * uniform(rng, 0, 1);  // through an edge
            }
            const Vec3 d = target - org;
            if (!(rt::length(d) > 0)) continue;
            r = {org, rt::normalize(d)};
        }
        ck.closest(r, 0, HUGE_VAL);
        ck.collect(r);
        if (k % 3 == 0) {
            // The camera rays of the pixel and the next ones in its row (up to kPacket): a
            // coherent packet; and the 4 x 4 pixels from it, the renderer's packet (render.cpp).
            const rt::Camera& cam = s.setup.cameras[0];
            const int x = static_cast<int>(pick(rng, size_t(cam.width))),
                      y = static_cast<int>(pick(rng, size_t(cam.height)));
            rt::Ray row[rt::kPacket];
            int n = 0;
            for (; n < rt::kPacket && x + n < cam.width; ++n) row[n] = cam.primary_ray(x + n, y);
            ck.packet(row, n, 0, HUGE_VAL);
            n = 0;
            for (int py = y; py < std::min(y + 4, cam.height); ++py)
                for (int px = x; px < std::min(x + 4, cam.width); ++px) row[n++] = cam.primary_ray(px, py);
            ck.packet(row, n, 0, HUGE_VAL);
            const std::vector<Vec3> points = ck.hit_points(row, n);
            for (const rt::PointLight& light : s.setup.lights) ck.shadow_packet(points, light.position, rng);
        }
        ck.any(r, 0, HUGE_VAL);
        const Real span = rt::length(size);
        const Real tmin = uniform(rng, 0, span), tmax = tmin + uniform(rng, 0, span);
        ck.any(r, tmin, tmax);
    }
    ck.finish();
    EXPECT_EQ(ck.mismatches, 0) << "of " << ck.queries << " queries on " << path;
    EXPECT_GT(ck.hits, ck.closest_queries / 20) << path;
}

TEST(BvhOfficial, Bunny) { check_official("bunny.json", 300, 4000); }

TEST(BvhOfficial, TonRoosendaal) { check_official("akif_uslu/ton_Roosendaal_smooth.json", 60, 10000); }

// Axis-aligned walls (flat boxes) and spheres.
TEST(BvhOfficial, CornellBox) { check_official("cornellbox.json", 600, 10); }

}  // namespace
