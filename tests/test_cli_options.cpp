// Command-line behaviour of ./raytracer, its options and messages, run as a separate process
// on tiny scenes written into temporary folders (the assignment's sample scene, spec
// section 7, at 16x16: cli_test_support.h).
//
// The contract:
//   -o DIR / --output-dir DIR, -j N / --threads N, --cull / --no-cull,
//   --rounding truncate|nearest, --precision, -q / --quiet, -h / --help (exit 0),
//   --version (exit 0); unknown option: exit 2, one line plus the usage; bad option
//   values are rejected without rendering; every option takes its value in every
//   spelling, the last of a repeated option counts, -- ends the options; one stderr
//   line per image unless --quiet; warnings do not change the exit status.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "test_support.h"

using json = nlohmann::ordered_json;
using namespace cli_test;

namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return s;
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
        {{"--samples", "4", "--sampler", "sobol"}, {"--samples=4", "--sampler=sobol"}},
        {{"--samples", "4", "--noise-target", "3", "--max-samples", "32"},
         {"--samples=4", "--noise-target=3", "--max-samples=32"}},
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
            for (const char* varies : {"seconds", "seconds_min", "seconds_max", "rays_per_second", "peak_rss_bytes",
                                       "render_rss_bytes", "image"})
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
        "usage: raytracer [-o DIR] [-j N] [--precision double|float] [--isa LEVEL] [--cull|--no-cull]\n"
        "                 [--rounding truncate|nearest] [--min-weight W] [--stats FILE] [-q] [--strict]\n"
        "                 [--samples N] [--seed S] [--sampler MODE] [--noise-target E [--max-samples N]]\n"
        "                 [--sample-map FILE] [--repeat N] [--max-depth N] [--epsilon-scale F]\n"
        "                 [--bvh-... (measurements)] [--frames A:B] [--shard K/N] scene.json|scene.xml...\n"
        "       raytracer --trace X,Y [--camera N] [--sample K] [--trace-json FILE] [options] "
        "scene.json|scene.xml";
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
        {{"--stats", "scene.json", "other.json"}, "--stats scene.json: that is a scene file; it is not overwritten"},
        {{"--trace", "1,1", "--trace-json", "scene.json", "scene.json"},
         "--trace-json scene.json: that is a scene file; it is not overwritten"},
        {{"--sampler", "halton", "scene.json"}, "--sampler takes sobol, stratified or random, got 'halton'"},
        {{"--noise-target", "0", "scene.json"}, "--noise-target needs a positive number of levels up to 255, got '0'"},
        {{"--max-samples", "64", "scene.json"}, "--max-samples caps adaptive sampling: it needs --noise-target"},
        {{"--sample-map", "scene.json", "other.json"},
         "--sample-map scene.json: that is a scene file; it is not overwritten"},
        {{"--trace", "1,1", "--sample-map", "m.png", "scene.json"},
         "--sample-map maps a render; --trace renders nothing"},
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
         {"-o, --output-dir DIR", "-j, --threads N", "--cull, --no-cull", "--rounding MODE", "--stats FILE",
          "-q, --quiet",          "-h, --help",      "--version",         "--max-depth N",   "--epsilon-scale F",
          "--bvh-leaf N",         "--bvh-bins N",    "--bvh-split MODE",  "--bvh-cost F",    "--bvh-block N",
          "--precision MODE",     "--isa LEVEL",     "--trace X,Y",       "--camera N",      "--trace-json FILE",
          "exit status"})
        EXPECT_TRUE(contains(r.out, option)) << option << dump(r);
    RunResult v = run_raytracer({"--version"});
    EXPECT_EQ(v.out, "raytracer 1.0 (" RT_ISA_NAME " kernels)\n") << dump(v);
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
    j["Scene"]["Cameras"]["Camera"]["Exposure"] = "4";
    j["Scene"]["TexCoordData"] = nullptr;
    TempDir tmp;
    write_scene(tmp.path(), "scene.json", j);
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path());
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(is_png(tmp / "out/warned.png", 16, 16));
    for (const char* key : {"Exposure", "TexCoordData"}) {
        bool warned = false;
        for (const std::string& l : split_lines(r.err))
            if (contains(l, key) && contains(lower(l), "warning")) warned = true;
        EXPECT_TRUE(warned) << "no warning line naming " << key << dump(r);
    }
}
