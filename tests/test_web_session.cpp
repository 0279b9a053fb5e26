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
    EXPECT_EQ(rt::web::trace(0, 20, 11), rt::trace_json(scene, t));
    const nlohmann::json outside = nlohmann::json::parse(rt::web::trace(0, 37, 0));
    EXPECT_EQ(outside["error"], "pixel 37,0 is outside the 37x23 image");
    EXPECT_EQ(nlohmann::json::parse(rt::web::trace(2, 0, 0))["error"], "no camera 3");
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
