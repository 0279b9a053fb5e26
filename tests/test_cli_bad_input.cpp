// Command-line behaviour of ./raytracer on bad scenes, run as a separate process on tiny
// scenes written into temporary folders (the assignment's sample scene, spec section 7,
// at 16x16, with edits made through JSON pointers: cli_test_support.h).
//
// The contract: bad input exits 1 with one stderr line "<scene path>: <json pointer>:
// <what>", writes no image of that scene, and the other scenes on the command line are
// still rendered, before or after it. test_bad_input.cpp adds the PLY, camera and size
// classes and the fuzzers' regression inputs.
#include <gtest/gtest.h>

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_test_support.h"
#include "test_support.h"

using json = nlohmann::ordered_json;
using namespace cli_test;

namespace {

bool starts_with(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

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
