// Geometry tests, cameras: the camera rays of include/rt/camera/camera.h for cameras given by
// their near plane, and for lookAt cameras through the loader (extents, aspect ratios, an
// up vector that is not perpendicular to the gaze).
//
// Expected values are worked out by hand in the comments.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "geometry_test_support.h"
#include "rt/camera/camera.h"
#include "rt/core/math.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace geometry_test;

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

}  // namespace
