// Distribution ray tracing (assignment 3; docs/conventions.md, "Assignment 3"): the scene
// file's new elements and their bad input, the random numbers, the sampling of pixels,
// lenses, area lights and rough surfaces with hand-computed answers, motion blur, and
// the promises of determinism (thread count, seed).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "distribution_test_support.h"
#include "loader_test_support.h"
#include "rt/core/error.h"
#include "rt/core/random.h"
#include "rt/geometry/light.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/load_scene.h"
#include "rt/materials/optics.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/pixel_samples.h"
#include "test_support.h"

namespace {

using distribution_test::area_light;
using distribution_test::build;
using distribution_test::everything;
using loader_test::json;
using loader_test::kPath;
using loader_test::parse;
using loader_test::sample;
using rt::Real;

const std::string kCam = "/Scene/Cameras/Camera";

// Expects rt::InputError "<file>: ...<pointer>..." on one line.
void expect_error(const json& j, const std::string& pointer) {
    try {
        (void)parse(j.dump());
        ADD_FAILURE() << "no error; expected one at " << pointer;
    } catch (const rt::InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(kPath + ": ", 0), 0u) << msg;
        EXPECT_NE(msg.find(pointer), std::string::npos) << "expected " << pointer << " in: " << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

// --- the scene file ----------------------------------------------------------------------

TEST(DistributionLoader, ReadsEveryNewElement) {
    json j = sample();
    j["Scene"]["Cameras"]["Camera"]["NumSamples"] = "16";
    j["Scene"]["Cameras"]["Camera"]["FocusDistance"] = "4.5";
    j["Scene"]["Cameras"]["Camera"]["ApertureSize"] = "0.25";
    j["Scene"]["Lights"]["AreaLight"] = area_light();
    j["Scene"]["Lights"]["AreaLight"]["Normal"] = "0 -3 0";  // kept as written; the build normalises it
    j["Scene"]["Objects"]["Sphere"]["MotionBlur"] = "1 2 3";
    j["Scene"]["Objects"]["Mesh"]["MotionBlur"] = "0 0 -1";
    j["Scene"]["Materials"]["Material"]["_type"] = "mirror";
    j["Scene"]["Materials"]["Material"]["MirrorReflectance"] = "1 1 1";
    j["Scene"]["Materials"]["Material"]["Roughness"] = "0.3";
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.cameras.size(), 1u);
    EXPECT_EQ(d.cameras[0].num_samples, 16);
    EXPECT_DOUBLE_EQ(d.cameras[0].focus_distance, 4.5);
    EXPECT_DOUBLE_EQ(d.cameras[0].aperture_size, 0.25);
    ASSERT_EQ(d.area_lights.size(), 1u);
    EXPECT_DOUBLE_EQ(d.area_lights[0].normal.y, -3);
    EXPECT_DOUBLE_EQ(d.area_lights[0].size, 2);
    EXPECT_DOUBLE_EQ(d.area_lights[0].radiance.x, 10);
    EXPECT_DOUBLE_EQ(d.all<rt::SphereDesc>()[0].motion.z, 3);
    EXPECT_DOUBLE_EQ(d.meshes[0].motion.z, -1);
    EXPECT_TRUE(d.meshes[0].instanced) << "a moving mesh is drawn as an instance of itself";
    EXPECT_DOUBLE_EQ(d.materials[0].roughness, Real(0.3));
    EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
    const rt::Scene s = rt::build_scene(d);
    ASSERT_EQ(s.setup.lights.size(), 2u);
    EXPECT_DOUBLE_EQ(s.setup.lights[1].normal.y, -1);  // normalised by the build
}

TEST(DistributionLoader, CameraWithoutNumSamplesHasNone) {
    const rt::SceneDesc d = parse(sample().dump());
    EXPECT_EQ(d.cameras[0].num_samples, 0);
    EXPECT_EQ(d.cameras[0].aperture_size, 0);
}

TEST(DistributionLoader, BadCameraValues) {
    for (const char* n : {"0", "-4", "2.5", "many", "1 2"}) {
        SCOPED_TRACE(n);
        json j = sample();
        j["Scene"]["Cameras"]["Camera"]["NumSamples"] = n;
        expect_error(j, kCam + "/NumSamples");
    }
    json j = sample();
    j["Scene"]["Cameras"]["Camera"]["ApertureSize"] = "-1";
    j["Scene"]["Cameras"]["Camera"]["FocusDistance"] = "3";
    expect_error(j, kCam + "/ApertureSize");
    for (const char* f : {"0", "-3", "nan", "far"}) {
        SCOPED_TRACE(f);
        j = sample();
        j["Scene"]["Cameras"]["Camera"]["FocusDistance"] = f;
        expect_error(j, kCam + "/FocusDistance");
    }
    j = sample();
    j["Scene"]["Cameras"]["Camera"]["ApertureSize"] = "0.5";  // a lens without a focus distance
    expect_error(j, kCam + "/ApertureSize");
}

TEST(DistributionLoader, BadAreaLights) {
    const std::string p = "/Scene/Lights/AreaLight";
    json j = sample();
    j["Scene"]["Lights"]["AreaLight"] = area_light();
    j["Scene"]["Lights"]["AreaLight"].erase("Position");
    expect_error(j, p);
    const std::vector<std::pair<const char*, const char*>> bad = {
        {"Normal", "0 0 0"}, {"Size", "0"}, {"Size", "-2"}, {"Radiance", "-1 0 0"}, {"Position", "1 2"}};
    for (const auto& [key, value] : bad) {
        SCOPED_TRACE(std::string(key) + " " + value);
        j = sample();
        j["Scene"]["Lights"]["AreaLight"] = area_light();
        j["Scene"]["Lights"]["AreaLight"][key] = value;
        expect_error(j, p + "/" + key);
    }
}

TEST(DistributionLoader, BadMotionBlur) {
    for (const char* object : {"Sphere", "Mesh", "Triangle"}) {
        for (const char* m : {"1 2", "1 2 3 4", "1 inf 2", "a b c"}) {
            SCOPED_TRACE(std::string(object) + " " + m);
            json j = sample();
            j["Scene"]["Objects"][object]["MotionBlur"] = m;
            expect_error(j, "/Scene/Objects/" + std::string(object) + "/MotionBlur");
        }
    }
    json j = sample();
    j["Scene"]["Objects"]["MeshInstance"] = {{"_id", "5"}, {"_baseMeshId", "1"}, {"MotionBlur", "0 0"}};
    expect_error(j, "/Scene/Objects/MeshInstance/MotionBlur");
}

TEST(DistributionLoader, NegativeRoughness) {
    for (const char* type : {"mirror", "conductor", "dielectric", ""}) {
        SCOPED_TRACE(type);
        json j = sample();
        json& m = j["Scene"]["Materials"]["Material"];
        if (*type) m["_type"] = type;
        m["MirrorReflectance"] = "1 1 1";
        m["RefractionIndex"] = "1.5";
        m["AbsorptionIndex"] = "1";
        m["Roughness"] = "-0.1";
        expect_error(j, "/Scene/Materials/Material/Roughness");
    }
}

// --- random numbers ----------------------------------------------------------------------

TEST(SampleStream, APureFunctionOfSeedPixelSampleAndCount) {
    rt::SampleStream a(7, 123, 4), b(7, 123, 4);
    for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next(), b.next());
    // Each of seed, pixel and sample changes the stream.
    const Real first = rt::SampleStream(7, 123, 4).next();
    EXPECT_NE(rt::SampleStream(8, 123, 4).next(), first);
    EXPECT_NE(rt::SampleStream(7, 124, 4).next(), first);
    EXPECT_NE(rt::SampleStream(7, 123, 5).next(), first);
}

TEST(SampleStream, UniformInTheUnitInterval) {
    double sum = 0, sum2 = 0;
    int below_tenth = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        rt::SampleStream s(1, uint64_t(i), 0);
        const double x = s.next();
        ASSERT_GE(x, 0);
        ASSERT_LT(x, 1);
        sum += x;
        sum2 += x * x;
        below_tenth += x < 0.1;
    }
    // Mean 1/2 and variance 1/12, each within about 5 standard errors.
    EXPECT_NEAR(sum / n, 0.5, 0.004);
    EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12, 0.002);
    EXPECT_NEAR(double(below_tenth) / n, 0.1, 0.004);
}

// --- lights, lenses, rough surfaces: hand-computed ---------------------------------------

TEST(AreaLight, IrradianceIsRadianceTimesAreaTimesCosineOverDistanceSquared) {
    // A 2 x 2 square at the origin facing down; its centre drawn (xi = 1/2, 1/2).
    const rt::Light l = rt::Light::square({0, 0, 0}, {0, -1, 0}, 2, {10, 20, 30});
    rt::LightSample s = rt::sample_light(l, {0, -3, 0}, Real(0.5), Real(0.5));
    EXPECT_NEAR(s.from.x, 0, 1e-12);
    EXPECT_NEAR(s.scale.x, 10 * 4 * 1.0, 1e-5);  // L A cos, cos = 1 straight below
    EXPECT_NEAR(s.scale.z, 30 * 4 * 1.0, 1e-5);
    s = rt::sample_light(l, {3, -3, 0}, Real(0.5), Real(0.5));  // 45 degrees off its normal
    EXPECT_NEAR(s.scale.x, 10 * 4 * std::sqrt(0.5), 1e-5);
    // Lit on both faces (the references' glow on cornellbox_area's ceiling).
    s = rt::sample_light(l, {0, 3, 0}, Real(0.5), Real(0.5));
    EXPECT_NEAR(s.scale.x, 10 * 4 * 1.0, 1e-5);
    // Its corners at xi 0 and 1: 1 from the centre along each edge.
    const rt::LightSample c0 = rt::sample_light(l, {0, -3, 0}, 0, 0);
    EXPECT_NEAR(rt::length(c0.from), std::sqrt(2.0), 1e-6);
    EXPECT_NEAR(c0.from.y, 0, 1e-12);
    // A point light ignores the numbers: E = I / d^2 as before.
    const rt::Light p = rt::Light::point({1, 2, 3}, {5, 5, 5});
    EXPECT_FALSE(p.sampled());
    EXPECT_EQ(rt::sample_light(p, {}, Real(0.1), Real(0.9)).scale.x, 5);
}

TEST(Roughness, PerturbationTurnsWithinItsSquare) {
    const rt::Vec3 r = rt::normalize(rt::Vec3{1, 2, -2});
    const rt::Vec3 same = rt::perturb_direction(r, Real(0.4), Real(0.5), Real(0.5));
    EXPECT_NEAR(rt::dot(same, r), 1, 1e-6) << "the centre of the square is the ideal direction";
    // At a corner, r + 0.4 (-1/2 u - 1/2 v): the angle is atan(0.4 * sqrt(2) / 2).
    const rt::Vec3 corner = rt::perturb_direction(r, Real(0.4), 0, 0);
    EXPECT_NEAR(rt::length(corner), 1, 1e-6);
    EXPECT_NEAR(std::acos(std::min(Real(1), rt::dot(corner, r))), std::atan(0.4 * std::sqrt(2.0) / 2), 1e-5);
}

rt::Camera lens_camera() {
    rt::CameraDesc d;
    d.position = {0, 0, 0};
    d.gaze = {0, 0, -1};
    d.up = {0, 1, 0};
    d.left = d.bottom = -1;
    d.right = d.top = 1;
    d.near_distance = 1;
    d.width = d.height = 10;
    d.num_samples = 16;
    d.aperture_size = 2;
    d.focus_distance = 5;
    return rt::make_camera(d);
}

TEST(ThinLens, EveryLensPointSeesThePixelsPointOnTheFocusPlane) {
    // A few roundings of coordinates about 5 in the precision's own epsilon.
    const double tol = std::max(1e-12, 64 * double(std::numeric_limits<Real>::epsilon()));
    const rt::Camera cam = lens_camera();
    const rt::Ray pin = cam.sample_ray(3, 7, Real(0.25), Real(0.75), Real(0.5), Real(0.5), 0);
    EXPECT_NEAR(rt::length(pin.org), 0, tol) << "the lens's centre is the pinhole";
    const rt::Vec3 focus = pin.org + pin.dir * (5 / -pin.dir.z);  // on the plane z = -5
    for (const auto& [lx, ly] : std::vector<std::pair<Real, Real>>{{0, 0}, {1, 0}, {Real(0.3), Real(0.9)}}) {
        const rt::Ray r = cam.sample_ray(3, 7, Real(0.25), Real(0.75), lx, ly, 0);
        // The lens point: a square of side ApertureSize (2) about Position, in the u-v plane.
        EXPECT_NEAR(r.org.x, 2 * (lx - 0.5), tol);
        EXPECT_NEAR(r.org.y, 2 * (ly - 0.5), tol);
        EXPECT_NEAR(r.org.z, 0, tol);
        const rt::Vec3 at = r.org + r.dir * ((-5 - r.org.z) / r.dir.z);
        EXPECT_NEAR(rt::length(at - focus), 0, tol);
    }
}

TEST(PixelSamples, SquareCountsAreStratifiedOnePerCell) {
    rt::Camera cam = lens_camera();
    rt::PixelSampling s;
    s.samples = 16;
    s.grid = 4;
    s.seed = 3;
    std::set<std::pair<int, int>> cells;
    for (int k = 0; k < 16; ++k) {
        const rt::CameraSample c = rt::camera_sample(cam, s, 2, 2, k);
        ASSERT_GE(c.dx, 0);
        ASSERT_LT(c.dx, 1);
        cells.insert({int(c.dx * 4), int(c.dy * 4)});
    }
    EXPECT_EQ(cells.size(), 16u);
    // Without samples, through a pinhole: the centre ray, as before assignment 3.
    s.samples = 0;
    s.grid = 0;
    cam.aperture = 0;
    const rt::CameraSample centre = rt::camera_sample(cam, s, 2, 2, 0);
    EXPECT_EQ(centre.dx, Real(0.5));
    const rt::Ray want = cam.primary_ray(2, 2);
    EXPECT_EQ(centre.ray.dir.x, want.dir.x);
    EXPECT_EQ(centre.ray.org.x, want.org.x);
}

// --- renders --------------------------------------------------------------------------------

TEST(DistributionRender, SameBytesForAnyThreadCountAndSeedChangesNoise) {
    const rt::Scene s = build(everything());
    rt::RenderOptions o;
    o.threads = 1;
    const rt::Image one = rt::render(s, 0, o);
    o.threads = 3;
    EXPECT_EQ(rt::render(s, 0, o).rgb, one.rgb);
    o.parts = 2;  // the page's halves, merged
    rt::Image merged = rt::render(s, 0, o);
    o.part = 1;
    const rt::Image other = rt::render(s, 0, o);
    for (size_t i = 0; i < merged.rgb.size(); ++i) merged.rgb[i] = std::max(merged.rgb[i], other.rgb[i]);
    EXPECT_EQ(merged.rgb, one.rgb);
    o = {};
    o.sampling.seed = 12345;
    EXPECT_NE(rt::render(s, 0, o).rgb, one.rgb);
}

TEST(DistributionRender, SamplesOverrideAndRayCounts) {
    rt::Scene s = build(everything());
    rt::RenderOptions o;
    o.samples = 3;
    rt::apply_overrides(s, o);
    EXPECT_EQ(s.setup.cameras[0].samples, 3);
    rt::RenderStats st;
    (void)rt::render(s, 0, o, &st);
    EXPECT_EQ(st.rays.camera, uint64_t(24 * 20 * 3));
    EXPECT_GT(st.rays.shadow, 0u);
}

// A one-pixel camera looking down -z at a point: its samples all but one ray.
json pinpoint(const std::string& objects, const std::string& samples = "1024") {
    return json::parse(R"({"Scene": {"BackgroundColor": "0 0 0",
        "Cameras": {"Camera": {"Position": "2 0 10", "Gaze": "0 0 -1", "Up": "0 1 0",
            "NearPlane": "-1e-4 1e-4 -1e-4 1e-4", "NearDistance": "1", "ImageResolution": "1 1",
            "NumSamples": ")" +
                       samples + R"(", "ImageName": "p.png"}},
        "Lights": {"AmbientLight": "1 1 1"},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "200 200 200"}},
        "VertexData": {"_data": "0 0 0 -1 -1 0 1 -1 0 1 1 0 -1 1 0"},
        "Objects": )" + objects +
                       "}}");
}

// Through x = 2 the ray meets a unit shape moving from x = 0 by 4 over the shutter for
// times in (1/4, 3/4): half the samples, 100 of 200 levels. 1024 samples: a standard
// error of 200 * 0.5 / 32 = 3.1 levels; 4 of them allowed.
void expect_half_covered(const std::string& objects) {
    const rt::Image img = rt::render(build(pinpoint(objects)), 0, {});
    EXPECT_NEAR(img.rgb[0], 100, 12.5) << objects;
    // Still, it is never there.
    std::string still = objects;
    for (size_t at; (at = still.find("4 0 0")) != std::string::npos;) still.replace(at, 5, "0 0 0");
    EXPECT_EQ(rt::render(build(pinpoint(still)), 0, {}).rgb[0], 0) << still;
}

TEST(MotionBlur, EveryKindMovesOverTheShutter) {
    expect_half_covered(R"({"Sphere": {"Material": "1", "Center": "1", "Radius": "1", "MotionBlur": "4 0 0"}})");
    expect_half_covered(R"({"Mesh": {"Material": "1", "Faces": {"_data": "2 3 4 2 4 5"}, "MotionBlur": "4 0 0"}})");
    expect_half_covered(R"({"Triangle": [{"Material": "1", "Indices": "2 3 4", "MotionBlur": "4 0 0"},
        {"Material": "1", "Indices": "2 4 5", "MotionBlur": "4 0 0"}]})");
    // An instance moves as a whole; its base mesh stays where it is (x in -1..1).
    expect_half_covered(R"({"Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "2 3 4 2 4 5"}},
        "MeshInstance": {"_id": "2", "_baseMeshId": "1", "MotionBlur": "4 0 0"}})");
}

TEST(MotionBlur, BoundsCoverTheMotionWithoutRebuilding) {
    // A ray at time t meets the sphere where it is at t, whichever BVH leaf holds it.
    const rt::Scene s =
        build(pinpoint(R"({"Sphere": {"Material": "1", "Center": "1", "Radius": "1", "MotionBlur": "10 0 0"}})", "4"));
    EXPECT_TRUE(s.geometry.moves);
    for (const Real t : {Real(0), Real(0.25), Real(0.5), Real(0.99)}) {
        rt::Hit h;
        const rt::Ray r{{10 * t, 0, 10}, {0, 0, -1}, t};
        ASSERT_TRUE(rt::closest_hit(s, r, 0, HUGE_VAL, true, h)) << "t " << t;
        EXPECT_NEAR(h.t, 9, 1e-9);
        rt::Ray miss = r;
        miss.time = t + Real(0.3) > 1 ? t - Real(0.3) : t + Real(0.3);
        EXPECT_FALSE(rt::closest_hit(s, miss, 0, HUGE_VAL, true, h)) << "t " << t;
    }
}

TEST(AreaLight, NotSeenByCameraRays) {
    // Looking straight at the light's face: the background, not the emitter.
    json j = pinpoint(R"({"Sphere": {"Material": "1", "Center": "1", "Radius": "0.1"}})", "4");
    j["Scene"]["Lights"]["AreaLight"] = {
        {"Position", "2 0 0"}, {"Normal", "0 0 1"}, {"Size", "4"}, {"Radiance", "1000 1000 1000"}};
    j["Scene"]["BackgroundColor"] = "7 7 7";
    EXPECT_EQ(rt::render(build(j), 0, {}).rgb[0], 7);
}

}  // namespace
