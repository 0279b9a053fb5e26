// Hostile input through the ./raytracer binary: every class of malformed scene or
// PLY file gives one stderr line naming the file and the place, exit status 1, no
// image (no temporary file either), and the good scene given after it on the same
// command line renders the same bytes as it does alone. Complements test_cli_bad_input.cpp
// (CliBadInput), which covers the JSON classes it lists; this file adds the PLY
// classes through the binary, the camera and size classes, number edge cases, and
// the fuzzers' regression inputs (tests/fuzz/regressions).
#include <gtest/gtest.h>

#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/ply.h"
#include "test_support.h"

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

// A 12x12 scene with every object kind; the mesh comes from mesh.ply beside it.
const char* const kScene = R"({
  "Scene": {
    "BackgroundColor": "0 0 0",
    "Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
      "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "12 12", "ImageName": "bad.png"}},
    "Lights": {"AmbientLight": "25 25 25",
      "PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "1000 1000 1000"}},
    "Materials": {"Material": [
      {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1", "SpecularReflectance": "1 1 1"},
      {"_id": "2", "_type": "mirror", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0.2 0.2 0.2",
       "SpecularReflectance": "0 0 0", "MirrorReflectance": "0.7 0.7 0.7"}]},
    "VertexData": {"_data": "0 -0.5 -3 0.5 0.5 -2 -0.5 0.5 -2 0 0 -4", "_type": "xyz"},
    "Objects": {
      "Mesh": {"_id": "1", "Material": "1", "Faces": {"_plyFile": "mesh.ply"}},
      "Triangle": {"_id": "1", "Material": "2", "Indices": "1 2 3"},
      "Sphere": {"_id": "1", "Material": "1", "Center": "4", "Radius": "0.5"},
      "Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 1 0"}
    }
  }
})";

const char* const kGoodPly =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 2\nproperty list uchar int vertex_indices\nend_header\n"
    "-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n3 0 1 2\n3 0 2 3\n";

std::string le32(uint32_t v) {
    std::string s(4, '\0');
    for (int i = 0; i < 4; ++i) s[i] = char((v >> (8 * i)) & 0xff);
    return s;
}
std::string lef(float f) {
    uint32_t u;
    std::memcpy(&u, &f, 4);
    return le32(u);
}

// A binary little-endian PLY: `nv` vertices declared, `nf` faces declared, the
// body as given (so counts and body can disagree).
std::string binary_ply(uint64_t nv, uint64_t nf, const std::string& body) {
    return "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
           "\nproperty float x\nproperty float y\nproperty float z\nelement face " + std::to_string(nf) +
           "\nproperty list uchar int vertex_indices\nend_header\n" + body;
}
std::string binary_vertices(int n) {
    std::string s;
    for (int i = 0; i < n; ++i) s += lef(float(i % 2)) + lef(float(i / 2)) + lef(-5.0f);
    return s;
}
std::string binary_face(uint32_t a, uint32_t b, uint32_t c) {
    return std::string(1, '\3') + le32(a) + le32(b) + le32(c);
}

json scene_json() { return json::parse(kScene); }

// `s` with the first `from` replaced by `to`.
std::string with(std::string s, const std::string& from, const std::string& to) {
    const size_t at = s.find(from);
    if (at != std::string::npos) s.replace(at, from.size(), to);
    return s;
}

struct Case {
    std::string name;
    std::function<json()> scene;      // the bad scene (written as bad.json)
    std::string ply;                  // written as mesh.ply beside it
    std::vector<std::string> expect;  // each must appear in the error line
    std::string raw;                  // when set: bad.json's text instead of scene()
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

Case ply_case(const std::string& name, const std::string& ply, std::vector<std::string> expect) {
    expect.insert(expect.begin(), "/Scene/Objects/Mesh/Faces/_plyFile");
    expect.insert(expect.begin() + 1, "mesh.ply");
    return {name, scene_json, ply, expect, ""};
}

Case edit_case(const std::string& name, const std::string& pointer, const json& value,
               std::vector<std::string> expect = {}) {
    if (expect.empty()) expect.push_back(pointer);
    return {name,
            [pointer, value] {
                json j = scene_json();
                j[json::json_pointer(pointer)] = value;
                return j;
            },
            kGoodPly, expect, ""};
}

Case raw_case(const std::string& name, const std::string& text, std::vector<std::string> expect) {
    return {name, scene_json, kGoodPly, expect, text};
}

std::vector<Case> cases() {
    const std::string v4 = binary_vertices(4);
    const std::string f2 = binary_face(0, 1, 2) + binary_face(0, 2, 3);
    const std::string ascii_head =
        "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 2\nproperty list uchar int vertex_indices\nend_header\n";
    return {
        // ---- PLY files -------------------------------------------------------------
        ply_case("ply_empty", "", {"byte 0"}),
        ply_case("ply_not_ply", "solid cube\nfacet normal 0 0 1\n", {"byte 0", "not a PLY file"}),
        ply_case("ply_unknown_format", "ply\nformat binary_middle_endian 1.0\nend_header\n", {"byte 4", "format"}),
        ply_case("ply_unknown_type", "ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n0\n",
                 {"byte 38", "quad"}),
        ply_case("ply_missing_end_header", binary_ply(4, 2, "").substr(0, 120), {"byte ", "end_header"}),
        ply_case("ply_no_vertex_element", "ply\nformat ascii 1.0\nelement face 0\nend_header\n", {"byte ", "vertex"}),
        ply_case("ply_truncated_binary_vertices", binary_ply(4, 2, v4.substr(0, 30)), {"byte "}),
        ply_case("ply_truncated_binary_faces", binary_ply(4, 2, v4 + f2.substr(0, 20)), {"byte "}),
        ply_case("ply_truncated_ascii", ascii_head + "-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n3 0 1 2\n3 0 2",
                 {"line 15", "end of file"}),
        ply_case("ply_huge_vertex_count", binary_ply(4000000000ull, 2, v4 + f2),
                 {"byte ", "more than the file can hold"}),
        ply_case("ply_huge_face_count", binary_ply(4, 1ull << 62, v4 + f2), {"byte ", "more than the file can hold"}),
        ply_case("ply_count_overflows_uint64",
                 with(binary_ply(4, 0, v4), "vertex 4\n", "vertex 99999999999999999999999\n"),
                 {"byte ", "element count"}),
        ply_case("ply_huge_ascii_count", with(ascii_head, "vertex 4\n", "vertex 123456789012\n") + "0 0 0\n",
                 {"byte ", "more than the file can hold"}),
        ply_case("ply_index_past_end_binary", binary_ply(4, 2, v4 + binary_face(0, 1, 2) + binary_face(0, 2, 4)),
                 {"byte ", "out of range"}),
        ply_case("ply_negative_index_binary",
                 binary_ply(4, 2, v4 + binary_face(0, 1, 2) + binary_face(0xffffffffu, 2, 3)),
                 {"byte ", "out of range"}),
        ply_case("ply_index_past_end_ascii", ascii_head + "-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n3 0 1 2\n3 0 2 9\n",
                 {"line 15", "out of range"}),
        ply_case("ply_nan_coordinate", ascii_head + "-1 -1 -5\n1 nan -5\n1 1 -5\n-1 1 -5\n3 0 1 2\n3 0 2 3\n",
                 {"line 11", "non-finite"}),
        ply_case("ply_face_with_two_vertices", ascii_head + "-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n2 0 1\n3 0 2 3\n",
                 {"line 14"}),
        ply_case("ply_coordinate_beyond_1e30", ascii_head + "-1 -1 -5\n1 -1 -5\n1 1e31 -5\n-1 1 -5\n3 0 1 2\n3 0 2 3\n",
                 {"vertex 2", "1e+31"}),
        // A fuzz finding: an ascii element without properties and a count of 8e10; a
        // reader that loops over the empty records runs for minutes.
        ply_case("ply_empty_element_huge_count",
                 with(ascii_head, "element face", "element junk 84294967296\nelement face") +
                     "-1 -1 -5\n1 -1 -5\n1 1 -5\n-1 1 -5\n3 0 1 2\n3 0 2 9\n",
                 {"line 16", "out of range"}),
        // ---- cameras and sizes -------------------------------------------------------
        edit_case("zero_gaze", "/Scene/Cameras/Camera/Gaze", "0 0 0"),
        edit_case("up_parallel_to_gaze", "/Scene/Cameras/Camera/Up", "0 0 -3"),
        edit_case("up_antiparallel_to_gaze", "/Scene/Cameras/Camera/Up", "0 0 2"),
        edit_case("zero_up", "/Scene/Cameras/Camera/Up", "0 0 0"),
        edit_case("zero_near_distance", "/Scene/Cameras/Camera/NearDistance", "0"),
        edit_case("empty_near_plane", "/Scene/Cameras/Camera/NearPlane", "1 1 -1 1"),
        edit_case("resolution_too_large", "/Scene/Cameras/Camera/ImageResolution", "200000 200000",
                  {"/Scene/Cameras/Camera/ImageResolution", "too large"}),
        edit_case("resolution_beyond_int", "/Scene/Cameras/Camera/ImageResolution", "1e12 1",
                  {"/Scene/Cameras/Camera/ImageResolution", "too large"}),
        edit_case("fractional_resolution", "/Scene/Cameras/Camera/ImageResolution", "12.5 12"),
        edit_case("empty_image_name", "/Scene/Cameras/Camera/ImageName", ""),
        // ---- objects -------------------------------------------------------------------
        edit_case("zero_sphere_radius", "/Scene/Objects/Sphere/Radius", "0"),
        edit_case("nan_sphere_radius", "/Scene/Objects/Sphere/Radius", "nan"),
        edit_case("zero_plane_normal", "/Scene/Objects/Plane/Normal", "0 0 0"),
        edit_case("fractional_vertex_id", "/Scene/Objects/Triangle/Indices", "1 2 2.5"),
        edit_case("negative_vertex_id", "/Scene/Objects/Triangle/Indices", "1 2 -3"),
        edit_case("huge_vertex_id", "/Scene/Objects/Triangle/Indices", "1 2 4294967297"),
        edit_case("material_id_negative", "/Scene/Objects/Plane/Material", "-1"),
        edit_case("vertex_data_not_triples", "/Scene/VertexData/_data", "0 0 0 1 1"),
        edit_case("coordinate_beyond_1e30", "/Scene/VertexData/_data", "0 -0.5 -3 0.5 0.5 -2 -0.5 0.5 -2 0 0 -1e31",
                  {"/Scene/VertexData/_data", "1e+31"}),
        edit_case("negative_colour", "/Scene/Lights/PointLight/Intensity", "1000 -1 1000"),
        edit_case("negative_shadow_epsilon", "/Scene/ShadowRayEpsilon", "-1e-3"),
        edit_case("recursion_depth_not_integer", "/Scene/MaxRecursionDepth", "2.5"),
        edit_case("recursion_depth_huge", "/Scene/MaxRecursionDepth", "1e9"),
        // ---- JSON types ----------------------------------------------------------------
        edit_case("cameras_is_a_number", "/Scene/Cameras", 3),
        edit_case("camera_array_holds_a_string", "/Scene/Cameras/Camera", json::array({"camera"}),
                  {"/Scene/Cameras/Camera/0"}),
        edit_case("materials_is_an_array", "/Scene/Materials", json::array()),
        edit_case("radius_is_a_boolean", "/Scene/Objects/Sphere/Radius", true),
        edit_case("position_is_an_array", "/Scene/Cameras/Camera/Position", json::array({0, 0, 0})),
        edit_case("faces_is_null", "/Scene/Objects/Mesh/Faces", nullptr),
        edit_case("ply_file_is_a_number", "/Scene/Objects/Mesh/Faces/_plyFile", 7),
        edit_case("ply_file_is_a_folder", "/Scene/Objects/Mesh/Faces/_plyFile", ".",
                  {"/Scene/Objects/Mesh/Faces/_plyFile"}),
        // ---- JSON text -------------------------------------------------------------------
        raw_case("only_whitespace", "  \n\t\n", {"parse error"}),
        raw_case("top_level_array", "[1, 2, 3]", {"/"}),
        raw_case("top_level_null", "null", {"/"}),
        raw_case("binary_garbage", std::string("\x89PNG\r\n\x1a\n\0\0\0\rIHDR", 16), {"parse error"}),
        raw_case("json_number_overflow", R"({"Scene": {"ShadowRayEpsilon": 1e999}})", {"line 1, column 32", "1e999"}),
        raw_case("unterminated_string", "{\"Scene\": {\"Cameras\": \"abc", {"parse error", "line 1"}),
        raw_case("deep_nesting", std::string(100000, '[') + std::string(100000, ']'), {"/"}),
    };
}

std::string dump(const RunResult& r) {
    return "\n--- exit " + std::to_string(r.exit_code) + " --- stderr ---\n" + r.err + "---";
}

// The good scene every run renders after the bad one; its image alone, for comparison.
const std::string& good_scene_bytes_alone() {
    static const std::string bytes = [] {
        TempDir tmp;
        json j = scene_json();
        j["Scene"]["Cameras"]["Camera"]["ImageName"] = "good.png";
        write_text(tmp / "good.json", j.dump(1));
        write_text(tmp / "mesh.ply", kGoodPly);
        RunResult r = run_raytracer({"-q", "-o", tmp / "out", tmp / "good.json"});
        return r.exit_code == 0 ? read_text(tmp / "out/good.png") : std::string();
    }();
    return bytes;
}

}  // namespace

class BadInput : public ::testing::TestWithParam<Case> {};

TEST_P(BadInput, OneLineNamingFileAndPlaceNoImageOtherSceneUnaffected) {
    const Case& c = GetParam();
    ASSERT_FALSE(good_scene_bytes_alone().empty()) << "the good scene does not render on its own";

    TempDir tmp;
    fs::create_directories(tmp / "bad");
    fs::create_directories(tmp / "good");
    const std::string bad = tmp / "bad/bad.json";
    write_text(bad, c.raw.empty() ? c.scene().dump(1) : c.raw);
    write_text(tmp / "bad/mesh.ply", c.ply);
    json g = scene_json();
    g["Scene"]["Cameras"]["Camera"]["ImageName"] = "good.png";
    write_text(tmp / "good/good.json", g.dump(1));
    write_text(tmp / "good/mesh.ply", kGoodPly);

    const auto t0 = std::chrono::steady_clock::now();
    RunResult r = run_raytracer({"-o", tmp / "out", bad, tmp / "good/good.json"}, tmp.path(), 60);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_LT(seconds, 20) << "bad input should be refused quickly" << dump(r);
    std::vector<std::string> lines;
    for (const std::string& l : split_lines(r.err))
        if (contains(l, bad)) lines.push_back(l);
    ASSERT_EQ(lines.size(), 1u) << "expected exactly one stderr line naming " << bad << dump(r);
    EXPECT_EQ(lines[0].rfind("error: " + bad + ": ", 0), 0u)
        << "the line should start with error: and the scene path" << dump(r);
    for (const std::string& e : c.expect)
        EXPECT_TRUE(contains(lines[0], e)) << "the line should name '" << e << "'" << dump(r);

    // Nothing from the bad scene (no image, no temporary), the good scene's image intact.
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"good.png"}) << dump(r);
    EXPECT_TRUE(read_text(tmp / "out/good.png") == good_scene_bytes_alone())
        << "the good scene's image differs when a bad scene comes first";
    EXPECT_FALSE(file_exists(tmp / "bad.png"));
    EXPECT_FALSE(file_exists(tmp / "bad/bad.png"));
}

INSTANTIATE_TEST_SUITE_P(Classes, BadInput, ::testing::ValuesIn(cases()),
                         [](const ::testing::TestParamInfo<Case>& p) { return p.param.name; });

// A scene file that is a folder, or a device: refused with a line naming it.
TEST(BadInputFiles, FolderAsSceneFile) {
    TempDir tmp;
    fs::create_directories(tmp / "scene.json");
    RunResult r = run_raytracer({"-o", tmp / "out", tmp / "scene.json"}, tmp.path(), 30);
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_TRUE(contains(r.err, tmp / "scene.json")) << dump(r);
    EXPECT_FALSE(file_exists(tmp / "out")) << dump(r);
}

TEST(BadInputFiles, DevNullAsSceneFile) {
    TempDir tmp;
    RunResult r = run_raytracer({"-o", tmp / "out", "/dev/null"}, tmp.path(), 30);
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_TRUE(contains(r.err, "/dev/null")) << dump(r);
    EXPECT_FALSE(file_exists(tmp / "out")) << dump(r);
}

// A PLY path naming an endless device must not hang or exhaust memory.
TEST(BadInputFiles, DevZeroAsPlyFile) {
    TempDir tmp;
    json j = scene_json();
    j["Scene"]["Objects"]["Mesh"]["Faces"]["_plyFile"] = "/dev/zero";
    write_text(tmp / "scene.json", j.dump(1));
    RunResult r = run_raytracer({"-o", tmp / "out", tmp / "scene.json"}, tmp.path(), 30);
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_TRUE(contains(r.err, "/dev/zero")) << dump(r);
    EXPECT_FALSE(file_exists(tmp / "out")) << dump(r);
}

// An output folder that is a regular file: every camera fails, named, nothing left behind.
TEST(BadInputFiles, OutputDirIsAFile) {
    TempDir tmp;
    json j = scene_json();
    write_text(tmp / "scene.json", j.dump(1));
    write_text(tmp / "mesh.ply", kGoodPly);
    write_text(tmp / "out", "a file\n");
    RunResult r = run_raytracer({"-o", tmp / "out", "scene.json"}, tmp.path(), 30);
    EXPECT_EQ(r.exit_code, 1) << dump(r);
    EXPECT_TRUE(contains(r.err, "bad.png")) << dump(r);
    EXPECT_EQ(list_files(tmp.path()), (std::vector<std::string>{"mesh.ply", "out", "scene.json"})) << dump(r);
}

// ---- Fuzz regressions ----------------------------------------------------------------
// Inputs the fuzzers (tests/fuzz) once crashed or hung on. Each must now load or be
// refused with an rt::InputError, quickly; through the binary, exit status 0 or 1.

namespace {

// The repo root: the first folder at or above the current one holding tests/fuzz.
std::string repo_root() {
    std::error_code ec;
    for (fs::path p = fs::current_path(ec); !p.empty(); p = p.parent_path()) {
        if (fs::is_directory(p / "tests/fuzz/regressions", ec)) return p.string();
        if (p == p.parent_path()) break;
    }
    return "";
}

std::vector<std::string> regression_files(const std::string& kind) {
    const std::string root = repo_root();
    if (root.empty()) return {};
    std::vector<std::string> out;
    for (const std::string& f : list_files(root + "/tests/fuzz/regressions/" + kind))
        out.push_back(root + "/tests/fuzz/regressions/" + kind + "/" + f);
    return out;
}

}  // namespace

TEST(FuzzRegressions, PlyInputsAreRefusedOrLoaded) {
    const std::vector<std::string> files = regression_files("ply");
    ASSERT_FALSE(files.empty()) << "tests/fuzz/regressions/ply not found above " << fs::current_path();
    for (const std::string& f : files) {
        SCOPED_TRACE(f);
        const std::string bytes = read_text(f);
        const auto t0 = std::chrono::steady_clock::now();
        try {
            rt::PlyMesh m = rt::parse_ply(bytes.data(), bytes.size(), f);
            for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
        } catch (const rt::InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(f + ": ", 0), 0u) << e.what();
        }
        EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 5);
    }
}

TEST(FuzzRegressions, SceneInputsAreRefusedOrLoaded) {
    const std::vector<std::string> files = regression_files("scene");
    ASSERT_FALSE(files.empty()) << "tests/fuzz/regressions/scene not found above " << fs::current_path();
    for (const std::string& f : files) {
        SCOPED_TRACE(f);
        TempDir tmp;
        // Through the library ...
        try {
            rt::parse_scene(read_text(f), tmp / "scene.json");
        } catch (const rt::InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(tmp / "scene.json: ", 0), 0u) << e.what();
        }
        // ... and through the binary: no crash, no hang. The scene's own image names
        // point anywhere, so the renders go under a scratch folder, at most 64x64.
        json j;
        bool parsed = true;
        try {
            j = json::parse(read_text(f));
        } catch (const json::exception&) {
            parsed = false;
        }
        std::string text = read_text(f);
        if (parsed && j.is_object() && j.contains("Scene") && j["Scene"].is_object() &&
            j["Scene"].contains("Cameras")) {
            // Keep the regression about its finding, not about a slow render.
            try {
                json& cams = j["Scene"]["Cameras"]["Camera"];
                auto shrink = [](json& c) {
                    if (c.is_object()) {
                        c["ImageResolution"] = "16 16";
                        c["ImageName"] = "img.png";
                    }
                };
                if (cams.is_array())
                    for (json& c : cams) shrink(c);
                else
                    shrink(cams);
                text = j.dump();
            } catch (const json::exception&) {
            }
        }
        write_text(tmp / "scene.json", text);
        RunResult r = run_raytracer({"-q", "-j", "2", "-o", tmp / "out", tmp / "scene.json"}, tmp.path(), 60);
        EXPECT_TRUE(r.exit_code == 0 || r.exit_code == 1) << dump(r);
        if (r.exit_code == 1) {
            EXPECT_TRUE(contains(r.err, tmp / "scene.json")) << dump(r);
        }
    }
}
