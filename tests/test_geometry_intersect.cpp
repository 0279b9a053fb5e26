// Geometry tests, intersections: the ray/sphere, ray/triangle and ray/plane tests of
// include/rt/bvh/intersect.h, and the scene queries rt::closest_hit and rt::any_hit
// on tiny hand-built scenes (culling, the meshes' materials and shading, the closest of
// mixed primitives).
//
// Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "geometry_test_support.h"
#include "rt/bvh/intersect.h"
#include "rt/core/math.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/scene_desc.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace geometry_test;

// --- ray / sphere ----------------------------------------------------------------

TEST(GeometrySphere, HitFromOutsideExact) {
    // Origin (0,0,5), direction -z, unit sphere at the origin: roots 5 -+ 1, nearest 4.
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 4);
    // Radius 2 centred at (3,0,0), ray from (3,0,10) down -z: t = 10 - 2 = 8.
    ASSERT_TRUE(rt::intersect_sphere({{3, 0, 10}, {0, 0, -1}}, {3, 0, 0}, 2, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 8);
    // Off-centre: from (0.6,0,5) the chord is at depth sqrt(1 - 0.36) = 0.8, t = 5 - 0.8 = 4.2.
    ASSERT_TRUE(rt::intersect_sphere({{0.6, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_NEAR(t, 4.2, kTol * 5);
}

TEST(GeometrySphere, DiagonalRay) {
    // From (-10,-10,-10) towards the origin along (1,1,1)/sqrt3; radius 3: t = 10 sqrt3 - 3.
    const Vec3 d = rt::normalize(Vec3{1, 1, 1});
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{-10, -10, -10}, d}, {0, 0, 0}, 3, 0, HUGE_VAL, t));
    EXPECT_NEAR(t, 10 * std::sqrt(Real(3)) - 3, kTol * 20);
}

TEST(GeometrySphere, FromInsideGivesFarRoot) {
    // Origin at the centre: roots -2 and +2; only +2 is in front.
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 0}, {0, 0, -1}}, {0, 0, 0}, 2, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 2);
    // Off-centre inside: origin (0,0,0.5) going +z, unit sphere: roots -1.5 and 0.5.
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 0.5}, {0, 0, 1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 0.5);
    // Same ray going -z: roots -0.5 and 1.5.
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 0.5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 1.5);
}

TEST(GeometrySphere, TminSkipsNearRoot) {
    // Roots 4 and 6; with tmin = 4.5 the far root 6 is reported; with tmax = 3 nothing.
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 4.5, HUGE_VAL, t));
    EXPECT_EQ(t, 6);
    EXPECT_FALSE(rt::intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, 3, t));
    // The interval is open: tmax = 4 excludes the root 4, tmin = 6 excludes both.
    EXPECT_FALSE(rt::intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, 4, t));
    EXPECT_FALSE(rt::intersect_sphere({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 6, HUGE_VAL, t));
}

TEST(GeometrySphere, Tangent) {
    // The line x = 1 grazes the unit sphere at (1,0,0): discriminant 1 - 1 = 0, double root at t = 5.
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{1, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 5);
    // Just outside the tangent line: no hit.
    EXPECT_FALSE(rt::intersect_sphere({{1 + 1e-6, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
}

TEST(GeometrySphere, Miss) {
    Real t = -1;
    EXPECT_FALSE(rt::intersect_sphere({{2, 0, 5}, {0, 0, -1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
    EXPECT_FALSE(rt::intersect_sphere({{0, 0, 5}, {1, 0, 0}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
}

TEST(GeometrySphere, BehindTheOrigin) {
    // Sphere entirely behind: roots -6 and -4.
    Real t = -1;
    EXPECT_FALSE(rt::intersect_sphere({{0, 0, 5}, {0, 0, 1}}, {0, 0, 0}, 1, 0, HUGE_VAL, t));
}

TEST(GeometrySphere, SmallSphereFarAway) {
    // Radius 1e-3 at distance 1e4: t = 1e4 - 1e-3 (the discriminant form keeps this accurate).
    Real t = -1;
    ASSERT_TRUE(rt::intersect_sphere({{0, 0, 0}, {0, 0, 1}}, {0, 0, 1e4}, 1e-3, 0, HUGE_VAL, t));
    EXPECT_NEAR(t, 1e4 - 1e-3, std::max(kLoose, Real(1e4) * 8 * std::numeric_limits<Real>::epsilon()));
    // Off-axis by 0.9 radius: still a hit.
    EXPECT_TRUE(rt::intersect_sphere({{0.9e-3, 0, 0}, {0, 0, 1}}, {0, 0, 1e4}, 1e-3, 0, HUGE_VAL, t));
    // Off-axis by 1.1 radius: miss.
    EXPECT_FALSE(rt::intersect_sphere({{1.1e-3, 0, 0}, {0, 0, 1}}, {0, 0, 1e4}, 1e-3, 0, HUGE_VAL, t));
}

// --- ray / triangle --------------------------------------------------------------

const Vec3 kA{0, 0, 0}, kB{1, 0, 0}, kC{0, 1, 0};  // CCW seen from +z, normal +z

TEST(GeometryTriangle, HitWithBarycentrics) {
    // Through (0.25, 0.25, 0) from z = 1 downwards: t = 1, weights (1 - 0.25 - 0.25, 0.25, 0.25).
    Real t = -1, w[3] = {-1, -1, -1};
    ASSERT_TRUE(rt::intersect_triangle(rt::prepare({{0.25, 0.25, 1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    EXPECT_EQ(t, 1);
    EXPECT_EQ(w[0], 0.5);
    EXPECT_EQ(w[1], 0.25);
    EXPECT_EQ(w[2], 0.25);
    // Through (0.5, 0.125, 0) from below (back side, no culling here): t = 2, weights (0.375, 0.5, 0.125).
    ASSERT_TRUE(rt::intersect_triangle(rt::prepare({{0.5, 0.125, -2}, {0, 0, 1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    EXPECT_EQ(t, 2);
    EXPECT_EQ(w[0], 0.375);
    EXPECT_EQ(w[1], 0.5);
    EXPECT_EQ(w[2], 0.125);
}

TEST(GeometryTriangle, ObliqueHitReconstructsPoint) {
    // Aim at a known point P = 0.2 a + 0.3 b + 0.5 c of a tilted triangle from an arbitrary origin;
    // the weights must come back and org + t dir must land on P.
    const Vec3 a{1, 2, 3}, b{4, 0, 1}, c{-2, 5, 2};
    const Vec3 p = a * Real(0.2) + b * Real(0.3) + c * Real(0.5);
    const Vec3 o{7, -3, 9};
    const Vec3 d = rt::normalize(p - o);
    Real t = -1, w[3];
    ASSERT_TRUE(rt::intersect_triangle(rt::prepare({o, d}), a, b, c, 0, HUGE_VAL, t, w));
    EXPECT_NEAR(t, rt::length(p - o), kClose);
    EXPECT_NEAR(w[0], 0.2, kClose);
    EXPECT_NEAR(w[1], 0.3, kClose);
    EXPECT_NEAR(w[2], 0.5, kClose);
    EXPECT_NEAR(w[0] + w[1] + w[2], 1, kClose);
}

TEST(GeometryTriangle, Miss) {
    Real t = -1, w[3];
    // (0.75, 0.75) lies beyond the hypotenuse x + y = 1.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{0.75, 0.75, 1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    // (-0.1, 0.5): left of the edge x = 0.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{-0.1, 0.5, 1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    // Pointing away from the triangle.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{0.25, 0.25, 1}, {0, 0, 1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
}

TEST(GeometryTriangle, Parallel) {
    Real t = -1, w[3];
    // Parallel to the triangle's plane, above it.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{-1, 0.25, 1}, {1, 0, 0}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    // In the triangle's plane (edge-on): det = 0, no hit.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{-1, 0.25, 0}, {1, 0, 0}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    const Vec3 diag = rt::normalize(Vec3{1, 1, 0});
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{-1, -0.9, 0}, diag}), kA, kB, kC, 0, HUGE_VAL, t, w));
}

TEST(GeometryTriangle, TRangeIsOpen) {
    // The hit is at t = 1.
    const rt::RayPre p = rt::prepare({{0.25, 0.25, 1}, {0, 0, -1}});
    Real t = -1, w[3];
    EXPECT_FALSE(rt::intersect_triangle(p, kA, kB, kC, 0, 1, t, w));  // tmax = t excluded
    EXPECT_TRUE(rt::intersect_triangle(p, kA, kB, kC, 0, 1.0001, t, w));
    EXPECT_FALSE(rt::intersect_triangle(p, kA, kB, kC, 1, HUGE_VAL, t, w));  // tmin = t excluded
    EXPECT_TRUE(rt::intersect_triangle(p, kA, kB, kC, 0.9999, HUGE_VAL, t, w));
    EXPECT_FALSE(rt::intersect_triangle(p, kA, kB, kC, 0, 0.5, t, w));
    EXPECT_FALSE(rt::intersect_triangle(p, kA, kB, kC, 1.5, 2, t, w));
    // Behind the origin (t = -1) is never a hit with tmin = 0.
    EXPECT_FALSE(rt::intersect_triangle(rt::prepare({{0.25, 0.25, -1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
}

TEST(GeometryTriangle, EdgesAndVertexCount) {
    // A ray through the midpoint of edge a-b (0.5, 0, 0) or through vertex c is a hit
    // (the watertight test accepts zero edge functions).
    Real t = -1, w[3];
    EXPECT_TRUE(rt::intersect_triangle(rt::prepare({{0.5, 0, 1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    EXPECT_EQ(t, 1);
    EXPECT_EQ(w[2], 0);
    EXPECT_TRUE(rt::intersect_triangle(rt::prepare({{0, 1, 1}, {0, 0, -1}}), kA, kB, kC, 0, HUGE_VAL, t, w));
    EXPECT_EQ(w[2], 1);
}

TEST(GeometryTriangle, DirectionAlongEveryAxis) {
    // Same unit triangle placed perpendicular to each axis, hit from both sides; the shear
    // picks a different dominant axis (and winding swap) each time.
    for (int axis = 0; axis < 3; ++axis) {
        for (Real sgn : {Real(-1), Real(1)}) {
            auto place = [&](Real a, Real b, Real c) {  // (a, b) in-plane, c along `axis`
                Vec3 v;
                v[axis] = c;
                v[(axis + 1) % 3] = a;
                v[(axis + 2) % 3] = b;
                return v;
            };
            const Vec3 a = place(0, 0, 0), b = place(1, 0, 0), c = place(0, 1, 0);
            Vec3 dir;
            dir[axis] = sgn;
            const Vec3 org = place(0.25, 0.5, -3 * sgn);
            Real t = -1, w[3];
            ASSERT_TRUE(rt::intersect_triangle(rt::prepare({org, dir}), a, b, c, 0, HUGE_VAL, t, w))
                << "axis " << axis << " sign " << sgn;
            EXPECT_EQ(t, 3);
            EXPECT_EQ(w[0], 0.25);  // 1 - 0.25 - 0.5
            EXPECT_EQ(w[1], 0.25);
            EXPECT_EQ(w[2], 0.5);
        }
    }
}

// --- ray / plane -----------------------------------------------------------------

TEST(GeometryPlane, BothSides) {
    Real t = -1;
    // Plane z = 0 with normal +z; from above going down: t = 5.
    ASSERT_TRUE(rt::intersect_plane({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, {0, 0, 1}, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 5);
    // From below going up: t = 3.
    ASSERT_TRUE(rt::intersect_plane({{0, 0, -3}, {0, 0, 1}}, {0, 0, 0}, {0, 0, 1}, 0, HUGE_VAL, t));
    EXPECT_EQ(t, 3);
    // Oblique: plane y = -1 (point (7,-1,2)), from (0,1,0) along (0,-1,1)/sqrt2: distance 2, t = 2 sqrt2.
    ASSERT_TRUE(rt::intersect_plane({{0, 1, 0}, rt::normalize(Vec3{0, -1, 1})}, {7, -1, 2}, {0, 1, 0}, 0, HUGE_VAL, t));
    EXPECT_NEAR(t, 2 * std::sqrt(Real(2)), kTol * 4);
}

TEST(GeometryPlane, ParallelBehindAndRange) {
    Real t = -1;
    EXPECT_FALSE(rt::intersect_plane({{0, 0, 5}, {1, 0, 0}}, {0, 0, 0}, {0, 0, 1}, 0, HUGE_VAL, t));  // parallel
    EXPECT_FALSE(rt::intersect_plane({{0, 0, 0}, {1, 0, 0}}, {0, 0, 0}, {0, 0, 1}, 0, HUGE_VAL, t));  // in plane
    EXPECT_FALSE(rt::intersect_plane({{0, 0, 5}, {0, 0, 1}}, {0, 0, 0}, {0, 0, 1}, 0, HUGE_VAL, t));  // behind
    EXPECT_FALSE(rt::intersect_plane({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, {0, 0, 1}, 0, 5, t));        // tmax open
    EXPECT_FALSE(rt::intersect_plane({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, {0, 0, 1}, 5, 9, t));        // tmin open
    EXPECT_TRUE(rt::intersect_plane({{0, 0, 5}, {0, 0, -1}}, {0, 0, 0}, {0, 0, 1}, 4.999, 5.001, t));
    EXPECT_EQ(t, 5);
}

// --- scene queries on tiny hand-built scenes ---------------------------------------

TEST(GeometryScene, CullingIgnoresBackFacesOnly) {
    rt::SceneDesc d = empty_desc();
    rt::MeshDesc m;
    m.positions = {kA, kB, kC};
    m.indices = {0, 1, 2};  // normal +z
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    ASSERT_EQ(s.geometry.triangles.size(), 1u);
    EXPECT_NEAR(s.geometry.face_normal(0).z, 1, kTol);
    rt::Hit h;
    const rt::Ray down{{0.25, 0.25, 1}, {0, 0, -1}}, up{{0.25, 0.25, -1}, {0, 0, 1}};
    EXPECT_TRUE(rt::closest_hit(s, down, 0, HUGE_VAL, true, h));  // front face
    EXPECT_FALSE(rt::closest_hit(s, up, 0, HUGE_VAL, true, h));   // back face, culled
    EXPECT_TRUE(rt::closest_hit(s, up, 0, HUGE_VAL, false, h));   // back face, not culled
    EXPECT_EQ(h.t, 1);
    EXPECT_TRUE(rt::any_hit(s, up, 0, HUGE_VAL)) << "shadow rays never cull";
}

// Each triangle's material and shading come from its mesh, through Geometry::runs:
// equal neighbours share a run, a mesh of degenerate faces only leaves none behind,
// and surface() reports each triangle's own material.
TEST(GeometryScene, TrianglesTakeTheirMeshsMaterialAndShading) {
    rt::SceneDesc d = empty_desc();
    d.materials.resize(3);
    struct Spec {
        uint32_t material;
        rt::ShadingMode shading;
        bool degenerate;
    };
    const Spec specs[] = {{0, rt::ShadingMode::Flat, false},  {0, rt::ShadingMode::Flat, false},
                          {2, rt::ShadingMode::Smooth, true}, {1, rt::ShadingMode::Smooth, false},
                          {1, rt::ShadingMode::Flat, false},  {2, rt::ShadingMode::Flat, true},
                          {1, rt::ShadingMode::Flat, false}};
    std::vector<const Spec*> want;  // per kept triangle
    for (size_t i = 0; i < std::size(specs); ++i) {
        rt::MeshDesc m;
        const Real z = Real(i);
        m.positions = {{0, 0, z}, {1, 0, z}, {0, 1, z}, {1, 1, z}, {2, 2, z}};
        // Two faces; a degenerate mesh's are collinear.
        m.indices =
            specs[i].degenerate ? std::vector<uint32_t>{0, 3, 4, 4, 3, 0} : std::vector<uint32_t>{0, 1, 2, 1, 3, 2};
        m.material = specs[i].material;
        m.shading = specs[i].shading;
        d.meshes.push_back(m);
        if (!specs[i].degenerate) want.insert(want.end(), 2, &specs[i]);
    }
    const rt::Scene s = rt::build_scene(d);
    const rt::Geometry& g = s.geometry;
    ASSERT_EQ(g.triangles.size(), want.size());
    // Runs: meshes 0+1 (merged), 3, 4+6 (5 left nothing, so 6 joins 4).
    ASSERT_EQ(g.runs.size(), 3u);
    EXPECT_EQ(g.runs[0].first, 0u);
    EXPECT_EQ(g.runs[1].first, 4u);
    EXPECT_EQ(g.runs[2].first, 6u);
    for (uint32_t t = 0; t < g.triangles.size(); ++t) {
        const rt::TriangleRun& r = g.run_of(t);
        EXPECT_EQ(r.material, want[t]->material) << "triangle " << t;
        EXPECT_EQ(r.smooth, want[t]->shading == rt::ShadingMode::Smooth) << "triangle " << t;
        rt::Hit h;
        h.kind = rt::ShapeKind::Triangle;
        h.index = t;
        h.w[0] = h.w[1] = h.w[2] = Real(1) / 3;
        EXPECT_EQ(g.surface(h, {0, 0, 0}).material, want[t]->material) << "triangle " << t;
    }
}

TEST(GeometryScene, ClosestOfMixedPrimitives) {
    // Along -z from z = 10: plane z = 0 at t 10, sphere radius 1 at z = 3 (t = 6), triangle at z = 5 (t = 5).
    rt::SceneDesc d = empty_desc();
    d.all<rt::PlaneDesc>().push_back(
        {{0, "1", nullptr, {}}, {0, 0, 0}, {0, 0, 2}});  // normal gets normalised by build_scene
    d.all<rt::SphereDesc>().push_back({{0, "1", nullptr, {}}, {0, 0, 3}, 1, {}});
    rt::MeshDesc m;
    m.positions = {{-1, -1, 5}, {1, -1, 5}, {0, 1, 5}};
    m.indices = {0, 1, 2};
    d.meshes.push_back(m);
    const rt::Scene s = rt::build_scene(d);
    EXPECT_NEAR(s.geometry.all<rt::Plane>()[0].normal.z, 1, kTol);
    const rt::Ray r{{0, 0, 10}, {0, 0, -1}};
    rt::Hit h;
    ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, true, h));
    EXPECT_EQ(h.kind, rt::ShapeKind::Triangle);
    EXPECT_EQ(h.t, 5);
    ASSERT_TRUE(rt::closest_hit(s, r, 5, HUGE_VAL, true, h));  // tmin open: skips the triangle
    EXPECT_EQ(h.kind, rt::ShapeKind::Sphere);
    EXPECT_EQ(h.t, 6);
    ASSERT_TRUE(rt::closest_hit(s, r, 8.5, HUGE_VAL, true, h));  // past the sphere's far root 8: plane
    EXPECT_EQ(h.kind, rt::ShapeKind::Plane);
    EXPECT_EQ(h.t, 10);
    EXPECT_FALSE(rt::closest_hit(s, r, 0, 4.5, true, h));
    EXPECT_FALSE(rt::any_hit(s, r, 0, 4.5));
    EXPECT_TRUE(rt::any_hit(s, r, 9, 11));  // only the plane
    EXPECT_FALSE(rt::any_hit(s, r, 10, 11));
}

}  // namespace
