// One binary for every x86-64 CPU (rt/cli/isa.h, src/main.cpp; docs/performance.md, "One
// binary, every CPU"): which copy of the library a run uses, and that every copy this CPU
// runs renders the same bytes. make check-march renders every official scene so; this
// checks a small scene, and the choice itself.
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "rt/cli/isa.h"
#include "test_support.h"

using namespace cli_test;

namespace {

// The levels ./raytracer holds, as its refusal of an unknown level lists them.
std::vector<std::string> held_levels() {
    RunResult r = run_raytracer({"--isa", "none-such", "--version"});
    const std::string marker = "a level this raytracer holds: ";
    const size_t at = r.err.find(marker);
    std::vector<std::string> out;
    if (at == std::string::npos) return out;
    std::string rest = r.err.substr(at + marker.size());
    while (!rest.empty() && (rest.back() == '\n' || rest.back() == '\r')) rest.pop_back();
    for (size_t start = 0; start <= rest.size();) {
        const size_t comma = rest.find(", ", start);
        out.push_back(rest.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
        if (comma == std::string::npos) break;
        start = comma + 2;
    }
    return out;
}

}  // namespace

TEST(Isa, BaselineAlwaysRunsAndAvx512ImpliesAvx2) {
    EXPECT_TRUE(rtcli::cpu_runs("x86-64"));
    EXPECT_TRUE(rtcli::cpu_runs("native"));  // a single copy built for this machine
    if (rtcli::cpu_runs("avx512")) EXPECT_TRUE(rtcli::cpu_runs("avx2"));
    const std::string levels = rtcli::cpu_levels();
    EXPECT_EQ(levels.rfind("x86-64", 0), 0u) << levels;
    EXPECT_EQ(levels.find("avx2") != std::string::npos, rtcli::cpu_runs("avx2")) << levels;
    EXPECT_EQ(levels.find("avx512") != std::string::npos, rtcli::cpu_runs("avx512")) << levels;
}

TEST(Isa, AutoChoosesTheLastLevelTheCpuRuns) {
    const std::string built[] = {"x86-64", "avx2", "avx512"};
    const std::string best = rtcli::cpu_runs("avx512") ? "avx512" : rtcli::cpu_runs("avx2") ? "avx2" : "x86-64";
    EXPECT_EQ(rtcli::choose_isa("", built, 3), best);
    EXPECT_EQ(rtcli::choose_isa("auto", built, 3), best);
    EXPECT_EQ(rtcli::choose_isa("auto", built, 1), "x86-64");  // a build holding the baseline alone
    EXPECT_EQ(rtcli::choose_isa("x86-64", built, 3), "x86-64");
}

TEST(Isa, RefusesLevelsNotHeldOrNotRun) {
    const std::string built[] = {"x86-64", "avx2", "avx512"};
    try {
        rtcli::choose_isa("sse4", built, 3);
        ADD_FAILURE() << "sse4 was accepted";
    } catch (const std::invalid_argument& e) {
        EXPECT_EQ(std::string(e.what()), "sse4: expected auto or a level this raytracer holds: x86-64, avx2, avx512");
    }
    EXPECT_THROW(rtcli::choose_isa("avx2", built, 1), std::invalid_argument);  // not held
    for (const char* level : {"avx2", "avx512"})
        if (!rtcli::cpu_runs(level)) {
            EXPECT_THROW(rtcli::choose_isa(level, built, 3), std::invalid_argument) << level;
        } else {
            EXPECT_EQ(rtcli::choose_isa(level, built, 3), level);
        }
}

TEST(Isa, CommandLineNamesTheCopyAndRefusesBadLevels) {
    // The first level a binary holds is one every CPU runs (x86-64 in the Makefile's build,
    // "native" in a single-copy one such as the sanitized build's).
    const std::vector<std::string> held = held_levels();
    ASSERT_FALSE(held.empty()) << "./raytracer listed no level";
    RunResult r = run_raytracer({"--isa", held[0], "--version"});
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    EXPECT_TRUE(contains(r.out, "(" + held[0] + " kernels)")) << dump(r);

    r = run_raytracer({"--isa=pentium", "--version"});
    EXPECT_EQ(r.exit_code, 2) << dump(r);
    EXPECT_EQ(r.err.rfind("error: --isa pentium: expected auto or a level this raytracer holds: ", 0), 0u) << dump(r);

    const char* before = std::getenv("RT_ISA");
    const std::string saved = before ? before : "";
    setenv("RT_ISA", "pentium", 1);
    r = run_raytracer({"--version"});
    EXPECT_EQ(r.exit_code, 2) << dump(r);
    EXPECT_EQ(r.err.rfind("error: RT_ISA=pentium: ", 0), 0u) << dump(r);
    r = run_raytracer({"--isa", held[0], "--version"});  // the option wins over the environment
    EXPECT_EQ(r.exit_code, 0) << dump(r);
    if (before)
        setenv("RT_ISA", saved.c_str(), 1);
    else
        unsetenv("RT_ISA");
}

TEST(Isa, EveryLevelThisCpuRunsRendersTheSameBytes) {
    const std::vector<std::string> held = held_levels();
    ASSERT_FALSE(held.empty()) << "./raytracer listed no level";
    TempDir tmp;
    nlohmann::ordered_json scene = sample_scene("simple.png", "64 48");
    write_scene(tmp.path(), "scene.json", scene);
    std::string first, first_level;
    int ran = 0;
    for (const std::string& level : held) {
        if (!rtcli::cpu_runs(level)) continue;
        RunResult r = run_raytracer({"-q", "--isa", level, "-o", level, "scene.json"}, tmp.path());
        ASSERT_EQ(r.exit_code, 0) << level << dump(r);
        const std::string png = read_text(tmp.path() + "/" + level + "/simple.png");
        ASSERT_FALSE(png.empty()) << level;
        ++ran;
        if (first.empty()) {
            first = png;
            first_level = level;
        } else {
            EXPECT_TRUE(png == first) << level << " and " << first_level << " rendered different bytes";
        }
    }
    EXPECT_GE(ran, 1);
}
