// BVH tie tests (include/rt/geometry/traverse.h): hits at the same t go to the lowest primitive
// id (triangles first, then spheres, then planes), with and without culling, on scenes of
// coincident primitives; and the triangle test's range check, which the traversal's
// tie-break relies on, accepts a hit under tmax = nextafter(its own t).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "bvh_test_support.h"
#include "rt/bvh/intersect.h"
#include "rt/geometry/traverse.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace bvh_test;

TEST(BvhProperty, AllCoincident) {
    // Many copies of one triangle and one sphere: every centroid equal, every hit a tie.
    // The tree must stay shallow and the lowest id must win.
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc m;
    m.positions = {{-1, -1, 0}, {1, -1, 0}, {0, 1, 0}};
    for (int i = 0; i < 3000; ++i) m.indices.insert(m.indices.end(), {0, 1, 2});
    d.meshes.push_back(m);
    for (int i = 0; i < 500; ++i) d.all<rt::SphereDesc>().push_back({{0, "1", nullptr, {}}, {0, 0, 5}, 1, {}});
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
    d.all<rt::SphereDesc>().push_back({{0, "1", nullptr, {}}, {0, 0, 6}, 1, {}});  // near root at z = 5
    d.all<rt::PlaneDesc>().push_back({{0, "1", nullptr, {}}, {0, 0, 5}, {0, 0, -1}});
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
    d.all<rt::SphereDesc>().clear();
    {
        const rt::Scene s = rt::build_scene(d);
        ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, false, h));
        EXPECT_EQ(h.kind, rt::ShapeKind::Plane);
        EXPECT_EQ(h.t, 5);
    }
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

}  // namespace
