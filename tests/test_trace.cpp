// raytracer --trace (issue 15): one pixel's ray tree, recorded by the integrator itself.
//
// The contract:
//   - the traced pixel's final value is the rendered image's pixel, byte for byte
//     (random pixels of every official scene, in process and through ./raytracer);
//   - hits are named as the scene file names them (Mesh _id and face index counting
//     skipped degenerate faces, Triangle, Sphere, Plane _ids);
//   - the tree shows Fresnel, refraction, total internal reflection and Beer's law where
//     the geometry forces them (a glass prism built here);
//   - a pixel outside the image, a camera the scene lacks, or --camera/--trace-json
//     without --trace are usage errors (exit 2, nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/core/error.h"
#include "rt/image/image.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/trace.h"
#include "test_support.h"

using json = nlohmann::json;

namespace {

// Tolerance of the hand-computed figures: a few operations in the renderer's
// precision, so a few units of its roundoff (1e-12, far above double's, serves double).
const double kTol = std::max(1e-12, 16 * double(std::numeric_limits<rt::Real>::epsilon()));

// The scene files of the complete rows of the official MANIFEST.tsv (each once).
std::vector<std::string> official_scenes() {
    std::vector<std::string> out;
    const std::string root = shared_dir();
    if (root.empty()) return out;
    std::ifstream f(root + "/scenes/hw1/MANIFEST.tsv");
    std::set<std::string> seen;
    for (std::string line; std::getline(f, line);) {
        if (line.empty() || line[0] == '#') continue;
        std::vector<std::string> cols;
        std::stringstream ss(line);
        for (std::string c; std::getline(ss, c, '\t');) cols.push_back(c);
        if (cols.size() >= 4 && cols[3] == "complete" && seen.insert(cols[0]).second)
            out.push_back(root + "/scenes/hw1/" + cols[0]);
    }
    return out;
}

std::vector<uint8_t> pixel_of(const rt::Image& img, int x, int y) {
    const size_t at = (size_t(y) * size_t(img.width) + size_t(x)) * 3;
    return {img.rgb[at], img.rgb[at + 1], img.rgb[at + 2]};
}

std::string dump(const RunResult& r) {
    return "\n--- exit " + std::to_string(r.exit_code) + " --- stderr ---\n" + r.err + "--- stdout ---\n" + r.out +
           "---";
}

// ./raytracer `options` --trace `pixel` ("x,y") --trace-json `json_path` `scene`: the run,
// and its JSON trace parsed (null when the run failed: callers assert the exit code).
struct Traced {
    RunResult run;
    json doc;
};
Traced trace_run(const std::string& scene, const std::string& pixel, const std::string& json_path,
                 std::vector<std::string> options = {}) {
    options.insert(options.end(), {"--trace", pixel, "--trace-json", json_path, scene});
    Traced t{run_raytracer(options), json()};
    if (t.run.exit_code == 0) t.doc = json::parse(read_text(json_path));
    return t;
}

// A glass prism (index 1.5) seen head-on: cross-section x in [-1, 1] at z = -2 (the
// front face, towards the camera), the hypotenuse from (x -1, z -2) to (x 1, z -4) and
// the side x = 1. Every face winds counter-clockwise seen from outside. A camera ray
// along -z enters the front face at normal incidence, meets the hypotenuse inside at
// 45 degrees, beyond the critical angle asin(1/1.5) = 41.8 degrees: total internal
// reflection, along +x, out through the side at normal incidence. Face 0 of the mesh
// is degenerate (skipped), so the faces hit are 1 (front), 4 (hypotenuse) and 5 (side).
const char* const kPrismScene = R"({"Scene": {
  "BackgroundColor": "0 0 0", "ShadowRayEpsilon": "1e-3", "MaxRecursionDepth": "4",
  "Cameras": {"Camera": {"_id": "1", "Position": "0.3 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
    "NearPlane": "-0.1 0.1 -0.1 0.1", "NearDistance": "1", "ImageResolution": "5 5", "ImageName": "prism.png"}},
  "Lights": {"AmbientLight": "10 10 10", "PointLight": {"_id": "1", "Position": "0 5 5", "Intensity": "1000 1000 1000"}},
  "Materials": {"Material": {"_id": "4", "_type": "dielectric", "AmbientReflectance": "0 0 0",
    "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0", "PhongExponent": "1",
    "MirrorReflectance": "1 1 1", "RefractionIndex": "1.5", "AbsorptionCoefficient": "0.1 0.2 0.3"}},
  "VertexData": {"_data": "-1 -1 -2  1 -1 -2  1 1 -2  -1 1 -2  1 -1 -4  1 1 -4", "_type": "xyz"},
  "Objects": {"Mesh": {"_id": "7", "Material": "4",
    "Faces": {"_data": "1 1 2  1 2 3  1 3 4  1 4 6  1 6 5  2 5 6  2 6 3", "_type": "triangle"}}}
}})";

}  // namespace

// ---- The traced pixel is the rendered pixel -------------------------------------------

TEST(Trace, TracedPixelsEqualTheRenderInEveryOfficialScene) {
    SKIP_UNLESS_SHARED("the official scenes' traces");
    const std::vector<std::string> scenes = official_scenes();
    ASSERT_FALSE(scenes.empty()) << shared_dir() << "/scenes/hw1/MANIFEST.tsv lists no complete scene";
    std::mt19937 rng(15);
    size_t traced = 0;
    for (const std::string& path : scenes) {
        const rt::Scene scene = rt::build_scene(rt::load_scene(path));
        for (size_t c = 0; c < scene.setup.cameras.size(); ++c) {
            const rt::Camera& cam = scene.setup.cameras[c];
            for (rt::Rounding rounding : {rt::Rounding::Truncate, rt::Rounding::Nearest}) {
                rt::RenderOptions ro;
                ro.threads = 2;
                ro.rounding = rounding;
                const rt::Image img = rt::render(scene, c, ro);
                for (int i = 0; i < 12; ++i) {
                    const int x = std::uniform_int_distribution<int>(0, cam.width - 1)(rng);
                    const int y = std::uniform_int_distribution<int>(0, cam.height - 1)(rng);
                    const rt::PixelTrace t = rt::trace_pixel(scene, c, x, y, rt::TraceOptions{true}, rounding);
                    EXPECT_EQ(std::vector<uint8_t>(t.pixel, t.pixel + 3), pixel_of(img, x, y))
                        << path << " camera " << c + 1 << " pixel " << x << "," << y;
                    ++traced;
                }
            }
        }
    }
    EXPECT_GE(traced, 20u * 2 * 12);
}

TEST(Trace, CommandLineTracePixelEqualsTheWrittenImageInEveryOfficialScene) {
    SKIP_UNLESS_SHARED("the official scenes' traces");
    const std::vector<std::string> scenes = official_scenes();
    ASSERT_FALSE(scenes.empty()) << shared_dir() << "/scenes/hw1/MANIFEST.tsv lists no complete scene";
    std::mt19937 rng(1507);
    TempDir tmp;
    for (const std::string& path : scenes) {
        const RunResult render = run_raytracer({"-q", "-j", "2", "-o", tmp.path(), path});
        ASSERT_EQ(render.exit_code, 0) << path << dump(render);
        const rt::SceneDesc desc = rt::load_scene(path);
        const size_t c = std::uniform_int_distribution<size_t>(0, desc.cameras.size() - 1)(rng);
        const rt::CameraDesc& cam = desc.cameras[c];
        const int x = std::uniform_int_distribution<int>(0, cam.width - 1)(rng);
        const int y = std::uniform_int_distribution<int>(0, cam.height - 1)(rng);
        const auto [r, doc] = trace_run(path, std::to_string(x) + "," + std::to_string(y), tmp / "trace.json",
                                        {"-q", "--camera", std::to_string(c + 1)});
        ASSERT_EQ(r.exit_code, 0) << path << dump(r);
        rt::Image img;
        ASSERT_TRUE(load_png(tmp / cam.image_name, img)) << tmp / cam.image_name;
        const std::vector<uint8_t> expected = pixel_of(img, x, y);
        EXPECT_EQ(doc["pixel"].get<std::vector<int>>(), std::vector<int>(expected.begin(), expected.end()))
            << path << " camera " << c + 1 << " pixel " << x << "," << y;
        // The text's last line (folded at 100 characters) names the same value.
        const std::string last = "\npixel [" + std::to_string(expected[0]) + ", " + std::to_string(expected[1]) + ", " +
                                 std::to_string(expected[2]) + "] after rounding (truncate),";
        const size_t at = r.out.rfind("\npixel [");
        EXPECT_TRUE(at != std::string::npos && r.out.compare(at, last.size(), last) == 0) << path << dump(r);
        // Every line fits a terminal of 100 columns.
        for (const std::string& line : split_lines(r.out)) EXPECT_LE(line.size(), 100u) << path << ": " << line;
        // --trace renders nothing: only the JSON and the images of the render are there.
        EXPECT_FALSE(file_exists(tmp / "trace.json.tmp"));
    }
}

// ---- Names, TIR, Fresnel, Beer's law ----------------------------------------------------

TEST(Trace, ShapeNamesCountSkippedFacesAndUseTheFilesIds) {
    rt::SceneDesc d;
    d.materials.push_back({});
    rt::MeshDesc a;  // faces: 0 degenerate, 1 ok, 2 and 3 degenerate, 4 ok
    a.id = "5";
    a.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
    a.indices = {0, 1, 3, 0, 1, 2, 0, 0, 1, 1, 3, 1, 0, 2, 1};
    rt::MeshDesc b = a;  // all degenerate
    b.id = "6";
    b.indices = {0, 1, 3};
    rt::MeshDesc tri;
    tri.id = "9";
    tri.triangle_object = true;
    tri.positions = {{0, 0, 1}, {1, 0, 1}, {0, 1, 1}};
    tri.indices = {0, 1, 2};
    d.meshes = {a, b, tri};
    d.all<rt::SphereDesc>().push_back({{0, "3", nullptr, {}}, {0, 0, 5}, 1, {}});
    d.all<rt::PlaneDesc>().push_back({{0, "11", nullptr, {}}, {0, 0, -5}, {0, 0, 1}});
    const rt::Scene s = rt::build_scene(d);
    ASSERT_EQ(s.geometry.triangles.size(), 3u);
    EXPECT_EQ(s.names.name({rt::ShapeKind::Triangle, 0}), "Mesh 5, face 1");
    EXPECT_EQ(s.names.name({rt::ShapeKind::Triangle, 1}), "Mesh 5, face 4");
    EXPECT_EQ(s.names.name({rt::ShapeKind::Triangle, 2}), "Triangle 9");
    EXPECT_EQ(s.names.name({rt::ShapeKind::Sphere, 0}), "Sphere 3");
    EXPECT_EQ(s.names.name({rt::ShapeKind::Plane, 0}), "Plane 11");
}

// Instances' names share one buffer (rt/geometry/shape_names.h): each keeps its own _id,
// whatever the lengths around it, and the key of the entry it came from.
TEST(Trace, InstanceNamesKeepTheirIdsAndKeys) {
    const std::string scene = R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-0.1 0.1 -0.1 0.1", "NearDistance": "1", "ImageResolution": "3 3", "ImageName": "c.png"}},
      "Materials": {"Material": {"AmbientReflectance": "1 1 1"}},
      "Transformations": {"Translation": {"_id": "1", "_data": "0 0 2"}},
      "VertexData": {"_data": "-1 -1 0  1 -1 0  1 1 0  -1 1 0", "_type": "xyz"},
      "Objects": {"Mesh": {"_id": "3", "Material": "1", "Transformations": "t1",
                           "Faces": {"_data": "1 2 3  1 3 4", "_type": "triangle"}},
                  "Triangle": {"_id": "t-17", "Material": "1", "Indices": "1 2 3", "Transformations": "t1"},
                  "MeshInstance": [{"_id": "a much longer instance name than SSO holds", "_baseMeshId": "3"},
                                   {"_baseMeshId": "3"},
                                   {"_id": "", "_baseMeshId": "3"},
                                   {"_id": 42, "_baseMeshId": "3"}]}}})";
    const rt::Scene s = rt::build_scene(rt::parse_scene(scene, "/nonexistent/names.json"));
    const std::vector<std::string> expected = {
        "Mesh 3",         "Triangle t-17", "MeshInstance a much longer instance name than SSO holds",
        "MeshInstance 2", "MeshInstance ", "MeshInstance 42"};
    ASSERT_EQ(s.geometry.count(rt::ShapeKind::Instance), expected.size());
    for (uint32_t i = 0; i < expected.size(); ++i)
        EXPECT_EQ(s.names.name({rt::ShapeKind::Instance, i}), expected[i]) << i;
    EXPECT_EQ(s.names.name({rt::ShapeKind::Instance, 6}), "instance #6");  // past the names: no name
}

TEST(Trace, PrismShowsTotalInternalReflection) {
    TempDir tmp;
    write_text(tmp / "prism.json", kPrismScene);
    const auto [r, doc] = trace_run(tmp / "prism.json", "2,2", tmp / "t.json");
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_EQ(list_files(tmp.path()), (std::vector<std::string>{"prism.json", "t.json"})) << "no image";
    const json& cam = doc["ray"];
    EXPECT_EQ(cam["kind"], "camera");
    EXPECT_EQ(cam["hit"]["object"], "Mesh 7, face 1");
    EXPECT_EQ(cam["hit"]["front"], true);
    EXPECT_EQ(cam["hit"]["material"]["id"], "4");
    EXPECT_EQ(cam["hit"]["material"]["type"], "dielectric");
    // Normal incidence, 1 -> 1.5: R = (0.5 / 2.5)^2.
    EXPECT_NEAR(cam["fresnel"]["reflectance"].get<double>(), 0.04, kTol);
    EXPECT_EQ(cam["fresnel"]["total_internal_reflection"], false);
    ASSERT_EQ(cam["children"].size(), 2u);
    const json& in = cam["children"][1];
    EXPECT_EQ(in["kind"], "refraction");
    EXPECT_EQ(in["depth"], 1);
    EXPECT_EQ(in["cull"], false);
    EXPECT_EQ(in["inside_material"], "4");
    EXPECT_EQ(in["hit"]["object"], "Mesh 7, face 4");
    EXPECT_EQ(in["hit"]["front"], false);
    EXPECT_EQ(in["shaded"], false);
    EXPECT_EQ(in["fresnel"]["reflectance"], 1.0);
    EXPECT_EQ(in["fresnel"]["total_internal_reflection"], true);
    EXPECT_TRUE(in["fresnel"]["refracted"].is_null());
    // Beer's law over the path inside, front face to hypotenuse: 1.3 less the offset.
    const double d = in["beer"]["distance"].get<double>();
    EXPECT_NEAR(d, 1.3, 2e-3);
    EXPECT_NEAR(in["beer"]["attenuation"][2].get<double>(), std::exp(-0.3 * d), kTol);
    ASSERT_EQ(in["children"].size(), 1u) << "total internal reflection: no refraction ray";
    const json& tir = in["children"][0];
    EXPECT_EQ(tir["kind"], "reflection");
    EXPECT_EQ(tir["inside_material"], "4");
    EXPECT_NEAR(tir["direction"][0].get<double>(), 1, kTol);
    EXPECT_EQ(tir["hit"]["object"], "Mesh 7, face 5");
    EXPECT_EQ(tir["hit"]["front"], false);
    EXPECT_NEAR(tir["fresnel"]["reflectance"].get<double>(), 0.04, kTol);  // 1.5 -> 1, normal incidence
    EXPECT_FALSE(tir["fresnel"]["refracted"].is_null());
    // The text says the same.
    EXPECT_TRUE(contains(r.out, "hit Mesh 7, face 4")) << dump(r);
    EXPECT_TRUE(contains(r.out, "total internal reflection")) << dump(r);
    EXPECT_TRUE(contains(r.out, "Beer's law over distance")) << dump(r);
}

TEST(Trace, LightsAreReportedLitOrShadowedByTheirOccluder) {
    // A plane lit by two lights; a sphere between the plane and the second light.
    const char* scene = R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-0.1 0.1 -0.1 0.1", "NearDistance": "1", "ImageResolution": "3 3", "ImageName": "l.png"}},
      "Lights": {"PointLight": [{"Position": "0 0 4", "Intensity": "100 100 100"},
                                {"Position": "0 4 2", "Intensity": "100 100 100"}]},
      "Materials": {"Material": {"_id": "2", "DiffuseReflectance": "1 1 1"}},
      "VertexData": {"_data": "0 0 0  0 2 1", "_type": "xyz"},
      "Objects": {"Sphere": {"_id": "8", "Material": "2", "Center": "2", "Radius": "0.5"},
                  "Plane": {"_id": "3", "Material": "2", "Point": "1", "Normal": "0 0 1"}}}})";
    TempDir tmp;
    write_text(tmp / "l.json", scene);
    const auto [r, doc] = trace_run(tmp / "l.json", "1,1", tmp / "t.json");
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    const json& ray = doc["ray"];
    EXPECT_EQ(ray["hit"]["object"], "Plane 3");
    ASSERT_EQ(ray["lights"].size(), 2u);
    const json& lit = ray["lights"][0];
    EXPECT_EQ(lit["shadowed"], false);
    EXPECT_NEAR(lit["n_dot_l"].get<double>(), 1, kTol);
    EXPECT_NEAR(lit["irradiance"][0].get<double>(), 100.0 / 16, 1e-9);  // I / d^2, d = 4
    EXPECT_NEAR(lit["diffuse"][0].get<double>(), 100.0 / 16, 1e-9);
    const json& dark = ray["lights"][1];
    EXPECT_EQ(dark["shadowed"], true);
    EXPECT_EQ(dark["occluder"]["object"], "Sphere 8");
    EXPECT_TRUE(dark.find("irradiance") == dark.end());
    // Only the first light counts: the pixel is 100/16 = 6.25, truncated to 6.
    EXPECT_EQ(doc["pixel"], json({6, 6, 6}));
    EXPECT_TRUE(contains(r.out, "shadowed by Sphere 8 at t = ")) << dump(r);
    // Both name the precision that traced (run_raytracer passes the suite's own).
    EXPECT_EQ(doc["precision"], rt::kPrecisionName);
    EXPECT_TRUE(contains(r.out, std::string(", ") + rt::kPrecisionName + "), MaxRecursionDepth ")) << dump(r);
}

TEST(Trace, ABackFaceTheCameraRayPassesOverIsReported) {
    // A triangle at z = 2 wound clockwise seen from the camera (its front faces -z), in front
    // of a plane at z = 0: culled, the camera ray passes it (t = 3) and hits the plane (t = 5).
    const char* scene = R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-0.1 0.1 -0.1 0.1", "NearDistance": "1", "ImageResolution": "3 3", "ImageName": "c.png"}},
      "Materials": {"Material": {"AmbientReflectance": "1 1 1"}},
      "Lights": {"AmbientLight": "10 10 10"},
      "VertexData": {"_data": "0 0 0  -1 -1 2  0 1 2  1 -1 2", "_type": "xyz"},
      "Objects": {"Triangle": {"_id": "5", "Material": "1", "Indices": "2 3 4"},
                  "Plane": {"_id": "2", "Material": "1", "Point": "1", "Normal": "0 0 1"}}}})";
    TempDir tmp;
    write_text(tmp / "c.json", scene);
    const auto [culled, a] = trace_run(tmp / "c.json", "1,1", tmp / "a.json");
    ASSERT_EQ(culled.exit_code, 0) << dump(culled);
    EXPECT_EQ(a["ray"]["hit"]["object"], "Plane 2");
    EXPECT_NEAR(a["ray"]["hit"]["t"].get<double>(), 5, kTol);
    EXPECT_EQ(a["ray"]["culled"]["object"], "Triangle 5");
    EXPECT_NEAR(a["ray"]["culled"]["t"].get<double>(), 3, kTol);
    EXPECT_TRUE(contains(culled.out, "back face culled: Triangle 5 at t = 3")) << dump(culled);
    const auto [all, b] = trace_run(tmp / "c.json", "1,1", tmp / "b.json", {"--no-cull"});
    ASSERT_EQ(all.exit_code, 0) << dump(all);
    EXPECT_EQ(b["ray"]["hit"]["object"], "Triangle 5");
    EXPECT_EQ(b["ray"]["hit"]["front"], false);
    EXPECT_EQ(b["ray"]["cull"], false);
    EXPECT_TRUE(b["ray"]["culled"].is_null());
}

// The Fresnel terms a student checks their Snell step against: at the prism's front face
// (normal incidence, 1 -> 1.5) and where the ray leaves through the side (1.5 -> 1), the
// indices, cosines, sin^2 of the refraction angle and both polarisations; at the
// hypotenuse, total internal reflection (sin^2 theta_t >= 1). Snell's law and the average
// of the polarisations hold in the JSON; the text prints the same terms.
TEST(Trace, FresnelTermsOfADielectricAreShown) {
    TempDir tmp;
    write_text(tmp / "prism.json", kPrismScene);
    const auto [r, doc] = trace_run(tmp / "prism.json", "2,2", tmp / "t.json");
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    const json& front = doc["ray"]["fresnel"];
    EXPECT_EQ(front["n1"], 1.0);
    EXPECT_EQ(front["n2"], 1.5);
    EXPECT_NEAR(front["cos_i"].get<double>(), 1, kTol);
    EXPECT_NEAR(front["sin2_t"].get<double>(), 0, kTol);
    EXPECT_NEAR(front["cos_t"].get<double>(), 1, kTol);
    EXPECT_NEAR(front["r_parallel"].get<double>(), 0.04, kTol);  // ((1.5 - 1) / 2.5)^2 for both
    EXPECT_NEAR(front["r_perpendicular"].get<double>(), 0.04, kTol);
    const json& hyp = doc["ray"]["children"][1]["fresnel"];
    EXPECT_EQ(hyp["n1"], 1.5);
    EXPECT_EQ(hyp["n2"], 1.0);
    EXPECT_NEAR(hyp["cos_i"].get<double>(), std::sqrt(0.5), 1e-6);  // 45 degrees
    EXPECT_NEAR(hyp["sin2_t"].get<double>(), 1.125, 1e-5);          // 1.5^2 * 0.5: total internal reflection
    EXPECT_EQ(hyp["cos_t"], 0.0);
    EXPECT_EQ(hyp["r_parallel"], 1.0);
    EXPECT_EQ(hyp["r_perpendicular"], 1.0);
    for (const json* f : {&front, &doc["ray"]["children"][1]["children"][0]["fresnel"]}) {
        const double n1 = (*f)["n1"], n2 = (*f)["n2"], ci = (*f)["cos_i"], s2 = (*f)["sin2_t"], ct = (*f)["cos_t"];
        EXPECT_NEAR(n1 * n1 * (1 - ci * ci), n2 * n2 * s2, kTol);  // Snell: n1 sin_i = n2 sin_t
        EXPECT_NEAR(ct * ct + s2, 1, kTol);
        EXPECT_NEAR(((*f)["r_parallel"].get<double>() + (*f)["r_perpendicular"].get<double>()) / 2,
                    (*f)["reflectance"].get<double>(), kTol);
    }
    EXPECT_TRUE(contains(r.out, "Fresnel (dielectric): n1 1 -> n2 1.5, cos theta_i 1, sin^2 theta_t 0, cos theta_t 1"))
        << dump(r);
    EXPECT_TRUE(contains(r.out, "Fresnel (dielectric): n1 1.5 -> n2 1, cos theta_i 0.7071067")) << dump(r);
    EXPECT_TRUE(contains(r.out, "sin^2 theta_t 1.125")) << dump(r);
    EXPECT_TRUE(contains(r.out, "R parallel 0.04")) << dump(r);
    EXPECT_TRUE(contains(r.out, "total internal reflection: no refracted ray")) << dump(r);
}

// A conductor's complex index n + i k and its two polarisations; at normal incidence
// both are ((n - 1)^2 + k^2) / ((n + 1)^2 + k^2).
TEST(Trace, FresnelTermsOfAConductorAreShown) {
    json j = json::parse(kPrismScene);
    j["Scene"]["Materials"]["Material"] = json::parse(R"({"_id": "4", "_type": "conductor",
        "MirrorReflectance": "1 1 1", "RefractionIndex": "0.37", "AbsorptionIndex": "2.82"})");
    TempDir tmp;
    write_text(tmp / "gold.json", j.dump());
    const auto [r, doc] = trace_run(tmp / "gold.json", "2,2", tmp / "t.json");
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    const json& f = doc["ray"]["fresnel"];
    EXPECT_EQ(f["n1"], 1.0);
    EXPECT_NEAR(f["n2"].get<double>(), 0.37, 1e-6);
    EXPECT_NEAR(f["k"].get<double>(), 2.82, 1e-6);
    const double n = 0.37, k = 2.82, r0 = ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    EXPECT_NEAR(f["r_parallel"].get<double>(), r0, 1e-6);
    EXPECT_NEAR(f["r_perpendicular"].get<double>(), r0, 1e-6);
    EXPECT_NEAR(f["reflectance"].get<double>(), r0, 1e-6);
    EXPECT_TRUE(f.find("cos_t") == f.end()) << "a conductor refracts nothing";
    EXPECT_TRUE(contains(r.out, "Fresnel (conductor): n1 1 -> n2 0.37 + 2.82i, cos theta_i 1")) << dump(r);
}

// On a back-face hit the printed geometric and shading normals are the outward ones; the
// facing normal is the shading normal turned towards the ray, and the offsets follow it.
TEST(Trace, BackFaceHitNamesWhichWayEachNormalPoints) {
    TempDir tmp;
    write_text(tmp / "prism.json", kPrismScene);
    const auto [r, doc] = trace_run(tmp / "prism.json", "2,2", tmp / "t.json");
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    const json& hit = doc["ray"]["children"][1]["hit"];  // the hypotenuse, from inside
    ASSERT_EQ(hit["front"], false);
    for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(hit["facing_normal"][a].get<double>(), -hit["shading_normal"][a].get<double>());
        // Outward: away from the prism's inside, towards +z and -x.
    }
    EXPECT_LT(hit["shading_normal"][0].get<double>(), 0);
    EXPECT_LT(hit["shading_normal"][2].get<double>(), 0);
    // The reflected ray starts on the ray's side: point + facing normal x eps.
    const json& refl = doc["ray"]["children"][1]["children"][0];
    for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(refl["origin"][a].get<double>(),
                    hit["point"][a].get<double>() + 1e-3 * hit["facing_normal"][a].get<double>(), kTol);
    EXPECT_TRUE(contains(r.out, "back face: the ray meets the inside; the outward normals point away from it"))
        << dump(r);
    EXPECT_TRUE(contains(r.out, ", outward: the lights use it")) << dump(r);
    EXPECT_TRUE(contains(r.out, ": the shading normal turned towards the ray")) << dump(r);
    EXPECT_TRUE(contains(r.out, "reflected rays start at (")) << dump(r);
}

// --min-weight: two facing half mirrors (MirrorReflectance 0.5) at MaxRecursionDepth 20.
// The default 1e-4 stops the bounces once 0.5^d < 1e-4 (d = 14); 0 traces all 20, and
// 0.3 only the first. The text says why a ray was not traced; the JSON has the option.
TEST(Trace, MinWeightDecidesWhichRaysAreTraced) {
    const char* scene = R"({"Scene": {"MaxRecursionDepth": "20",
      "Cameras": {"Camera": {"Position": "0 0 0.5", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-0.01 0.01 -0.01 0.01", "NearDistance": "1", "ImageResolution": "1 1", "ImageName": "m.png"}},
      "Lights": {"AmbientLight": "10 10 10"},
      "Materials": {"Material": {"_type": "mirror", "AmbientReflectance": "1 1 1", "MirrorReflectance": "0.5 0.5 0.5"}},
      "VertexData": "0 0 -1  0 0 1",
      "Objects": {"Plane": [{"Material": "1", "Point": "1", "Normal": "0 0 1"},
                            {"Material": "1", "Point": "2", "Normal": "0 0 -1"}]}}})";
    TempDir tmp;
    write_text(tmp / "m.json", scene);
    // The depth of the deepest traced ray, and whether a ray was left untraced.
    const auto deepest = [](const json& doc) {
        int depth = 0;
        bool skipped = false;
        for (const json* n = &doc["ray"]; n;) {
            if (!(*n)["traced"].get<bool>()) {
                skipped = true;
                break;
            }
            depth = (*n)["depth"];
            n = (*n)["children"].empty() ? nullptr : &(*n)["children"][0];
        }
        return std::make_pair(depth, skipped);
    };
    const auto [def, d_doc] = trace_run(tmp / "m.json", "0,0", tmp / "d.json");
    ASSERT_EQ(def.exit_code, 0) << dump(def);
    EXPECT_EQ(d_doc["min_weight"], 1e-4);
    EXPECT_EQ(deepest(d_doc), std::make_pair(13, true));  // 0.5^13 >= 1e-4 > 0.5^14
    EXPECT_TRUE(contains(def.out, "not traced (weight below --min-weight 0.0001)")) << dump(def);
    const auto [all, a_doc] = trace_run(tmp / "m.json", "0,0", tmp / "a.json", {"--min-weight", "0"});
    ASSERT_EQ(all.exit_code, 0) << dump(all);
    EXPECT_EQ(deepest(a_doc), std::make_pair(20, false));
    EXPECT_FALSE(contains(all.out, "not traced")) << dump(all);
    const auto [few, f_doc] = trace_run(tmp / "m.json", "0,0", tmp / "f.json", {"--min-weight=0.3"});
    ASSERT_EQ(few.exit_code, 0) << dump(few);
    EXPECT_EQ(deepest(f_doc), std::make_pair(1, true));
    // The render takes the option too, and --stats records it: 10 + 5 + 2.5 + ... over 21
    // terms with 0 (and over 14 at the default, also 19 once truncated); 0.3 stops after
    // the first reflection, 10 + 5.
    const auto render_with = [&](const std::string& weight) {
        const RunResult r = run_raytracer({"-q", "--min-weight", weight, "--stats", "s.json", "m.json"}, tmp.path());
        EXPECT_EQ(r.exit_code, 0) << dump(r);
        rt::Image img;
        EXPECT_TRUE(load_png(tmp / "m.png", img));
        const json stats = json::parse(read_text(tmp / "s.json"));
        EXPECT_EQ(stats["images"][0]["min_weight"], std::stod(weight));
        return img.rgb.empty() ? -1 : int(img.rgb[0]);
    };
    EXPECT_EQ(render_with("0"), 19);  // 20 (1 - 0.5^21) = 19.99999, truncated
    EXPECT_EQ(render_with("0.3"), 15);
    const RunResult bad = run_raytracer({"--min-weight", "2", "m.json"}, tmp.path());
    EXPECT_EQ(bad.exit_code, 2) << dump(bad);
    EXPECT_TRUE(contains(bad.err, "error: --min-weight needs a number from 0 to 1, got '2'")) << dump(bad);
}

// ---- Usage errors -----------------------------------------------------------------------

TEST(Trace, UsageErrorsExitTwoAndWriteNothing) {
    TempDir tmp;
    write_text(tmp / "prism.json", kPrismScene);
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--trace", "5,0", "prism.json"}, "--trace 5,0: outside the 5x5 image of camera 1 (x 0..4, y 0..4)"},
        {{"--trace", "0,5", "prism.json"}, "--trace 0,5: outside the 5x5 image of camera 1 (x 0..4, y 0..4)"},
        {{"--trace", "-1,0", "prism.json"}, "--trace X needs a whole number from 0 to 1073741824, got '-1'"},
        {{"--trace", "3", "prism.json"}, "--trace needs X,Y, got '3'"},
        {{"--trace", "1,1", "--camera", "2", "prism.json"}, "--camera 2: prism.json has 1 camera"},
        {{"--trace", "1,1", "--camera", "0", "prism.json"},
         "--camera needs a whole number from 1 to 1073741824, got '0'"},
        {{"--camera", "1", "prism.json"}, "--camera, --sample and --trace-json need --trace"},
        {{"--trace-json", "t.json", "prism.json"}, "--camera, --sample and --trace-json need --trace"},
        {{"--sample", "2", "prism.json"}, "--camera, --sample and --trace-json need --trace"},
        {{"--trace", "1,1", "prism.json", "prism.json"}, "--trace takes one scene file"},
    };
    for (const auto& [args, message] : cases) {
        const RunResult r = run_raytracer(args, tmp.path());
        std::string all;
        for (const std::string& a : args) all += a + " ";
        EXPECT_EQ(r.exit_code, 2) << all << dump(r);
        EXPECT_TRUE(contains(r.err, "error: " + message + "\nusage: raytracer ")) << all << dump(r);
        EXPECT_EQ(r.out, "") << all;
    }
    EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"prism.json"});
}

TEST(Trace, BadSceneIsBadInput) {
    TempDir tmp;
    json j = json::parse(kPrismScene);
    j["Scene"]["Objects"]["Mesh"]["Material"] = "5";  // no such material
    write_text(tmp / "bad.json", j.dump());
    const RunResult r = run_raytracer({"--trace", "0,0", tmp / "bad.json"});
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_EQ(r.err, "error: " + tmp / "bad.json" +
                         ": /Scene/Objects/Mesh/Material: material id 5 does not exist (1 material defined)\n")
        << dump(r);
    EXPECT_EQ(r.out, "");
}

TEST(Trace, AnInstanceHitNamesItsMeshFaceAndTheObjectSpacePoint) {
    // Mesh 3 (faces 0 and 1, a quad at z = 0) is drawn by instance 8, moved by
    // (0, 0, 2) and scaled by 2: the camera ray (0, 0, 5) -> -z hits the instance at
    // z = 2, t = 3, which is the mesh's point (0, 0, 0) -- on the diagonal: face 0 or 1.
    const char* scene = R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-0.1 0.1 -0.1 0.1", "NearDistance": "1", "ImageResolution": "3 3", "ImageName": "c.png"}},
      "Materials": {"Material": {"AmbientReflectance": "1 1 1"}},
      "Lights": {"AmbientLight": "10 10 10"},
      "Transformations": {"Translation": {"_id": "1", "_data": "0 0 2"}, "Scaling": {"_id": "1", "_data": "2 2 2"}},
      "VertexData": {"_data": "-1 -1 0  1 -1 0  1 1 0  -1 1 0", "_type": "xyz"},
      "Objects": {"Mesh": {"_id": "3", "Material": "1", "Transformations": "t1 t1 t1",
                           "Faces": {"_data": "1 2 3  1 3 4", "_type": "triangle"}},
                  "MeshInstance": {"_id": "8", "_baseMeshId": "3", "_resetTransform": "true",
                                   "Transformations": "s1 t1"}}}})";
    TempDir tmp;
    write_text(tmp / "c.json", scene);
    const auto [run, doc] = trace_run(tmp / "c.json", "1,1", tmp / "a.json");
    ASSERT_EQ(run.exit_code, 0) << dump(run);
    const json& hit = doc["ray"]["hit"];
    EXPECT_EQ(hit["object"], "MeshInstance 8");
    EXPECT_NEAR(hit["t"].get<double>(), 3, kTol);
    const std::string face = hit["object_space"]["face"];
    EXPECT_TRUE(face == "Mesh 3, face 0" || face == "Mesh 3, face 1") << face;
    for (int a = 0; a < 3; ++a) EXPECT_NEAR(hit["object_space"]["point"][a].get<double>(), 0, kTol);
    EXPECT_TRUE(contains(run.out, "in its mesh's own space: " + face + ", point (")) << dump(run);
    // The mesh itself (moved by t1 three times, to z = 6, behind the camera) is not hit.
    EXPECT_EQ(run.out.find("hit Mesh 3"), std::string::npos) << dump(run);
}

// ---- Distribution ray tracing: one sample of a pixel -----------------------------------

// A rough mirror floor under an area light, seen through a lens at 9 samples, with a
// moving sphere: --trace X,Y --sample K shows sample K (its point in the pixel, on the lens,
// its time, the area light's point drawn, the rough reflection's ideal direction), and the
// pixel is the mean of all 9, which the image holds.
TEST(Trace, ASampleShowsItsLensTimeLightPointAndRoughDirection) {
    TempDir tmp;
    std::ofstream(tmp / "d.json") << R"({"Scene": {"MaxRecursionDepth": "2",
      "Cameras": {"Camera": {"Position": "0 1 4", "Gaze": "0 -0.3 -1", "Up": "0 1 0",
        "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "8 8", "NumSamples": "9",
        "FocusDistance": "4", "ApertureSize": "0.2", "ImageName": "d.png"}},
      "Lights": {"AmbientLight": "5 5 5", "AreaLight": {"Position": "0 3 0", "Normal": "0 -1 0", "Size": "1",
        "Radiance": "500 500 500"}},
      "Materials": {"Material": [{"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "0.5 0.5 0.5"},
        {"_id": "2", "_type": "mirror", "DiffuseReflectance": "0.2 0.2 0.2", "MirrorReflectance": "0.5 0.5 0.5",
         "Roughness": "0.3"}]},
      "VertexData": {"_data": "-9 0 -9  9 0 -9  9 0 9  -9 0 9  0 0.5 -1"},
      "Objects": {"Mesh": {"Material": "2", "Faces": {"_data": "1 3 2 1 4 3"}},
        "Sphere": {"Material": "1", "Center": "5", "Radius": "0.5", "MotionBlur": "0.5 0 0"}}}})";
    const RunResult img = run_raytracer({"-q", "-o", tmp / "out", tmp / "d.json"});
    ASSERT_EQ(img.exit_code, 0) << dump(img);
    rt::Image rendered;
    ASSERT_TRUE(load_png(tmp / "out/d.png", rendered));
    for (const char* k : {"0", "8"}) {
        const Traced t = trace_run(tmp / "d.json", "4,6", tmp / "t.json", {"--sample", k});
        ASSERT_EQ(t.run.exit_code, 0) << dump(t.run);
        EXPECT_TRUE(contains(t.run.out, std::string("sample ") + k + " of 9 (--sample, seed 0, sampler sobol)"))
            << t.run.out;
        EXPECT_TRUE(contains(t.run.out, "lens point (")) << t.run.out;
        EXPECT_TRUE(contains(t.run.out, ", time ")) << t.run.out;
        EXPECT_TRUE(contains(t.run.out, "light 1 (area): point drawn (")) << t.run.out;
        EXPECT_TRUE(contains(t.run.out, "turned from the ideal direction")) << t.run.out;
        EXPECT_TRUE(contains(t.run.out, "the mean of its 9 samples")) << t.run.out;
        const json& s = t.doc["sample"];
        ASSERT_TRUE(s.is_object()) << t.doc.dump();
        EXPECT_EQ(s["index"].get<int>(), std::atoi(k));
        EXPECT_EQ(s["lens"].size(), 2u);
        const std::vector<uint8_t> px = t.doc["pixel"].get<std::vector<uint8_t>>();
        EXPECT_EQ(px, pixel_of(rendered, 4, 6)) << "the trace's pixel is the image's, whichever sample is shown";
    }
    // Two samples differ in where they fall.
    const Traced a = trace_run(tmp / "d.json", "4,6", tmp / "a.json", {"--sample", "0"});
    const Traced b = trace_run(tmp / "d.json", "4,6", tmp / "b.json", {"--sample", "5"});
    EXPECT_NE(a.doc["sample"]["pixel_offset"], b.doc["sample"]["pixel_offset"]);
    // A sample the camera does not take is a usage error.
    const RunResult bad = run_raytracer({"--trace", "4,6", "--sample", "9", tmp / "d.json"});
    EXPECT_EQ(bad.exit_code, 2) << dump(bad);
    EXPECT_TRUE(contains(bad.err, "--sample 9: camera 1 takes 9 samples per pixel (0..8)")) << dump(bad);
}
