// Command-line behaviour of ./raytracer, run as a separate process on tiny scenes
// written into temporary folders. The scenes are the assignment's sample scene
// (spec section 7) at 16x16, with edits made through JSON pointers.
//
// The contract:
//   raytracer [options] scene.json...   one PNG per camera, named by its ImageName
//   -o DIR / --output-dir DIR           relative ImageNames go under DIR (folders created)
//   -j N / --threads N, --cull / --no-cull, --rounding truncate|nearest,
//   -q / --quiet, -h / --help (exit 0), --version (exit 0); unknown option: exit 2
//   bad input: exit 1, one stderr line "<scene path>: <json pointer>: <what>",
//   no image of that scene, other scenes still rendered; one stderr line per image
//   unless --quiet; warnings do not change the exit status; output independent of
//   the thread count; images written atomically.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/image/image.h"
#include "test_support.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

// The sample scene of spec section 7, with a second material (a mirror) and a
// second sphere so that arrays appear in /Scene/Materials and /Scene/Objects/Sphere.
const char* const kSampleScene = R"({
  "Scene": {
    "BackgroundColor": "0 0 0",
    "ShadowRayEpsilon": "1e-3",
    "IntersectionTestEpsilon": "1e-6",
    "Cameras": {
      "Camera": {
        "_id": "1",
        "Position": "0 0 0",
        "Gaze": "0 0 -1",
        "Up": "0 1 0",
        "NearPlane": "-1 1 -1 1",
        "NearDistance": "1",
        "ImageResolution": "16 16",
        "ImageName": "simple.png"
      }
    },
    "Lights": {
      "AmbientLight": "25 25 25",
      "PointLight": {
        "_id": "1",
        "Position": "0 0 0",
        "Intensity": "1000 1000 1000"
      }
    },
    "Materials": {
      "Material": [
        {
          "_id": "1",
          "AmbientReflectance": "1 1 1",
          "DiffuseReflectance": "1 1 1",
          "SpecularReflectance": "1 1 1",
          "PhongExponent": "1"
        },
        {
          "_id": "2",
          "_type": "mirror",
          "AmbientReflectance": "0.1 0.1 0.1",
          "DiffuseReflectance": "0.2 0.2 0.2",
          "SpecularReflectance": "0.5 0.5 0.5",
          "PhongExponent": "10",
          "MirrorReflectance": "0.7 0.7 0.7"
        }
      ]
    },
    "VertexData": {
      "_data": "-0.5 0.5 -2 -0.5 -0.5 -2 0.5 -0.5 -2 0.5 0.5 -2 0.75 0.75 -2 1 0.75 -2 0.875 1 -2 -0.875 1 -2 0 -0.5 0 -0.6 -0.3 -1.5",
      "_type": "xyz"
    },
    "Objects": {
      "Mesh": {
        "_id": "1",
        "Material": "1",
        "Faces": {
          "_data": "3 1 2 1 3 4",
          "_type": "triangle"
        }
      },
      "Triangle": {
        "_id": "1",
        "Material": "1",
        "Indices": "5 6 7"
      },
      "Sphere": [
        {
          "_id": "1",
          "Material": "1",
          "Center": "8",
          "Radius": "0.3"
        },
        {
          "_id": "2",
          "Material": "2",
          "Center": "10",
          "Radius": "0.2"
        }
      ],
      "Plane": {
        "_id": "1",
        "Material": "1",
        "Point": "9",
        "Normal": "0 1 0"
      }
    }
  }
})";

json sample_scene(const std::string& image = "simple.png", const std::string& resolution = "16 16") {
    json j = json::parse(kSampleScene);
    j["Scene"]["Cameras"]["Camera"]["ImageName"] = image;
    j["Scene"]["Cameras"]["Camera"]["ImageResolution"] = resolution;
    return j;
}

// Replaces the single camera by one camera per (ImageName, resolution).
json with_cameras(json j, const std::vector<std::pair<std::string, std::string>>& cams) {
    json proto = j["Scene"]["Cameras"]["Camera"];
    json arr = json::array();
    int id = 1;
    for (const auto& [name, res] : cams) {
        json c = proto;
        c["_id"] = std::to_string(id++);
        c["ImageName"] = name;
        c["ImageResolution"] = res;
        arr.push_back(c);
    }
    j["Scene"]["Cameras"]["Camera"] = arr;
    return j;
}

void set_at(json& j, const std::string& pointer, const json& value) { j[json::json_pointer(pointer)] = value; }

void erase_at(json& j, const std::string& pointer) {
    json::json_pointer p(pointer);
    j[p.parent_pointer()].erase(p.back());
}

std::string write_scene(const std::string& dir, const std::string& name, const json& j) {
    std::string path = dir + "/" + name;
    write_text(path, j.dump(2) + "\n");
    return path;
}

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
}

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

int count_lines_containing(const std::string& text, const std::string& needle) {
    int n = 0;
    for (const std::string& l : split_lines(text))
        if (contains(l, needle)) ++n;
    return n;
}

std::string dump(const RunResult& r) {
    return "\n--- exit " + std::to_string(r.exit_code) + " --- stderr ---\n" + r.err + "--- stdout ---\n" + r.out +
           "---";
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return "{" + s + "}";
}

// Checks that `path` is a PNG of the given size.
::testing::AssertionResult is_png(const std::string& path, int width, int height) {
    rt::Image img;
    if (!load_png(path, img)) return ::testing::AssertionFailure() << path << " is not a readable PNG";
    if (img.width != width || img.height != height)
        return ::testing::AssertionFailure()
               << path << " is " << img.width << "x" << img.height << ", expected " << width << "x" << height;
    return ::testing::AssertionSuccess();
}

std::vector<uint8_t> pixel(const rt::Image& img, int x, int y) {
    size_t at = (size_t(y) * size_t(img.width) + size_t(x)) * 3;
    return {img.rgb[at], img.rgb[at + 1], img.rgb[at + 2]};
}

}  // namespace

// ---- Options ----------------------------------------------------------------------

TEST(Cli, HelpPrintsUsageOnStdoutAndExitsZero) {
    for (const char* flag : {"-h", "--help"}) {
        RunResult r = run_raytracer({flag});
        EXPECT_EQ(r.exit_code, 0) << flag << dump(r);
        EXPECT_TRUE(contains(lower(r.out), "usage")) << flag << ": no usage on stdout" << dump(r);
    }
}

TEST(Cli, VersionExitsZero) {
    RunResult r = run_raytracer({"--version"});
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_FALSE(r.out.empty()) << "--version printed nothing on stdout" << dump(r);
}

TEST(Cli, UnknownOptionExitsTwoWithUsageOnStderr) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene());
    RunResult r = run_raytracer({"--no-such-option", "scene.json"}, tmp.path());
    EXPECT_EQ(r.exit_code, 2) << dump(r);
    EXPECT_TRUE(contains(lower(r.err), "usage")) << "no usage line on stderr" << dump(r);
    EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"scene.json"}) << dump(r);
}

TEST(Cli, BadOptionValuesAreRejectedWithoutRendering) {
    const std::vector<std::vector<std::string>> cases = {
        {"--rounding", "sideways", "scene.json"},
        {"-j", "many", "scene.json"},
        {"--threads", "-3", "scene.json"},
        {"scene.json", "-o"},  // missing value
    };
    for (const auto& args : cases) {
        TempDir tmp;
        write_scene(tmp.path(), "scene.json", sample_scene());
        RunResult r = run_raytracer(args, tmp.path());
        std::string what = join(args);
        EXPECT_NE(r.exit_code, 0) << what << dump(r);
        EXPECT_LT(r.exit_code, 128) << what << dump(r);
        EXPECT_FALSE(r.err.empty()) << what << ": nothing on stderr" << dump(r);
        EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"scene.json"}) << what << dump(r);
    }
}

// Every option takes "--opt value" and "--opt=value"; short ones also "-j 2" and "-j2".
// The spellings of one setting give the same image and the same --stats figures.
TEST(Cli, EveryOptionTakesItsValueInEverySpelling) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene("s.png", "8 8"));
    const std::vector<std::vector<std::vector<std::string>>> spellings = {
        {{"-j", "2"}, {"-j2"}, {"--threads", "2"}, {"--threads=2"}},
        {{"--rounding", "nearest"}, {"--rounding=nearest"}},
        {{"--max-depth", "1"}, {"--max-depth=1"}},
        {{"--epsilon-scale", "2"}, {"--epsilon-scale=2"}},
        {{"--bvh-leaf", "2"}, {"--bvh-leaf=2"}},
        {{"--bvh-bins", "4"}, {"--bvh-bins=4"}},
        {{"--bvh-split", "median"}, {"--bvh-split=median"}},
        {{"--bvh-cost", "2"}, {"--bvh-cost=2"}},
        {{"--bvh-block", "2"}, {"--bvh-block=2"}},
        {{"--repeat", "2"}, {"--repeat=2"}},
        {{"--min-weight", "0.5"}, {"--min-weight=0.5"}},
        {{"--precision", "float"}, {"--precision=float"}},
        {{"--precision", "double"}, {"--precision=double"}},
    };
    for (const auto& same : spellings) {
        std::vector<std::string> stats;
        for (size_t i = 0; i < same.size(); ++i) {
            std::vector<std::string> args = same[i];
            const std::string out = tmp / ("out" + std::to_string(i));
            args.insert(args.end(), {"-q", "--stats=" + out + ".json", "--output-dir=" + out, "scene.json"});
            RunResult r = run_raytracer(args, tmp.path());
            ASSERT_EQ(r.exit_code, 0) << join(args) << dump(r);
            EXPECT_EQ(r.err, "") << join(args);
            ASSERT_TRUE(is_png(out + "/s.png", 8, 8)) << join(args);
            json doc = json::parse(read_text(out + ".json"));
            json& im = doc["images"][0];
            for (const char* varies :
                 {"seconds", "seconds_min", "seconds_max", "rays_per_second", "peak_rss_bytes", "image"})
                im.erase(varies);
            stats.push_back(doc.dump());
            if (i > 0) {
                EXPECT_TRUE(read_text(out + "/s.png") == read_text(tmp / "out0/s.png")) << join(args);
                EXPECT_EQ(stats[i], stats[0]) << join(args) << " and " << join(same[0]);
            }
        }
    }
}

TEST(Cli, TheLastOfARepeatedOptionCounts) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene("s.png", "8 8"));
    RunResult r = run_raytracer({"-q", "-j", "3", "-j1", "--no-cull", "--cull", "--stats", "first.json", "--stats",
                                 "st.json", "-o", "a", "-o", "b", "scene.json"},
                                tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_EQ(list_files(tmp.path()), (std::vector<std::string>{"b/s.png", "scene.json", "st.json"})) << dump(r);
    const json doc = json::parse(read_text(tmp / "st.json"));
    EXPECT_EQ(doc["images"][0]["threads"], 1);
    EXPECT_EQ(doc["images"][0]["cull"], true);
}

TEST(Cli, UsageErrorsAreOneLinePlusTheUsage) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene());
    const std::string usage =
        "usage: raytracer [-o DIR] [-j N] [--precision double|float] [--cull|--no-cull]\n"
        "                 [--rounding truncate|nearest] [--min-weight W] [--stats FILE] [-q] [--strict]\n"
        "                 [--repeat N] [--max-depth N] [--epsilon-scale F] [--bvh-... (measurements)]\n"
        "                 scene.json|scene.xml...\n"
        "       raytracer --trace X,Y [--camera N] [--trace-json FILE] [options] scene.json|scene.xml";
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"--no-such-option", "scene.json"}, "unknown option '--no-such-option'"},
        {{"-j", "many", "scene.json"}, "--threads needs a whole number from 1 to 1024, got 'many'"},
        {{"--threads=0", "scene.json"}, "--threads needs a whole number from 1 to 1024, got '0'"},
        {{"--rounding=up", "scene.json"}, "--rounding takes truncate or nearest, got 'up'"},
        {{"--stats=", "scene.json"}, "--stats needs a file name"},
        {{"--max-depth=x", "scene.json"}, "--max-depth needs a whole number from 0 to 10000, got 'x'"},
        {{"--repeat", "0", "scene.json"}, "--repeat needs a whole number from 1 to 1000, got '0'"},
        {{"--repeat", "2", "--trace", "1,1", "scene.json"}, "--repeat times renders; --trace renders nothing"},
        {{"--epsilon-scale", "0", "scene.json"}, "--epsilon-scale needs a positive number, got '0'"},
        {{"--bvh-cost", "200", "scene.json"}, "--bvh-cost needs a number from 0.1 to 100, got '200'"},
        {{"--bvh-split", "fast", "scene.json"}, "--bvh-split takes sah or median, got 'fast'"},
        {{"--precision", "half", "scene.json"}, "--precision takes double or float, got 'half'"},
        {{"--precision=Float", "scene.json"}, "--precision takes double or float, got 'Float'"},
        {{"scene.json", "-o"}, "option --output-dir needs a value"},
        {{"-q"}, "no scene file given"},
    };
    for (const auto& [args, message] : cases) {
        RunResult r = run_raytracer(args, tmp.path());
        EXPECT_EQ(r.exit_code, 2) << join(args) << dump(r);
        EXPECT_EQ(r.err, "error: " + message + "\n" + usage + "\n") << join(args);
        EXPECT_EQ(r.out, "") << join(args);
    }
    EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"scene.json"});
}

TEST(Cli, HelpNamesEveryOption) {
    RunResult r = run_raytracer({"--help"});
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_EQ(r.err, "");
    for (const char* option :
         {"-o, --output-dir DIR", "-j, --threads N", "--cull, --no-cull", "--rounding MODE",   "--stats FILE",
          "-q, --quiet",          "-h, --help",      "--version",         "--max-depth N",     "--epsilon-scale F",
          "--bvh-leaf N",         "--bvh-bins N",    "--bvh-split MODE",  "--bvh-cost F",      "--bvh-block N",
          "--precision MODE",     "--trace X,Y",     "--camera N",        "--trace-json FILE", "exit status"})
        EXPECT_TRUE(contains(r.out, option)) << option << dump(r);
    RunResult v = run_raytracer({"--version"});
    EXPECT_EQ(v.out, "raytracer 1.0\n") << dump(v);
}

// One program, two precisions: --precision picks the copy of the library that renders
// (src/main.cpp), the last --precision counts, and the image line and --stats name it.
TEST(Cli, PrecisionPicksTheRendererAndSaysWhich) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", sample_scene("s.png", "8 8"));
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{}, "double"},  // no --precision at all
        {{"--precision", "double"}, "double"},
        {{"--precision", "float"}, "float"},
        {{"--precision=float"}, "float"},
        {{"--precision", "float", "--precision", "double"}, "double"},
        {{"--precision=double", "--precision", "float"}, "float"},
    };
    for (const auto& [options, precision] : cases) {
        std::vector<std::string> args = options;
        args.insert(args.end(), {"--stats", "st.json", "scene.json"});
        // Without raytracer_args: these runs choose their own precision.
        RunResult r = run_program(raytracer_path(), args, tmp.path());
        ASSERT_EQ(r.exit_code, 0) << join(args) << dump(r);
        EXPECT_EQ(r.err.rfind("s.png: 8x8, " + precision + ", ", 0), 0u) << join(args) << dump(r);
        EXPECT_EQ(json::parse(read_text(tmp / "st.json"))["precision"], precision) << join(args);
    }
    // A scene file named like an option's value is still a scene file after "--".
    write_scene(tmp.path(), "float", sample_scene("f.png", "8 8"));
    RunResult r = run_program(raytracer_path(), {"-q", "--stats", "st.json", "--", "float"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_EQ(json::parse(read_text(tmp / "st.json"))["precision"], "double");
}

TEST(Cli, DoubleDashEndsTheOptions) {
    TempDir tmp;
    write_scene(tmp.path(), "-scene.json", sample_scene("s.png", "8 8"));
    RunResult r = run_raytracer({"-q", "--", "-scene.json"}, tmp.path());
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "s.png", 8, 8));
}

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

// ---- Messages -------------------------------------------------------------------------

TEST(Cli, OneProgressLinePerImageUnlessQuiet) {
    TempDir tmp;
    write_scene(tmp.path(), "scene.json",
                with_cameras(sample_scene(), {{"first_cam.png", "16 16"}, {"second_cam.png", "16 16"}}));
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_EQ(count_lines_containing(r.err, "first_cam.png"), 1) << dump(r);
    EXPECT_EQ(count_lines_containing(r.err, "second_cam.png"), 1) << dump(r);

    for (const char* flag : {"-q", "--quiet"}) {
        RunResult q = run_raytracer({flag, "-o", tmp / "quiet", "scene.json"}, tmp.path());
        ASSERT_EQ(q.exit_code, 0) << flag << dump(q);
        EXPECT_EQ(q.err, "") << flag << ": a clean scene should print nothing" << dump(q);
        EXPECT_TRUE(is_png(tmp / "quiet/first_cam.png", 16, 16));
        EXPECT_TRUE(is_png(tmp / "quiet/second_cam.png", 16, 16));
    }
}

TEST(Cli, UnknownKeysAreWarningsNotErrors) {
    json j = sample_scene("warned.png");
    j["Scene"]["Cameras"]["Camera"]["NumSamples"] = "4";
    j["Scene"]["TexCoordData"] = nullptr;
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", j);
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "out/warned.png", 16, 16));
    for (const char* key : {"NumSamples", "TexCoordData"}) {
        bool warned = false;
        for (const std::string& l : split_lines(r.err))
            if (contains(l, key) && contains(lower(l), "warning")) warned = true;
        EXPECT_TRUE(warned) << "no warning line naming " << key << dump(r);
    }
}

// ---- Bad input --------------------------------------------------------------------------

namespace {

struct BadCase {
    std::string name;
    // The bad scene's text; nullopt: the file does not exist.
    std::function<std::optional<std::string>()> text;
    std::string expect;  // must appear in the error line (besides the scene path)
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

BadCase raw(const std::string& name, const std::optional<std::string>& text) {
    return {name, [text] { return text; }, ""};
}

BadCase edited(const std::string& name, const std::string& pointer, const json& value, const std::string& expect = "") {
    return {name,
            [pointer, value] {
                json j = sample_scene("bad.png");
                set_at(j, pointer, value);
                return std::optional<std::string>(j.dump(2));
            },
            expect.empty() ? pointer : expect};
}

BadCase erased(const std::string& name, const std::string& pointer) {
    return {name,
            [pointer] {
                json j = sample_scene("bad.png");
                erase_at(j, pointer);
                return std::optional<std::string>(j.dump(2));
            },
            pointer};
}

std::vector<BadCase> bad_cases() {
    const std::string full = sample_scene("bad.png").dump(2);
    return {
        raw("nonexistent_file", std::nullopt),
        raw("empty_file", std::string()),
        raw("not_json", std::string("this is not JSON\n")),
        raw("truncated_json", full.substr(0, full.size() / 2)),
        {"missing_scene", [] { return std::optional<std::string>(R"({"Scenery": {}})"); }, "/Scene"},
        edited("scene_not_an_object", "/Scene", "hello"),
        erased("missing_cameras", "/Scene/Cameras"),
        erased("missing_camera_position", "/Scene/Cameras/Camera/Position"),
        edited("object_instead_of_string", "/Scene/Cameras/Camera/ImageName", json{{"name", "x.png"}}),
        edited("non_numeric_vector", "/Scene/Lights/PointLight/Position", "1 2 x"),
        edited("short_vector", "/Scene/Objects/Plane/Normal", "1 2"),
        edited("nan_value", "/Scene/BackgroundColor", "nan 0 0"),
        edited("infinite_radius", "/Scene/Objects/Sphere/0/Radius", "inf"),
        edited("zero_resolution", "/Scene/Cameras/Camera/ImageResolution", "0 16"),
        edited("negative_resolution", "/Scene/Cameras/Camera/ImageResolution", "16 -4"),
        edited("vertex_id_zero", "/Scene/Objects/Mesh/Faces/_data", "3 1 2 1 3 0", "/Scene/Objects/Mesh/Faces"),
        edited("vertex_id_past_end", "/Scene/Objects/Mesh/Faces/_data", "3 1 2 1 3 11", "/Scene/Objects/Mesh/Faces"),
        edited("faces_not_multiple_of_3", "/Scene/Objects/Mesh/Faces/_data", "3 1 2 1 3", "/Scene/Objects/Mesh/Faces"),
        edited("triangle_vertex_past_end", "/Scene/Objects/Triangle/Indices", "5 6 99"),
        edited("sphere_center_past_end", "/Scene/Objects/Sphere/0/Center", "11"),
        edited("material_id_past_end", "/Scene/Objects/Triangle/Material", "3"),
        edited("material_id_zero", "/Scene/Objects/Sphere/0/Material", "0"),
        edited("negative_sphere_radius", "/Scene/Objects/Sphere/1/Radius", "-0.2"),
        edited("unknown_material_type", "/Scene/Materials/Material/1/_type", "glowing"),
        edited("malformed_specular", "/Scene/Materials/Material/0/SpecularReflectance", "1 1"),
        edited("null_ambient", "/Scene/Materials/Material/1/AmbientReflectance", nullptr),
        edited("missing_ply_file", "/Scene/Objects/Mesh/Faces", json{{"_plyFile", "nothere.ply"}}, "nothere.ply"),
        edited("faces_without_data", "/Scene/Objects/Mesh/Faces", json{{"_type", "triangle"}}),
    };
}

}  // namespace

class CliBadInput : public ::testing::TestWithParam<BadCase> {};

// The bad scene is given first, a good one after it: the good one is still rendered,
// the bad one is reported on one line and writes nothing, and the exit status is 1.
TEST_P(CliBadInput, ReportsOneLineAndRendersTheOtherScenes) {
    const BadCase& c = GetParam();
    TempDir tmp;
    const std::string bad = tmp / "bad.json";
    if (std::optional<std::string> text = c.text()) write_text(bad, *text);
    const std::string good = write_scene(tmp.path(), "good.json", sample_scene("good.png"));
    const std::string out = tmp / "out";

    RunResult r = run_raytracer({"-o", out, bad, good}, tmp.path());
    EXPECT_EQ(r.exit_code, 1) << dump(r);

    std::vector<std::string> lines;
    for (const std::string& l : split_lines(r.err))
        if (contains(l, bad)) lines.push_back(l);
    ASSERT_EQ(lines.size(), 1u) << "expected one stderr line naming " << bad << dump(r);
    EXPECT_TRUE(starts_with(lines[0], "error: " + bad))
        << "the error line should start with error: and the scene path" << dump(r);
    if (!c.expect.empty()) {
        EXPECT_TRUE(contains(lines[0], c.expect)) << "the error line should name " << c.expect << dump(r);
    }

    EXPECT_TRUE(is_png(out + "/good.png", 16, 16)) << dump(r);
    EXPECT_EQ(list_files(out), std::vector<std::string>{"good.png"})
        << "the bad scene wrote something, or a temporary file was left" << dump(r);
}

INSTANTIATE_TEST_SUITE_P(Cases, CliBadInput, ::testing::ValuesIn(bad_cases()),
                         [](const ::testing::TestParamInfo<BadCase>& p) { return p.param.name; });

TEST(Cli, BadSceneAfterGoodSceneStillFails) {
    TempDir tmp;
    json j = sample_scene("bad.png");
    erase_at(j, "/Scene/Cameras/Camera/Position");
    const std::string bad = write_scene(tmp.path(), "bad.json", j);
    const std::string good = write_scene(tmp.path(), "good.json", sample_scene("good.png"));
    RunResult r = run_raytracer({"-o", tmp / "out", good, bad}, tmp.path());
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_EQ(count_lines_containing(r.err, "/Scene/Cameras/Camera/Position"), 1) << dump(r);
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"good.png"}) << dump(r);
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
