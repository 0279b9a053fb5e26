// BVH traversal tests (include/rt/bvh/bvh.h, include/rt/geometry/traverse.h, src/bvh): the scene
// queries rt::closest_hit and rt::any_hit must give exactly the answer of a brute-force loop
// over every primitive (same t to the last bit, same primitive, ties in t going to the
// lowest primitive id: triangles first, then spheres, then planes), the packet queries
// closest_hits and any_hits exactly theirs (Checker, bvh_test_support.h), and the tree must
// be well formed. Leaves read the leaf-order vertex copy (double, float or none) and test
// blocks of triangles at once: the same answers.
//
// Scenes: random triangle soups and sphere sets of several sizes and seeds, including
// coincident and overlapping primitives, needles and slivers, exactly degenerate
// triangles and axis-aligned ones, with double, float or mixed vertices; and a jittered
// height field whose inner edges and vertices rays must not slip through.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "bvh_test_support.h"
#include "rt/bvh/bvh.h"
#include "rt/geometry/traverse.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace bvh_test;

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
            d.all<rt::SphereDesc>().push_back(
                d.all<rt::SphereDesc>()[pick(rng, d.all<rt::SphereDesc>().size())]);  // coincident: exact tie
        } else {
            rt::SphereDesc sp;
            sp.center = point();
            sp.radius = spec.size * uniform(rng, 0.01, 1);
            d.all<rt::SphereDesc>().push_back(sp);
        }
    }
    for (int i = 0; i < spec.planes; ++i) {
        rt::PlaneDesc pl;
        pl.point = point() * Real(1.5);
        pl.normal = (i == 0) ? Vec3{0, 0, 1} : random_unit(rng);
        if (i == 0) pl.point = {0, 0, 0};  // coincides with the clustered triangles at z = 0
        d.all<rt::PlaneDesc>().push_back(pl);
    }
    return d;
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

// The leaf-order copy (rt/geometry/leaf_vertices.h) is in double for scenes of up to
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

}  // namespace
