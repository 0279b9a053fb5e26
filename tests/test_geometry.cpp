// Geometry tests: camera rays (include/rt/camera/camera.h, through the loader for lookAt
// cameras), the ray/primitive tests of include/rt/geometry/intersect.h, and a watertightness
// property of the scene query rt::closest_hit on jittered meshes.
//
// Expected values are worked out by hand in the comments. Random tests use fixed
// seeds, so every run shoots the same rays.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "rt/bvh/traverse.h"
#include "rt/camera/camera.h"
#include "rt/core/math.h"
#include "rt/geometry/intersect.h"
#include "rt/geometry/scene.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/scene_desc.h"

namespace {

using rt::Real;
using rt::Vec3;

// Tolerance for directions and distances worked out by hand: a few ulps of Real.
const Real kTol = 16 * std::numeric_limits<Real>::epsilon();
// Tolerances for values worked out by hand: tight ones for a single formula, loose ones for
// results of a few chained operations (double by default; float with PRECISION=float).
const Real kClose = sizeof(Real) == sizeof(double) ? Real(1e-12) : Real(2e-5);
const Real kLoose = sizeof(Real) == sizeof(double) ? Real(1e-9) : Real(2e-4);

void expect_dir(Vec3 got, Vec3 want_unnormalised, const char* what) {
    const Vec3 want = rt::normalize(want_unnormalised);
    EXPECT_NEAR(got.x, want.x, kTol) << what;
    EXPECT_NEAR(got.y, want.y, kTol) << what;
    EXPECT_NEAR(got.z, want.z, kTol) << what;
    EXPECT_NEAR(rt::length(got), 1, kTol) << what << ": direction must have unit length";
}

// A scene holding nothing but the given camera object.
rt::Scene camera_scene(const std::string& camera_json) {
    const std::string text = R"({"Scene": {"Cameras": {"Camera": )" + camera_json + "}}}";
    return rt::build_scene(rt::parse_scene(text, "/nonexistent/x.json"));
}

// --- cameras -------------------------------------------------------------------

TEST(GeometryCamera, SimpleCameraCentreAndCorners) {
    const rt::Scene s = camera_scene(R"({
        "_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "3 3", "ImageName": "a.png"})");
    ASSERT_EQ(s.setup.cameras.size(), 1u);
    const rt::Camera& c = s.setup.cameras[0];
    EXPECT_EQ(c.width, 3);
    EXPECT_EQ(c.height, 3);
    EXPECT_EQ(c.image_name, "a.png");
    // Pixel centres of a 3-wide plane spanning [-1, 1]: -1 + 2 (i + 0.5) / 3 = -2/3, 0, 2/3.
    // Centre pixel looks along the gaze.
    const rt::Ray mid = c.primary_ray(1, 1);
    EXPECT_EQ(mid.org.x, 0);
    EXPECT_EQ(mid.org.y, 0);
    EXPECT_EQ(mid.org.z, 0);
    expect_dir(mid.dir, {0, 0, -1}, "centre");
    // Top-left (i = 0 column from the left, j = 0 row from the top): (-2/3, +2/3, -1) / (sqrt(17)/3).
    expect_dir(c.primary_ray(0, 0).dir, {-2.0 / 3, 2.0 / 3, -1}, "top-left");
    EXPECT_NEAR(c.primary_ray(0, 0).dir.x, -2 / std::sqrt(Real(17)), kTol);
    expect_dir(c.primary_ray(2, 0).dir, {2.0 / 3, 2.0 / 3, -1}, "top-right");
    expect_dir(c.primary_ray(0, 2).dir, {-2.0 / 3, -2.0 / 3, -1}, "bottom-left");
    expect_dir(c.primary_ray(2, 2).dir, {2.0 / 3, -2.0 / 3, -1}, "bottom-right");
    expect_dir(c.primary_ray(1, 0).dir, {0, 2.0 / 3, -1}, "top-centre");
}

TEST(GeometryCamera, AsymmetricNearPlaneAndNearDistance) {
    // NearPlane -1 3 -2 0 at distance 2, 2x2 image:
    // s_u = -1 + 4 (i + 0.5) / 2 = 0 or 2; s_v = 0 - 2 (j + 0.5) / 2 = -0.5 or -1.5.
    const rt::Scene s = camera_scene(R"({
        "Position": "1 2 3", "Gaze": "0 0 -4", "Up": "0 7 0",
        "NearPlane": "-1 3 -2 0", "NearDistance": "2", "ImageResolution": "2 2", "ImageName": "a.png"})");
    const rt::Camera& c = s.setup.cameras[0];
    const rt::Ray r00 = c.primary_ray(0, 0);
    EXPECT_EQ(r00.org.x, 1);
    EXPECT_EQ(r00.org.y, 2);
    EXPECT_EQ(r00.org.z, 3);
    expect_dir(r00.dir, {0, -0.5, -2}, "(0,0)");
    expect_dir(c.primary_ray(1, 0).dir, {2, -0.5, -2}, "(1,0)");
    expect_dir(c.primary_ray(1, 1).dir, {2, -1.5, -2}, "(1,1)");
}

TEST(GeometryCamera, RotatedBasisIsRightHanded) {
    // Gaze +x, Up +z: w = (-1,0,0), u = up x w = (0,0,1) x (-1,0,0) = (0,-1,0), v = w x u = (0,0,1).
    // Looking along +x with +z up, the right of the image is -y.
    rt::CameraDesc d;
    d.position = {0, 0, 0};
    d.gaze = {5, 0, 0};
    d.up = {0, 0, 3};
    d.width = d.height = 3;
    const rt::Camera c = rt::make_camera(d);
    EXPECT_NEAR(c.w.x, -1, kTol);
    EXPECT_NEAR(c.u.y, -1, kTol);
    EXPECT_NEAR(c.v.z, 1, kTol);
    expect_dir(c.primary_ray(1, 1).dir, {1, 0, 0}, "centre");
    expect_dir(c.primary_ray(2, 1).dir, {1, -2.0 / 3, 0}, "right-centre");
    expect_dir(c.primary_ray(1, 0).dir, {1, 0, 2.0 / 3}, "top-centre");
}

TEST(GeometryCamera, UpIsReorthogonalised) {
    // Up (0,1,1) is 45 degrees off the image plane; v must become (0,1,0) for gaze (0,0,-1):
    // w = (0,0,1), u = normalize((0,1,1) x (0,0,1)) = normalize((1,0,0)), v = w x u = (0,1,0).
    rt::CameraDesc d;
    d.position = {0, 0, 0};
    d.gaze = {0, 0, -1};
    d.up = {0, 1, 1};
    d.width = d.height = 3;
    const rt::Camera c = rt::make_camera(d);
    EXPECT_NEAR(c.u.x, 1, kTol);
    EXPECT_NEAR(c.u.y, 0, kTol);
    EXPECT_NEAR(c.u.z, 0, kTol);
    EXPECT_NEAR(c.v.x, 0, kTol);
    EXPECT_NEAR(c.v.y, 1, kTol);
    EXPECT_NEAR(c.v.z, 0, kTol);
    EXPECT_NEAR(rt::dot(c.u, c.v), 0, kTol);
    EXPECT_NEAR(rt::dot(c.v, c.w), 0, kTol);
    EXPECT_NEAR(rt::length(c.v), 1, kTol);
    expect_dir(c.primary_ray(1, 1).dir, {0, 0, -1}, "centre looks along the gaze");
    expect_dir(c.primary_ray(1, 0).dir, {0, 2.0 / 3, -1}, "top-centre");
    expect_dir(c.primary_ray(2, 1).dir, {2.0 / 3, 0, -1}, "right-centre");
}

TEST(GeometryCamera, ReorthogonalisedThroughTheLoaderToo) {
    // Gaze (1,0,-1). Camera a: Up (0,1,0), already perpendicular. Camera c: Up (0.5,1,-0.5)
    // = (0,1,0) + 0.5 (1,0,-1), tilted along the gaze, so it must re-orthogonalise to a's
    // camera exactly. Camera b: Up (1,1,1), perpendicular to the gaze, rolls the image.
    const std::string common = R"("Position": "0 0 0", "Gaze": "1 0 -1", "NearPlane": "-1 1 -1 1",
        "NearDistance": "1", "ImageResolution": "5 5", "ImageName": "a.png")";
    const rt::Scene a = camera_scene("{" + common + R"(, "Up": "0 1 0"})");
    const rt::Scene b = camera_scene("{" + common + R"(, "Up": "1 1 1"})");
    const rt::Scene c = camera_scene("{" + common + R"(, "Up": "0.5 1 -0.5"})");
    for (int j = 0; j < 5; ++j)
        for (int i = 0; i < 5; ++i) {
            const Vec3 da = a.setup.cameras[0].primary_ray(i, j).dir, dc = c.setup.cameras[0].primary_ray(i, j).dir;
            EXPECT_NEAR(da.x, dc.x, kTol);
            EXPECT_NEAR(da.y, dc.y, kTol);
            EXPECT_NEAR(da.z, dc.z, kTol);
        }
    // Centre: along the gaze (1,0,-1)/sqrt(2) in all three.
    expect_dir(a.setup.cameras[0].primary_ray(2, 2).dir, {1, 0, -1}, "a centre");
    expect_dir(b.setup.cameras[0].primary_ray(2, 2).dir, {1, 0, -1}, "b centre");
    expect_dir(c.setup.cameras[0].primary_ray(2, 2).dir, {1, 0, -1}, "c centre");
    // Camera a: w = (-1,0,1)/sqrt2, u = (0,1,0) x w = (1,0,1)/sqrt2, v = (0,1,0).
    // Top-centre pixel (2, 0): s_v = 1 - 2 * 0.5/5 = 0.8: dir ~ 0.8 v - w = (1/sqrt2, 0.8, -1/sqrt2).
    const Real h = 1 / std::sqrt(Real(2));
    expect_dir(a.setup.cameras[0].primary_ray(2, 0).dir, {h, 0.8, -h}, "a top-centre");
    // Camera b: u = normalize((1,1,1) x w) = normalize((1*1-1*0, 1*(-1)-1*1, 1*0-1*(-1))) = (1,-2,1)/sqrt6,
    // v = w x u = (0*1-1*(-2), 1*1-(-1)*1, (-1)(-2)-0*1)/sqrt12 = (2,2,2)/sqrt12 = (1,1,1)/sqrt3.
    EXPECT_NEAR(b.setup.cameras[0].v.x, 1 / std::sqrt(Real(3)), kTol);
    EXPECT_NEAR(b.setup.cameras[0].v.y, 1 / std::sqrt(Real(3)), kTol);
    EXPECT_NEAR(b.setup.cameras[0].u.y, -2 / std::sqrt(Real(6)), kTol);
}

TEST(GeometryCamera, LookAtSquareNinetyDegrees) {
    // FovY 90 at NearDistance 2: top = 2 tan(45) = 2, right = top * 3/3 = 2.
    const rt::Scene s = camera_scene(R"({
        "_type": "lookAt", "Position": "0 0 0", "GazePoint": "0 0 -10", "Up": "0 1 0",
        "FovY": "90", "NearDistance": "2", "ImageResolution": "3 3", "ImageName": "a.png"})");
    const rt::Camera& c = s.setup.cameras[0];
    EXPECT_NEAR(c.top, 2, kTol);
    EXPECT_NEAR(c.bottom, -2, kTol);
    EXPECT_NEAR(c.right, 2, kTol);
    EXPECT_NEAR(c.left, -2, kTol);
    // The image plane's top edge is at 45 degrees above the gaze: atan(top / d) = atan(1).
    EXPECT_NEAR(std::atan2(c.top, c.near_distance), std::atan(Real(1)), kTol);
    // Centre pixel looks at the gaze point.
    expect_dir(c.primary_ray(1, 1).dir, {0, 0, -1}, "centre");
    // Corner pixel centres: s = +-2 * 2/3 at distance 2, i.e. (-2/3, 2/3, -1) up to scale.
    expect_dir(c.primary_ray(0, 0).dir, {-2.0 / 3, 2.0 / 3, -1}, "top-left");
    expect_dir(c.primary_ray(2, 2).dir, {2.0 / 3, -2.0 / 3, -1}, "bottom-right");
    // Symmetric: the horizontal and vertical angles of the corner pixel are equal, atan(2/3).
    const Vec3 d = c.primary_ray(0, 0).dir;
    EXPECT_NEAR(std::atan2(d.y, -d.z), std::atan(Real(2) / 3), kTol);
    EXPECT_NEAR(std::atan2(-d.x, -d.z), std::atan(Real(2) / 3), kTol);
}

TEST(GeometryCamera, LookAtCornerOfLargeImageApproaches45Degrees) {
    // 1001 x 1001, FovY 90: the top-left pixel centre sits half a pixel in from the corner,
    // at s = 1 - 1/1001 on both axes: atan(1000/1001) = 44.9714 degrees, within 0.03 of 45.
    const rt::Scene s = camera_scene(R"({
        "_type": "lookAt", "Position": "0 0 0", "GazePoint": "0 0 -1", "Up": "0 1 0",
        "FovY": "90", "NearDistance": "1", "ImageResolution": "1001 1001", "ImageName": "a.png"})");
    const Vec3 d = s.setup.cameras[0].primary_ray(0, 0).dir;
    const Real deg = Real(180) / rt::kPi;
    EXPECT_NEAR(std::atan2(d.y, -d.z) * deg, 44.97138, 1e-4);
    EXPECT_NEAR(std::atan2(-d.x, -d.z) * deg, 44.97138, 1e-4);
    expect_dir(s.setup.cameras[0].primary_ray(500, 500).dir, {0, 0, -1}, "centre");
}

TEST(GeometryCamera, LookAtLandscapeAndPortrait) {
    // FovY 90 at distance 1: top = 1.
    // Landscape 4x2: right = 1 * 4/2 = 2; pixel (0,0): s_u = -2 + 4*0.5/4 = -1.5, s_v = 1 - 2*0.5/2 = 0.5.
    const rt::Scene land = camera_scene(R"({
        "_type": "lookAt", "Position": "0 0 0", "GazePoint": "0 0 -3", "Up": "0 1 0",
        "FovY": "90", "NearDistance": "1", "ImageResolution": "4 2", "ImageName": "a.png"})");
    EXPECT_NEAR(land.setup.cameras[0].right, 2, kTol);
    EXPECT_NEAR(land.setup.cameras[0].top, 1, kTol);
    expect_dir(land.setup.cameras[0].primary_ray(0, 0).dir, {-1.5, 0.5, -1}, "landscape (0,0)");
    expect_dir(land.setup.cameras[0].primary_ray(3, 1).dir, {1.5, -0.5, -1}, "landscape (3,1)");
    // Portrait 2x4: right = 1 * 2/4 = 0.5; pixel (0,0): s_u = -0.5 + 1*0.5/2 = -0.25, s_v = 1 - 2*0.5/4 = 0.75.
    const rt::Scene port = camera_scene(R"({
        "_type": "lookAt", "Position": "0 0 0", "GazePoint": "0 0 -3", "Up": "0 1 0",
        "FovY": "90", "NearDistance": "1", "ImageResolution": "2 4", "ImageName": "a.png"})");
    EXPECT_NEAR(port.setup.cameras[0].right, 0.5, kTol);
    EXPECT_NEAR(port.setup.cameras[0].top, 1, kTol);
    expect_dir(port.setup.cameras[0].primary_ray(0, 0).dir, {-0.25, 0.75, -1}, "portrait (0,0)");
    expect_dir(port.setup.cameras[0].primary_ray(1, 3).dir, {0.25, -0.75, -1}, "portrait (1,3)");
}

TEST(GeometryCamera, LookAtSixtyDegreesOffAxisGazePoint) {
    // FovY 60, distance 1: top = tan(30) = 1/sqrt(3) = 0.57735; square image.
    // Camera at (1,1,1) looking at the origin, Up (0,1,0) not perpendicular to the gaze.
    const rt::Scene s = camera_scene(R"({
        "_type": "lookAt", "Position": "1 1 1", "GazePoint": "0 0 0", "Up": "0 1 0",
        "FovY": "60", "NearDistance": "1", "ImageResolution": "5 5", "ImageName": "a.png"})");
    const rt::Camera& c = s.setup.cameras[0];
    EXPECT_NEAR(c.top, 1 / std::sqrt(Real(3)), kTol);
    EXPECT_NEAR(c.right, 1 / std::sqrt(Real(3)), kTol);
    expect_dir(c.primary_ray(2, 2).dir, {-1, -1, -1}, "centre looks at the gaze point");
    // v must be perpendicular to the gaze and have a positive y: w = (1,1,1)/sqrt3,
    // u = normalize((0,1,0) x w) = (1,0,-1)/sqrt2, v = w x u = (-1,2,-1)/sqrt6.
    EXPECT_NEAR(c.v.x, -1 / std::sqrt(Real(6)), kTol);
    EXPECT_NEAR(c.v.y, 2 / std::sqrt(Real(6)), kTol);
    EXPECT_NEAR(c.u.x, 1 / std::sqrt(Real(2)), kTol);
    EXPECT_NEAR(c.u.z, -1 / std::sqrt(Real(2)), kTol);
}

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

rt::SceneDesc empty_desc() {
    rt::SceneDesc d;
    d.path = "/nonexistent/x.json";
    d.materials.push_back({});
    return d;
}

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
    d.all<rt::Plane>().push_back({{0, "1"}, {0, 0, 0}, {0, 0, 2}});  // normal gets normalised by build_scene
    d.all<rt::Sphere>().push_back({{0, "1"}, {0, 0, 3}, 1});
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
