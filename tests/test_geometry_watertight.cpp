// Geometry tests, watertightness: a property of the scene query rt::closest_hit on jittered
// meshes (a grid, a closed cube sphere): rays from random origins through shared edges and
// vertices never slip between the triangles, bar the silhouettes where a miss is right.
//
// Random tests use fixed seeds, so every run shoots the same rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "geometry_test_support.h"
#include "rt/core/math.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/scene_desc.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace geometry_test;

// --- watertightness property --------------------------------------------------------

using Rng = std::mt19937_64;

Real uniform(Rng& rng, Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }

Vec3 random_unit(Rng& rng) {
    for (;;) {
        const Vec3 v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        const Real l = rt::length(v);
        if (l > Real(0.1) && l <= 1) return v / l;
    }
}

// Topology of a consistently oriented triangle mesh: its shared edges with the two
// vertices opposite them, and each vertex's link (the far edge of every incident triangle,
// in the triangle's winding).
struct Topology {
    struct Edge {
        uint32_t a, b;  // the edge
        uint32_t c, d;  // opposite vertices of the two triangles sharing it
    };
    std::vector<Edge> shared;
    std::vector<std::vector<std::pair<uint32_t, uint32_t>>> link;  // per vertex
    bool consistent = true;                                        // every shared edge is used once in each direction
};

Topology topology(const std::vector<uint32_t>& idx, size_t nverts) {
    Topology topo;
    topo.link.resize(nverts);
    std::map<std::pair<uint32_t, uint32_t>, std::vector<std::pair<bool, uint32_t>>> uses;  // (fwd, opposite)
    for (size_t f = 0; f < idx.size(); f += 3)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = idx[f + e], b = idx[f + (e + 1) % 3], c = idx[f + (e + 2) % 3];
            uses[{std::min(a, b), std::max(a, b)}].push_back({a < b, c});
            topo.link[a].push_back({b, c});
        }
    for (const auto& [k, u] : uses) {
        if (u.size() != 2) continue;
        if (u[0].first == u[1].first) topo.consistent = false;
        topo.shared.push_back({k.first, k.second, u[0].second, u[1].second});
    }
    return topo;
}

// How clearly a configuration must be away from a silhouette for the watertightness property
// to apply: rays aimed at a point only pass within rounding error of it.
const Real kMargin = sizeof(Real) == sizeof(double) ? Real(1e-6) : Real(1e-3);

// Could a ray from `o` through a point of edge e legitimately miss both triangles? Only
// when the edge is on the silhouette seen from o: both opposite vertices on the same
// side of the plane through o and the edge (or too close to it to tell).
bool edge_is_silhouette(const std::vector<Vec3>& pos, const Topology::Edge& e, Vec3 o) {
    const Vec3 n = rt::cross(pos[e.a] - o, pos[e.b] - o);
    const Real sc = rt::dot(n, pos[e.c] - o), sd = rt::dot(n, pos[e.d] - o);
    const Real scale = rt::length(n) * kMargin;
    return !(sc * sd < 0 && std::fabs(sc) > scale && std::fabs(sd) > scale);
}

// Does the fan around vertex v, seen along `dir`, wind once around v (so that every ray
// close to v along dir crosses it)? Signed angles of the link edges, projected onto the
// plane perpendicular to dir, must add up to +-2 pi.
bool vertex_is_covered(const std::vector<Vec3>& pos, const Topology& topo, uint32_t v, Vec3 dir) {
    const Vec3 helper = std::fabs(dir.x) < Real(0.6) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    const Vec3 e1 = rt::normalize(rt::cross(dir, helper)), e2 = rt::cross(dir, e1);
    Real sum = 0;
    for (const auto& [p, q] : topo.link[v]) {
        const Vec3 P = pos[p] - pos[v], Q = pos[q] - pos[v];
        const Real px = rt::dot(P, e1), py = rt::dot(P, e2), qx = rt::dot(Q, e1), qy = rt::dot(Q, e2);
        if (std::hypot(px, py) < kMargin || std::hypot(qx, qy) < kMargin) return false;
        const Real ang = std::atan2(px * qy - py * qx, px * qx + py * qy);
        if (std::fabs(std::fabs(ang) - rt::kPi) < kMargin) return false;  // edge through v
        sum += ang;
    }
    return std::fabs(sum) > rt::kPi;
}

// Shoots rays from random origins through random points on shared edges and through the
// given vertices, skipping the silhouette cases where a miss is legitimate. Every other
// ray must hit a triangle around the aimed-at point, or something in front of it.
// `s` must hold exactly the one mesh whose positions are `pos` (so triangle vertex ids are
// the mesh's own). Returns the rays shot.
int shoot_through_edges_and_vertices(const rt::Scene& s, const std::vector<Vec3>& pos, const Topology& topo,
                                     const std::vector<uint32_t>& vertices, Rng& rng, int rays,
                                     const std::function<Vec3(Rng&, Vec3)>& make_origin) {
    int misses = 0, shot = 0, skipped = 0;
    for (int k = 0; k < rays; ++k) {
        Vec3 target, org;
        bool fair;
        uint32_t must_have[2];  // vertices of the aimed-at edge, or the vertex twice
        if (k % 3 == 2) {
            const uint32_t v = vertices[std::uniform_int_distribution<size_t>(0, vertices.size() - 1)(rng)];
            target = pos[v];
            org = make_origin(rng, target);
            fair = vertex_is_covered(pos, topo, v, rt::normalize(target - org));
            must_have[0] = must_have[1] = v;
        } else {
            const Topology::Edge& e =
                topo.shared[std::uniform_int_distribution<size_t>(0, topo.shared.size() - 1)(rng)];
            const Real f = uniform(rng, 0, 1);
            target = pos[e.a] + (pos[e.b] - pos[e.a]) * f;
            org = make_origin(rng, target);
            fair = !edge_is_silhouette(pos, e, org);
            must_have[0] = e.a;
            must_have[1] = e.b;
        }
        if (!fair) {
            ++skipped;
            continue;
        }
        const Vec3 to = target - org;
        const Real dist = rt::length(to);
        const rt::Ray ray{org, to / dist};
        rt::Hit h;
        ++shot;
        const bool hit = rt::closest_hit(s, ray, 0, HUGE_VAL, false, h);
        // The hit must be one of the triangles around the aimed-at edge or vertex (the ray passes
        // within rounding error of it, so at grazing angles it may meet them a little past the
        // target), or something in front of the target.
        bool around = false;
        if (hit && h.kind == rt::ShapeKind::Triangle) {
            const uint32_t* tv = s.geometry.triangles[h.index].v;
            auto has = [&](uint32_t v) { return tv[0] == v || tv[1] == v || tv[2] == v; };
            around = has(must_have[0]) && has(must_have[1]);
        }
        if (!hit || !(around || h.t <= dist * (1 + kLoose))) {
            if (++misses <= 5)
                ADD_FAILURE() << "ray " << k << " from (" << org.x << ", " << org.y << ", " << org.z << ") through ("
                              << target.x << ", " << target.y << ", " << target.z << ") "
                              << (hit ? "hit too far, t = " + std::to_string(h.t) : std::string("missed"))
                              << ", distance " << dist;
        }
    }
    EXPECT_EQ(misses, 0) << "of " << shot << " rays";
    // The filter must leave most rays in, or the property says little.
    EXPECT_GT(shot, rays / 2) << skipped << " silhouette rays skipped";
    return shot;
}

TEST(GeometryWatertight, JitteredGridThroughEdgesAndVertices) {
    Rng rng(20251029);
    const int n = 20;  // 20 x 20 cells, 21 x 21 vertices
    rt::MeshDesc m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.push_back(
                {Real(i) + uniform(rng, -0.3, 0.3), Real(j) + uniform(rng, -0.3, 0.3), uniform(rng, -0.5, 0.5)});
    auto id = [&](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
            if (rng() & 1)
                m.indices.insert(m.indices.end(), {a, b, c, a, c, e});  // diagonal a-c
            else
                m.indices.insert(m.indices.end(), {a, b, e, b, c, e});  // diagonal b-e
        }
    rt::SceneDesc d = empty_desc();
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    ASSERT_EQ(s.geometry.triangles.size(), size_t(2 * n * n));
    ASSERT_EQ(s.report.degenerate_triangles, 0u);

    const Topology topo = topology(m.indices, m.positions.size());
    ASSERT_TRUE(topo.consistent);
    ASSERT_EQ(topo.shared.size(), size_t(3 * n * n - 2 * n));  // 2n(n+1) + n^2 edges minus 4n on the border
    std::vector<uint32_t> inner;
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) inner.push_back(id(i, j));

    // Origins above and below the sheet, at random angles (grazing ones included).
    auto origin = [](Rng& r, Vec3 target) {
        Vec3 dir = random_unit(r);
        return target + dir * uniform(r, 0.5, 40);
    };
    shoot_through_edges_and_vertices(s, m.positions, topo, inner, rng, 30000, origin);
}

TEST(GeometryWatertight, JitteredGridAxisAlignedRays) {
    // Axis-aligned directions make several ray components zero (infinite inv_dir): the
    // shear and the slab test must still be watertight.
    Rng rng(7);
    const int n = 20;
    rt::MeshDesc m;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i)
            m.positions.push_back(
                {Real(i) + uniform(rng, -0.3, 0.3), Real(j) + uniform(rng, -0.3, 0.3), uniform(rng, -0.5, 0.5)});
    auto id = [&](int i, int j) { return static_cast<uint32_t>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            const uint32_t a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), e = id(i, j + 1);
            m.indices.insert(m.indices.end(), {a, b, c, a, c, e});
        }
    rt::SceneDesc d = empty_desc();
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    const Topology topo = topology(m.indices, m.positions.size());
    ASSERT_TRUE(topo.consistent);
    std::vector<uint32_t> inner;
    for (int j = 1; j < n; ++j)
        for (int i = 1; i < n; ++i) inner.push_back(id(i, j));
    auto origin = [](Rng& r, Vec3 target) {
        // Straight down or straight up onto the target.
        return target + Vec3{0, 0, (r() & 1) ? Real(5) : Real(-5)};
    };
    shoot_through_edges_and_vertices(s, m.positions, topo, inner, rng, 6000, origin);
}

// A closed, star-shaped mesh: a cube with k x k cells per face, projected onto the unit
// sphere, each vertex's radius jittered by up to +-8%. Vertices are shared between faces.
rt::MeshDesc jittered_cube_sphere(int k, Rng& rng) {
    rt::MeshDesc m;
    std::map<std::tuple<int, int, int>, uint32_t> ids;
    auto vertex = [&](int x, int y, int z) {  // lattice coordinates in [0, k]
        auto [it, inserted] = ids.emplace(std::make_tuple(x, y, z), static_cast<uint32_t>(m.positions.size()));
        if (inserted) {
            const Vec3 p{Real(2 * x - k) / k, Real(2 * y - k) / k, Real(2 * z - k) / k};
            m.positions.push_back(rt::normalize(p) * (1 + uniform(rng, -0.08, 0.08)));
        }
        return it->second;
    };
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side <= k; side += k)
            for (int a = 0; a < k; ++a)
                for (int b = 0; b < k; ++b) {
                    auto lattice = [&](int u, int v) {
                        int c[3];
                        c[axis] = side;
                        c[(axis + 1) % 3] = u;
                        c[(axis + 2) % 3] = v;
                        return vertex(c[0], c[1], c[2]);
                    };
                    uint32_t q[4] = {lattice(a, b), lattice(a + 1, b), lattice(a + 1, b + 1), lattice(a, b + 1)};
                    uint32_t tri[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
                    if ((a + b) & 1) {
                        tri[0][0] = q[0], tri[0][1] = q[1], tri[0][2] = q[3];
                        tri[1][0] = q[1], tri[1][1] = q[2], tri[1][2] = q[3];
                    }
                    for (auto& t : tri) {
                        const Vec3 p0 = m.positions[t[0]], p1 = m.positions[t[1]], p2 = m.positions[t[2]];
                        // Outward (CCW seen from outside): flip when the normal points at the centre.
                        if (rt::dot(rt::cross(p1 - p0, p2 - p0), p0 + p1 + p2) < 0) std::swap(t[1], t[2]);
                        m.indices.insert(m.indices.end(), {t[0], t[1], t[2]});
                    }
                }
    return m;
}

TEST(GeometryWatertight, ClosedMeshThroughEdgesAndVertices) {
    Rng rng(42);
    const int k = 8;
    const rt::MeshDesc m = jittered_cube_sphere(k, rng);
    ASSERT_EQ(m.positions.size(), size_t(6 * k * k + 2));  // Euler: V = F/2 + 2 with F = 12 k^2
    rt::SceneDesc d = empty_desc();
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    ASSERT_EQ(s.geometry.triangles.size(), size_t(12 * k * k));
    const Topology topo = topology(m.indices, m.positions.size());
    ASSERT_TRUE(topo.consistent) << "the test mesh must be consistently oriented";
    ASSERT_EQ(topo.shared.size(), size_t(18 * k * k)) << "every edge must be shared by exactly two triangles";
    std::vector<uint32_t> all(m.positions.size());
    for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;

    // From outside: origins on a shell of radius 1.5 .. 20 around the centre.
    auto outside = [](Rng& r, Vec3) { return random_unit(r) * uniform(r, 1.5, 20); };
    shoot_through_edges_and_vertices(s, m.positions, topo, all, rng, 20000, outside);
    // From inside: origins within radius 0.5 of the centre, aimed at edges and vertices.
    auto inside = [](Rng& r, Vec3) { return random_unit(r) * uniform(r, 0, 0.5); };
    shoot_through_edges_and_vertices(s, m.positions, topo, all, rng, 20000, inside);
}

TEST(GeometryWatertight, ClosedMeshRandomRaysFromInsideAlwaysHit) {
    Rng rng(4242);
    rt::SceneDesc d = empty_desc();
    d.meshes.push_back(jittered_cube_sphere(8, rng));
    const rt::Scene s = rt::build_scene(d);
    int misses = 0;
    for (int k = 0; k < 30000; ++k) {
        // Half of the origins at the exact centre or on a coordinate axis, whose rays are
        // likeliest to pass through the cube lattice's edges and vertices.
        Vec3 org = (k % 2) ? random_unit(rng) * uniform(rng, 0, 0.8) : Vec3{};
        if (k % 4 == 2) org[static_cast<int>(rng() % 3)] = uniform(rng, -0.5, 0.5);
        Vec3 dir = random_unit(rng);
        if (k % 8 == 0) {  // diagonal directions through cube corners and face diagonals
            Vec3 v;
            do v = {Real(rng() % 3) - 1, Real(rng() % 3) - 1, Real(rng() % 3) - 1};
            while (rt::dot(v, v) == 0);
            dir = rt::normalize(v);
        }
        rt::Hit h;
        const bool hit = rt::closest_hit(s, {org, dir}, 0, HUGE_VAL, false, h);
        // The surface lies between radius 0.92 and 1.08 (chords make it a little nearer).
        if (!hit || !(h.t > 0.05 && h.t < 2)) {
            if (++misses <= 5)
                ADD_FAILURE() << "ray from (" << org.x << ", " << org.y << ", " << org.z << ") along (" << dir.x << ", "
                              << dir.y << ", " << dir.z << ") " << (hit ? "hit at a wrong t" : "escaped");
        }
    }
    EXPECT_EQ(misses, 0);
}

}  // namespace
