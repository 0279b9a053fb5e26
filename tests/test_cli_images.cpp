// Command-line behaviour of ./raytracer, the images it writes, run as a separate process on
// tiny scenes written into temporary folders (the assignment's sample scene, spec section
// 7, at 16x16, with edits made through JSON pointers: cli_test_support.h).
//
// The contract:
//   raytracer [options] scene.json...   one PNG per camera, named by its ImageName
//   -o DIR / --output-dir DIR           relative ImageNames go under DIR (folders created)
//   output independent of the thread count; --cull / --no-cull and --rounding change it
//   as they say; images written atomically: an output path that cannot be written
//   fails, the other cameras' images are still written, nothing is left behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "rt/geometry/traverse.h"
#include "rt/image/image.h"
#include "rt/shading/pixel_samples.h"
#include "test_support.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;
using namespace cli_test;

namespace {

std::vector<uint8_t> pixel(const rt::Image& img, int x, int y) {
    size_t at = (size_t(y) * size_t(img.width) + size_t(x)) * 3;
    return {img.rgb[at], img.rgb[at + 1], img.rgb[at + 2]};
}

}  // namespace

// ---- Where images go ----------------------------------------------------------------

TEST(Cli, RendersOnePngPerCameraIntoCurrentDirectory) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json",
                with_cameras(sample_scene(), {{"first_cam.png", "24 16"}, {"second_cam.png", "16 8"}}));
    RunResult r = run_raytracer({"scene.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "first_cam.png", 24, 16));
    EXPECT_TRUE(is_png(tmp / "second_cam.png", 16, 8));
    EXPECT_EQ(list_files(tmp.path()), (std::vector<std::string>{"first_cam.png", "scene.json", "second_cam.png"}))
        << "unexpected or leftover files" << dump(r);
}

TEST(Cli, SampleMapOfOneImageAndOfSeveral) {
    TempDir tmp;
    write_scene(tmp.path(), "one.json", sample_scene("one.png", "16 16"));
    write_scene(tmp.path(), "two.json", sample_scene("two.png", "8 12"));
    // One image: the map at the path given; with a cap of 64, each pixel's level is
    // 255 n / 64 (rounded) for a count n of its first samples (adaptive_first) and then
    // whole packets of 16, or the cap.
    RunResult r = run_raytracer(
        {"-q", "--samples", "8", "--noise-target", "2", "--max-samples", "64", "--sample-map", "m/map.png", "one.json"},
        tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    rt::Image map;
    ASSERT_TRUE(load_png(tmp / "m/map.png", map));
    ASSERT_EQ(map.width, 16);
    ASSERT_EQ(map.height, 16);
    std::set<int> allowed = {255};
    for (int n = rt::adaptive_first(8); n < 64; n += rt::kPacket) allowed.insert((255 * n + 32) / 64);
    for (int level : std::set<int>(map.rgb.begin(), map.rgb.end())) EXPECT_EQ(allowed.count(level), 1u) << level;
    // Several images: one map each, named after its image.
    r = run_raytracer({"-q", "--samples", "8", "--sample-map", "map.png", "one.json", "two.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "map_one.png", 16, 16));
    EXPECT_TRUE(is_png(tmp / "map_two.png", 8, 12));
    // Without adaptive sampling every pixel takes its NumSamples: white.
    ASSERT_TRUE(load_png(tmp / "map_two.png", map));
    EXPECT_EQ(*std::min_element(map.rgb.begin(), map.rgb.end()), 255);
}

TEST(Cli, RendersSeveralSceneFiles) {
    TempDir tmp;
    write_scene(tmp.path(), "one.json", sample_scene("one.png"));
    write_scene(tmp.path(), "two.json", sample_scene("two.png", "8 12"));
    RunResult r = run_raytracer({"one.json", "two.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "one.png", 16, 16));
    EXPECT_TRUE(is_png(tmp / "two.png", 8, 12));
}

TEST(Cli, OutputDirTakesRelativeNamesAndCreatesFolders) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene("sub/dir/a.png"));
    RunResult r = run_raytracer({"-o", "out/nested", "scene.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "out/nested/sub/dir/a.png", 16, 16));
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"nested/sub/dir/a.png"}) << dump(r);
    EXPECT_FALSE(file_exists(tmp / "sub")) << "image also written relative to the current directory";

    // Long form, absolute folder, scene given by an absolute path from elsewhere.
    TempDir other;
    RunResult r2 = run_raytracer({"--output-dir", other / "long", tmp / "scene.json"}, "/");
    ASSERT_EQ(r2.exit_code, 0) << dump(r2);
    EXPECT_TRUE(is_png(other / "long/sub/dir/a.png", 16, 16));
    EXPECT_EQ(list_files(other.path()), std::vector<std::string>{"long/sub/dir/a.png"}) << dump(r2);
}

TEST(Cli, OutputDirLeavesAbsoluteNamesAlone) {
    TempDir tmp;
    fs::create_directories(tmp / "abs");
    const std::string absolute = tmp / "abs/x.png";
    write_scene(tmp.path(), "scene.json", with_cameras(sample_scene(), {{absolute, "16 16"}, {"rel.png", "16 16"}}));
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(absolute, 16, 16));
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"rel.png"}) << dump(r);
    EXPECT_EQ(list_files(tmp / "abs"), std::vector<std::string>{"x.png"}) << dump(r);
}

TEST(Cli, ReplacesAnExistingImage) {
    TempDir tmp;
    fs::create_directories(tmp / "out");
    write_text(tmp / "out/simple.png", "not a png, left over from an earlier run");
    write_scene(tmp.path(), "scene.json", sample_scene());
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "out/simple.png", 16, 16));
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"simple.png"}) << dump(r);
}

// ---- Rendering options ----------------------------------------------------------------

TEST(Cli, OutputDoesNotDependOnThreadCount) {
    // A scene exercising every material type, at a size that is not a multiple of
    // any likely tile size.
    json j = sample_scene("det.png", "37 23");
    j["Scene"]["MaxRecursionDepth"] = "4";
    j["Scene"]["Materials"]["Material"].push_back(json::parse(R"({
        "_id": "3", "_type": "conductor",
        "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0.1 0.1 0.1",
        "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "20",
        "MirrorReflectance": "1 0.86 0.57", "RefractionIndex": "0.37", "AbsorptionIndex": "2.82"})"));
    j["Scene"]["Materials"]["Material"].push_back(json::parse(R"({
        "_id": "4", "_type": "dielectric",
        "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
        "SpecularReflectance": "0 0 0", "PhongExponent": "1",
        "MirrorReflectance": "1 1 1", "AbsorptionCoefficient": "0.01 0.02 0.03",
        "RefractionIndex": "1.5"})"));
    set_at(j, "/Scene/Objects/Triangle/Material", "3");
    set_at(j, "/Scene/Objects/Sphere/0/Material", "4");
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", j);

    std::vector<std::vector<std::string>> runs = {{"-j", "1"}, {"-j", "3"}, {"--threads", "2"}, {"-j", "7"}};
    std::vector<std::string> bytes;
    for (size_t i = 0; i < runs.size(); ++i) {
        std::string out = tmp / ("out" + std::to_string(i));
        std::vector<std::string> args = runs[i];
        args.insert(args.end(), {"-o", out, "scene.json"});
        RunResult r = run_raytracer(args, tmp.path());
        ASSERT_EQ(r.exit_code, 0) << join(args) << dump(r);
        ASSERT_TRUE(is_png(out + "/det.png", 37, 23));
        bytes.push_back(read_text(out + "/det.png"));
    }
    for (size_t i = 1; i < runs.size(); ++i)
        EXPECT_TRUE(bytes[i] == bytes[0]) << join(runs[i]) << " differs from " << join(runs[0]);
}

TEST(Cli, CullingOptionsHideBackFacingTriangles) {
    // One large triangle whose vertices run clockwise as seen from the camera, so its
    // normal points away: culled camera rays see the background through it.
    json j = sample_scene("cull.png");
    j["Scene"]["BackgroundColor"] = "0 0 100";
    j["Scene"]["Lights"] = json::parse(R"({"AmbientLight": "50 50 50",
        "PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "0 0 0"}})");
    j["Scene"]["VertexData"]["_data"] = "-10 -10 -2 0 10 -2 10 -10 -2";
    j["Scene"]["Objects"] = json::parse(R"({"Triangle": {"_id": "1", "Material": "1", "Indices": "1 2 3"}})");
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", j);

    std::map<std::string, rt::Image> images;
    for (const std::string flag : {"--cull", "--no-cull", ""}) {
        std::string out = tmp / ("out" + flag);
        std::vector<std::string> args = {"-o", out, "scene.json"};
        if (!flag.empty()) args.insert(args.begin(), flag);
        RunResult r = run_raytracer(args, tmp.path());
        ASSERT_EQ(r.exit_code, 0) << join(args) << dump(r);
        ASSERT_TRUE(load_png(out + "/cull.png", images[flag])) << join(args);
        ASSERT_EQ(images[flag].width, 16);
    }
    EXPECT_EQ(pixel(images["--cull"], 8, 8), (std::vector<uint8_t>{0, 0, 100}))
        << "--cull: the back-facing triangle should not be seen by camera rays";
    EXPECT_NE(pixel(images["--no-cull"], 8, 8), (std::vector<uint8_t>{0, 0, 100}))
        << "--no-cull: the back-facing triangle should be visible";
    EXPECT_TRUE(images[""].rgb == images["--cull"].rgb) << "culling should be on by default";
}

TEST(Cli, RoundingOption) {
    // A plane facing the camera that fills the view, lit by ambient light only:
    // every channel is 25.6 before quantisation.
    json j = sample_scene("round.png", "8 8");
    j["Scene"]["Lights"] = json::parse(R"({"AmbientLight": "25.6 25.6 25.6",
        "PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "0 0 0"}})");
    j["Scene"]["VertexData"]["_data"] = "0 0 -2";
    j["Scene"]["Objects"] = json::parse(R"({"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 1"}})");
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", j);

    std::map<std::string, rt::Image> images;
    for (const std::string mode : {"truncate", "nearest", ""}) {
        std::string out = tmp / ("out_" + mode);
        std::vector<std::string> args = {"-o", out, "scene.json"};
        if (!mode.empty()) args.insert(args.begin(), {"--rounding", mode});
        RunResult r = run_raytracer(args, tmp.path());
        ASSERT_EQ(r.exit_code, 0) << join(args) << dump(r);
        ASSERT_TRUE(load_png(out + "/round.png", images[mode])) << join(args);
        ASSERT_EQ(images[mode].width, 8);
    }
    EXPECT_EQ(pixel(images["truncate"], 4, 4), (std::vector<uint8_t>{25, 25, 25}));
    EXPECT_EQ(pixel(images["nearest"], 4, 4), (std::vector<uint8_t>{26, 26, 26}));
    EXPECT_TRUE(images[""].rgb == images["truncate"].rgb) << "truncation should be the default";
}

TEST(Cli, AbsentBlinnPhongCoefficientsAreZero) {
    // Spec 3: a material "can be defined with" ambient, diffuse and specular properties;
    // each one absent renders byte for byte as "0 0 0" (a matte wall has no specular term).
    // The sample scene's material 1 is lit by ambient light and a point light, so each
    // coefficient shows: the image with it as given must differ from both.
    TempDir tmp;
    auto render = [&](const json& j, const std::string& name) {
        write_scene(tmp.path(), name + ".json", j);
        RunResult r = run_raytracer({"-q", "-o", tmp / "out", name + ".json"}, tmp.path());
        EXPECT_EQ(r.exit_code, 0) << name << dump(r);
        EXPECT_EQ(r.err, "") << name << ": an absent coefficient is no warning" << dump(r);
        return read_text(tmp / ("out/" + name + ".png"));
    };
    const std::string given = render(sample_scene("given.png"), "given");
    for (const std::string key : {"AmbientReflectance", "DiffuseReflectance", "SpecularReflectance"}) {
        SCOPED_TRACE(key);
        const std::string pointer = "/Scene/Materials/Material/0/" + key;
        json absent = sample_scene("absent.png");
        erase_at(absent, pointer);
        json zero = sample_scene("zero.png");
        set_at(zero, pointer, "0 0 0");
        const std::string a = render(absent, "absent"), z = render(zero, "zero");
        EXPECT_TRUE(a == z) << "absent differs from 0 0 0";
        EXPECT_FALSE(a == given) << "the coefficient does not show in the test scene";
    }
    // All three absent at once.
    json none = sample_scene("none.png");
    json zeros = sample_scene("zeros.png");
    for (const std::string key : {"AmbientReflectance", "DiffuseReflectance", "SpecularReflectance"}) {
        erase_at(none, "/Scene/Materials/Material/0/" + key);
        set_at(zeros, "/Scene/Materials/Material/0/" + key, "0 0 0");
    }
    EXPECT_TRUE(render(none, "none") == render(zeros, "zeros"));
}

// ---- Output paths that cannot be written ------------------------------------------------

TEST(Cli, UnwritableOutputPathFailsButOtherCamerasAreWritten) {
    TempDir tmp;
    write_text(tmp / "regular_file", "a file, not a folder\n");
    fs::create_directories(tmp / "out");
    write_text(tmp / "out/blocker", "a file, not a folder\n");

    struct Case {
        std::string image_name;  // as written in the scene
        std::string named;       // what the error line must contain
    };
    const std::vector<Case> cases = {
        {"/proc/nonexistent_dir/x.png", "/proc/nonexistent_dir/x.png"},
        {tmp / "regular_file/x.png", tmp / "regular_file/x.png"},
        {"blocker/x.png", "blocker/x.png"},  // relative, under -o out
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.image_name);
        fs::remove(tmp / "out/ok.png");
        write_scene(tmp.path(), "scene.json",
                    with_cameras(sample_scene(), {{c.image_name, "16 16"}, {"ok.png", "16 16"}}));
        RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
        EXPECT_NE(r.exit_code, 0) << dump(r);
        EXPECT_LT(r.exit_code, 128) << dump(r);
        EXPECT_GE(count_lines_containing(r.err, c.named), 1) << "the error should name the output path" << dump(r);
        EXPECT_TRUE(is_png(tmp / "out/ok.png", 16, 16)) << "the other camera's image is missing" << dump(r);
        EXPECT_EQ(list_files(tmp / "out"), (std::vector<std::string>{"blocker", "ok.png"}))
            << "leftover files in the output folder" << dump(r);
        EXPECT_EQ(list_files(tmp.path()),
                  (std::vector<std::string>{"out/blocker", "out/ok.png", "regular_file", "scene.json"}))
            << "leftover files" << dump(r);
    }
}
