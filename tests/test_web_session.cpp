// The browser page's renderer session (rt/web/session.h), natively: parts merge into the
// whole image, the trace is --trace-json's, options and errors are the command line's.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/trace.h"
#include "rt/web/session.h"
#include "test_support.h"

namespace {

// Two spheres and a mirror-ish plane, 37x23 (tiles that do not divide it), two cameras.
const char* kScene = R"({"Scene": {
  "BackgroundColor": "10 20 30", "MaxRecursionDepth": "3",
  "Cameras": {"Camera": [
    {"_id": "1", "Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -0.6 0.6",
     "NearDistance": "1", "ImageResolution": "37 23", "ImageName": "a.png"},
    {"_id": "2", "Position": "0 3 5", "Gaze": "0 -0.5 -1", "Up": "0 1 0", "NearPlane": "-1 1 -1 1",
     "NearDistance": "1", "ImageResolution": "17 17", "ImageName": "b.png"}]},
  "Lights": {"AmbientLight": "20 20 20", "PointLight": {"_id": "1", "Position": "2 4 4", "Intensity": "900 900 900"}},
  "Materials": {"Material": [
    {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "0.6 0.3 0.2", "SpecularReflectance": "1 1 1", "PhongExponent": "20"},
    {"_id": "2", "_type": "mirror", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.1 0.1 0.1", "MirrorReflectance": "0.8 0.8 0.8"}]},
  "VertexData": "-1 0 0  1 0 0  0 -1 -3",
  "Objects": {"Sphere": [{"_id": "1", "Material": "1", "Center": "1", "Radius": "0.8"},
                         {"_id": "2", "Material": "2", "Center": "2", "Radius": "0.7"}],
              "Plane": {"_id": "1", "Material": "2", "Point": "3", "Normal": "0 1 0.2"}}}})";

std::vector<uint8_t> rgba_of(const rt::Image& img) {
    std::vector<uint8_t> out(static_cast<size_t>(img.width) * img.height * 4);
    for (size_t i = 0; i < out.size() / 4; ++i) {
        for (int c = 0; c < 3; ++c) out[4 * i + c] = img.rgb[3 * i + c];
        out[4 * i + 3] = 255;
    }
    return out;
}

}  // namespace

TEST(WebSession, PartsMergeIntoTheCommandLinesImage) {
    TempDir tmp;
    write_text(tmp / "s.json", kScene);
    ASSERT_EQ(rt::web::load(tmp / "s.json", R"({"cull": false})"), "");
    const nlohmann::json info = nlohmann::json::parse(rt::web::scene_json());
    ASSERT_EQ(info["cameras"].size(), 2u);
    EXPECT_EQ(info["cameras"][0]["name"], "a.png");
    EXPECT_EQ(info["cameras"][0]["width"], 37);
    EXPECT_EQ(info["cameras"][1]["height"], 17);
    const rt::Scene scene = rt::build_scene(rt::load_scene(tmp / "s.json"));
    rt::RenderOptions o;
    o.trace.cull = false;
    for (int camera = 0; camera < 2; ++camera) {
        const std::vector<uint8_t> whole = rgba_of(rt::render(scene, camera, o));
        for (int parts : {1, 2, 5}) {
            std::vector<uint8_t> merged(whole.size(), 0);
            for (int part = 0; part < parts; ++part) {
                std::vector<uint8_t> mine(whole.size(), 0);
                ASSERT_EQ(rt::web::render_part(camera, part, parts, mine.data()), "");
                for (size_t i = 0; i < mine.size(); i += 4)
                    if (mine[i + 3]) {
                        EXPECT_EQ(merged[i + 3], 0) << "pixel " << i / 4 << " rendered by two parts";
                        for (int c = 0; c < 4; ++c) merged[i + c] = mine[i + c];
                    }
            }
            EXPECT_EQ(merged, whole) << "camera " << camera << ", " << parts << " parts";
        }
    }
}

TEST(WebSession, TraceIsTheTraceJsonOfTheCommandLine) {
    TempDir tmp;
    write_text(tmp / "s.json", kScene);
    ASSERT_EQ(rt::web::load(tmp / "s.json", R"({"max_depth": 2, "epsilon_scale": 2})"), "");
    rt::Scene scene = rt::build_scene(rt::load_scene(tmp / "s.json"));
    scene.setup.max_recursion_depth = 2;
    scene.setup.shadow_ray_epsilon *= 2;
    rt::PixelTrace t = rt::trace_pixel(scene, 0, 20, 11, rt::TraceOptions{}, rt::Rounding::Truncate);
    t.scene = tmp / "s.json";
    EXPECT_EQ(rt::web::trace(0, 20, 11, 0), rt::trace_json(scene, t));
    const nlohmann::json outside = nlohmann::json::parse(rt::web::trace(0, 37, 0, 0));
    EXPECT_EQ(outside["error"], "pixel 37,0 is outside the 37x23 image");
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(2, 0, 0, 0))["error"], "no camera 3");
}

// The options' samples and seed are --samples and --seed: the image is render()'s under
// them, another seed gives another image, and a trace is --sample's.
TEST(WebSession, SamplesAndSeedAreTheCommandLines) {
    TempDir tmp;
    nlohmann::json j = nlohmann::json::parse(kScene);
    j["Scene"]["Cameras"]["Camera"][0]["NumSamples"] = "4";
    write_text(tmp / "s.json", j.dump());
    rt::Scene scene = rt::build_scene(rt::load_scene(tmp / "s.json"));
    rt::RenderOptions o;
    o.samples = 9;
    o.sampling.seed = 5;
    rt::apply_overrides(scene, o);
    ASSERT_EQ(rt::web::load(tmp / "s.json", R"({"samples": 9, "seed": 5})"), "");
    const nlohmann::json info = nlohmann::json::parse(rt::web::scene_json());
    EXPECT_EQ(info["cameras"][0]["samples"], 9);
    EXPECT_EQ(info["cameras"][1]["samples"], 9);
    const std::vector<uint8_t> whole = rgba_of(rt::render(scene, 0, o));
    std::vector<uint8_t> mine(whole.size(), 0);
    ASSERT_EQ(rt::web::render_part(0, 0, 1, mine.data()), "");
    EXPECT_EQ(mine, whole);
    rt::RenderOptions other = o;
    other.sampling.seed = 6;
    EXPECT_NE(rgba_of(rt::render(scene, 0, other)), whole) << "the seed changes nothing: the test shows nothing";

    rt::PixelTrace t = rt::trace_pixel(scene, 0, 20, 11, rt::TraceOptions{}, rt::Rounding::Truncate, o.sampling, 7);
    t.scene = tmp / "s.json";
    const std::string traced = rt::web::trace(0, 20, 11, 7);
    EXPECT_EQ(traced, rt::trace_json(scene, t));
    const nlohmann::json sample = nlohmann::json::parse(traced)["sample"];
    EXPECT_EQ(sample["index"], 7);
    EXPECT_EQ(sample["seed"], 5);
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(0, 20, 11, 9))["error"],
              "sample 9: camera 1 takes 9 samples per pixel (0..8)");
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(0, 20, 11, -1))["error"],
              "sample -1: camera 1 takes 9 samples per pixel (0..8)");

    // samples 0 keeps each camera's NumSamples; a seed beyond 2^53 comes as a string of digits.
    ASSERT_EQ(rt::web::load(tmp / "s.json", R"({"samples": 0, "seed": "4611686018427387904"})"), "");
    const nlohmann::json own = nlohmann::json::parse(rt::web::scene_json());
    EXPECT_EQ(own["cameras"][0]["samples"], 4);
    EXPECT_EQ(own["cameras"][1]["samples"], 0);
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(0, 1, 2, 3))["sample"]["seed"].get<uint64_t>(), uint64_t(1) << 62);
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(1, 0, 0, 1))["error"],
              "sample 1: camera 2 takes 1 sample per pixel (0..0)");
    EXPECT_TRUE(nlohmann::json::parse(rt::web::trace(1, 0, 0, 0))["sample"].is_null());
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"seed": "12"})"), "");
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(0, 1, 2, 3))["sample"]["seed"], 12);
}

// Bad samples and seeds are refused as every option's bad value is; the largest pass.
TEST(WebSession, BadSamplesAndSeedsAreRefused) {
    TempDir tmp;
    write_text(tmp / "s.json", kScene);
    for (const char* bad :
         {R"({"samples": -1})", R"({"samples": 2.5})", R"({"samples": "4"})", R"({"samples": 1048577})",
          R"({"samples": null})", R"({"seed": -1})", R"({"seed": 1.5})", R"({"seed": "12a"})", R"({"seed": ""})",
          R"({"seed": "-3"})", R"({"seed": " 3"})", R"({"seed": 4611686018427387905})",
          R"({"seed": "4611686018427387905"})", R"({"seed": "99999999999999999999"})", R"({"seed": true})"}) {
        const nlohmann::json o = nlohmann::json::parse(bad);
        EXPECT_EQ(rt::web::load(tmp / "s.json", bad),
                  "options: " + o.begin().key() + ": unknown option or bad value " + o.begin().value().dump())
            << bad;
    }
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"samples": 1048576, "seed": 4611686018427387904})"), "");
}

TEST(WebSession, ErrorsAreTheCommandLinesLines) {
    TempDir tmp;
    nlohmann::json bad = nlohmann::json::parse(kScene);
    bad["Scene"]["Objects"]["Sphere"][1]["Radius"] = "-1";
    write_text(tmp / "bad.json", bad.dump());
    EXPECT_EQ(rt::web::load(tmp / "bad.json", ""),
              tmp / "bad.json" + ": /Scene/Objects/Sphere/1/Radius: must be greater than 0");
    // Nothing stays loaded after a failure.
    std::vector<uint8_t> px(37 * 23 * 4);
    EXPECT_EQ(rt::web::render_part(0, 0, 1, px.data()), "no scene loaded");
    EXPECT_EQ(nlohmann::json::parse(rt::web::scene_json())["cameras"].size(), 0u);
    write_text(tmp / "s.json", kScene);
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"cull": 1})"), "options: cull: unknown option or bad value 1");
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"colour": true})"),
              "options: colour: unknown option or bad value true");
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"rounding": "nearest", "min_weight": 0})"), "");
    EXPECT_EQ(rt::web::render_part(0, 3, 3, px.data()), "render: part outside 0..parts-1");
    // A syntax error too is the line without its "error: ", which raytracer.js adds once.
    write_text(tmp / "broken.json", "{\"Scene\": {\n  \"A\": \"1\"\n  \"B\": \"2\"}}");
    EXPECT_EQ(rt::web::load(tmp / "broken.json", "").rfind(tmp / "broken.json" + ": parse error at line 3", 0), 0u);
}

// raytracer.js rejects with the command line's line, "error: " once, whether the module's
// message has it or not (tests/web/node_api.js, under Node with stand-in workers).
TEST(WebSession, ApiErrorsHaveOnePrefix) {
    if (run_program("/bin/sh", {"-c", "command -v node"}).exit_code != 0)
        GTEST_SKIP() << "node not found (apt-get install nodejs): tests/web/node_api.js not run";
    const RunResult r = run_program("/usr/bin/env", {"node", repo_file("tests/web/node_api.js")});
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
}
