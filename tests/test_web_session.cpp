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

namespace {

// kScene with what draws random numbers: a lens, an area light, a rough mirror.
std::string sampled_scene() {
    nlohmann::json j = nlohmann::json::parse(kScene);
    nlohmann::json& cam = j["Scene"]["Cameras"]["Camera"][0];
    cam["ApertureSize"] = "0.1";
    cam["FocusDistance"] = "5";
    j["Scene"]["Lights"]["AreaLight"] = {
        {"_id", "1"}, {"Position", "0 3 2"}, {"Normal", "0 -1 0"}, {"Size", "1"}, {"Radiance", "9000 9000 9000"}};
    j["Scene"]["Materials"]["Material"][1]["Roughness"] = "0.2";
    return j.dump();
}

// The image after each pass of a progressive render of camera `camera` in `parts` parts,
// the passes adding samples [bounds[i], bounds[i + 1]) to every part in turn.
std::vector<std::vector<uint8_t>> refined_images(int camera, int parts, const std::vector<int>& bounds, size_t bytes) {
    std::vector<std::vector<uint8_t>> images;
    std::vector<uint8_t> merged(bytes, 0);
    for (size_t pass = 0; pass + 1 < bounds.size(); ++pass) {
        for (int part = 0; part < parts; ++part) {
            std::vector<uint8_t> mine(bytes, 0);
            EXPECT_EQ(rt::web::refine_part(camera, part, parts, bounds[pass], bounds[pass + 1], mine.data()), "");
            for (size_t i = 0; i < bytes; i += 4)
                if (mine[i + 3]) std::copy(&mine[i], &mine[i] + 4, &merged[i]);
        }
        images.push_back(merged);
    }
    return images;
}

// Render options of `samples` per pixel under `seed` and `sampler`, and the page's load
// options that say the same.
rt::RenderOptions sampled(int samples, uint64_t seed, rt::SamplerKind sampler) {
    rt::RenderOptions o;
    o.samples = samples;
    o.sampling.seed = seed;
    o.sampling.sampler = sampler;
    return o;
}
std::string load_options(const rt::RenderOptions& o) {
    return nlohmann::json{
        {"samples", o.samples}, {"seed", o.sampling.seed}, {"sampler", rt::sampler_name(o.sampling.sampler)}}
        .dump();
}

rt::Scene built(const std::string& path, const rt::RenderOptions& o) {
    rt::Scene scene = rt::build_scene(rt::load_scene(path));
    rt::apply_overrides(scene, o);
    return scene;
}

}  // namespace

// Passes of samples add up to the render of all of them, byte for byte, whatever the
// sampler, the parts and where the passes split a pixel's samples (a packet of samples
// traces each ray as it would alone).
TEST(WebSession, RefinedPassesAddUpToTheRender) {
    TempDir tmp;
    write_text(tmp / "s.json", sampled_scene());
    for (const rt::SamplerKind kind : {rt::SamplerKind::Random, rt::SamplerKind::Stratified, rt::SamplerKind::Sobol}) {
        const rt::RenderOptions o = sampled(40, 7, kind);
        const char* sampler = rt::sampler_name(kind);
        ASSERT_EQ(rt::web::load(tmp / "s.json", load_options(o)), "");
        const rt::Scene scene = built(tmp / "s.json", o);
        const std::vector<uint8_t> whole = rgba_of(rt::render(scene, 0, o));
        std::vector<uint8_t> part_whole(whole.size(), 0);
        ASSERT_EQ(rt::web::render_part(0, 0, 1, part_whole.data()), "");
        EXPECT_EQ(part_whole, whole) << "the sampler option does not reach the session: " << sampler;
        for (const std::vector<int>& bounds : {std::vector<int>{0, 1, 16, 32, 40}, {0, 1, 2, 19, 40}, {0, 40}})
            for (int parts : {1, 3}) {
                const auto images = refined_images(0, parts, bounds, whole.size());
                EXPECT_EQ(images.back(), whole)
                    << sampler << ", " << parts << " parts, passes ending at " << nlohmann::json(bounds).dump();
                if (images.size() > 1) {
                    EXPECT_NE(images.front(), whole) << "a pass of one sample is the final image";
                }
            }
    }
}

// Under the random and sobol samplers sample k of a pixel is the same whatever the count N
// when neither k nor N is a square (the random sampler's grid, rt/shading/pixel_samples.h)
// and k > 1 (one sample is the pixel's centre): the image after 32 of 40 samples is then
// the render at 32. The stratified sampler lays its pattern out for N (no such promise).
TEST(WebSession, APassIsTheRenderAtItsSamplesWhereTheSamplerSaysSo) {
    TempDir tmp;
    write_text(tmp / "s.json", sampled_scene());
    for (const rt::SamplerKind kind : {rt::SamplerKind::Random, rt::SamplerKind::Sobol}) {
        const char* sampler = rt::sampler_name(kind);
        ASSERT_EQ(rt::web::load(tmp / "s.json", load_options(sampled(40, 3, kind))), "");
        const rt::RenderOptions o = sampled(32, 3, kind);
        const std::vector<uint8_t> at32 = rgba_of(rt::render(built(tmp / "s.json", o), 0, o));
        const auto images = refined_images(0, 2, {0, 1, 16, 32, 40}, at32.size());
        EXPECT_EQ(images[2], at32) << sampler;
        EXPECT_NE(images[3], at32) << sampler << ": 8 more samples change nothing: the test shows nothing";
    }
}

// A camera without samples is one pass of its one ray: render_part's bytes.
TEST(WebSession, RefiningACameraWithoutSamplesIsItsRender) {
    TempDir tmp;
    write_text(tmp / "s.json", kScene);
    ASSERT_EQ(rt::web::load(tmp / "s.json", ""), "");
    for (int camera = 0; camera < 2; ++camera) {
        const rt::Scene scene = built(tmp / "s.json", rt::RenderOptions{});
        const std::vector<uint8_t> whole = rgba_of(rt::render(scene, camera, rt::RenderOptions{}));
        EXPECT_EQ(refined_images(camera, 2, {0, 1}, whole.size()).back(), whole) << "camera " << camera;
    }
}

TEST(WebSession, RefiningChecksItsSamplesAndParts) {
    TempDir tmp;
    write_text(tmp / "s.json", sampled_scene());
    ASSERT_EQ(rt::web::load(tmp / "s.json", R"({"samples": 20})"), "");
    std::vector<uint8_t> px(37 * 23 * 4);
    EXPECT_EQ(rt::web::refine_part(0, 0, 2, 0, 16, px.data()), "");
    EXPECT_EQ(rt::web::refine_part(0, 0, 2, 8, 20, px.data()), "samples 8..20: part 0 holds 16 samples");
    EXPECT_EQ(rt::web::refine_part(0, 1, 2, 16, 20, px.data()), "samples 16..20: part 1 holds 0 samples");
    EXPECT_EQ(rt::web::refine_part(0, 0, 2, 16, 21, px.data()), "samples 16..21: camera 1 takes 20 samples per pixel");
    EXPECT_EQ(rt::web::refine_part(0, 0, 2, 16, 16, px.data()), "samples 16..16: camera 1 takes 20 samples per pixel");
    EXPECT_EQ(rt::web::refine_part(0, 2, 2, 0, 1, px.data()), "render: part outside 0..parts-1");
    EXPECT_EQ(rt::web::refine_part(2, 0, 2, 0, 1, px.data()), "no such camera");
    // Another camera or part count drops the sums; 0 starts a part afresh.
    EXPECT_EQ(rt::web::refine_part(1, 0, 2, 0, 1, px.data()), "");
    EXPECT_EQ(rt::web::refine_part(0, 0, 2, 16, 20, px.data()), "samples 16..20: part 0 holds 0 samples");
    EXPECT_EQ(rt::web::refine_part(0, 0, 3, 0, 4, px.data()), "");
    EXPECT_EQ(rt::web::refine_part(0, 0, 3, 0, 4, px.data()), "");
    EXPECT_EQ(rt::web::refine_part(0, 0, 3, 4, 20, px.data()), "");
    EXPECT_EQ(rt::web::load(tmp / "s.json", R"({"sampler": "halton"})"),
              R"(options: sampler: unknown option or bad value "halton")");
    EXPECT_EQ(rt::web::refine_part(0, 0, 1, 0, 1, px.data()), "no scene loaded");
}
