// The converters (rt/convert/convert.h, ./rtconvert), round trips: every official scene,
// XML -> JSON and JSON -> XML, loads to the same SceneDesc field by field (the JSON a fixed
// point of XML -> JSON -> XML -> JSON), PLY files keep their place when the converted
// file lands in another folder, and an official PLY scene goes round through the command
// line; assignment 3's scenes through XML and glTF render byte-identical images. Also:
// every scene of our own (scenes/) loads without warnings and renders.
#include <gtest/gtest.h>

// A build without pugixml or tinyobjloader (see mk/convert.mk) has none of this to test.
#if !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "convert_test_support.h"
#include "rt/convert/convert.h"
#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace convert_test;

namespace {

// ---- SceneDesc equality, field by field ---------------------------------------------

std::string canonical(const std::string& path) {
    std::error_code ec;
    const fs::path p = fs::weakly_canonical(path, ec);
    return ec ? path : p.string();
}

// Equal scenes. With `same_file` false the two were loaded from different files:
// the paths in SceneDesc::path, MeshDesc::source and the warnings may differ, but PLY
// sources must name the same file.
::testing::AssertionResult same_scene(const rt::SceneDesc& a, const rt::SceneDesc& b, bool same_file = true) {
    std::ostringstream why;
    auto differ = [&](const std::string& what) { why << what << "; "; };
#define RT_CMP_VEC(x) \
    if (!same(a.x, b.x)) differ(#x ": " + str(a.x) + " vs " + str(b.x))
#define RT_CMP(x) \
    if (!(a.x == b.x)) differ(#x)
    RT_CMP_VEC(background);
    RT_CMP(shadow_ray_epsilon);
    RT_CMP(intersection_test_epsilon);
    RT_CMP(max_recursion_depth);
    RT_CMP_VEC(ambient_light);
    if (same_file) {
        RT_CMP(path);
        RT_CMP(warnings);
    } else if (a.warnings.size() != b.warnings.size()) {
        differ("warning count");
    }
#undef RT_CMP
#undef RT_CMP_VEC
    if (a.cameras.size() != b.cameras.size()) differ("camera count");
    for (size_t i = 0; i < std::min(a.cameras.size(), b.cameras.size()); ++i) {
        const rt::CameraDesc &x = a.cameras[i], &y = b.cameras[i];
        if (!same(x.position, y.position) || !same(x.gaze, y.gaze) || !same(x.up, y.up) || x.left != y.left ||
            x.right != y.right || x.bottom != y.bottom || x.top != y.top || x.near_distance != y.near_distance ||
            x.width != y.width || x.height != y.height || x.image_name != y.image_name)
            differ("camera " + std::to_string(i));
    }
    if (a.point_lights.size() != b.point_lights.size()) differ("light count");
    for (size_t i = 0; i < std::min(a.point_lights.size(), b.point_lights.size()); ++i)
        if (!same(a.point_lights[i].position, b.point_lights[i].position) ||
            !same(a.point_lights[i].intensity, b.point_lights[i].intensity))
            differ("light " + std::to_string(i));
    if (a.materials.size() != b.materials.size()) differ("material count");
    for (size_t i = 0; i < std::min(a.materials.size(), b.materials.size()); ++i) {
        const rt::MaterialDesc &x = a.materials[i], &y = b.materials[i];
        if (x.type != y.type || !same(x.ambient, y.ambient) || !same(x.diffuse, y.diffuse) ||
            !same(x.specular, y.specular) || x.phong_exponent != y.phong_exponent || !same(x.mirror, y.mirror) ||
            x.refraction_index != y.refraction_index || x.absorption_index != y.absorption_index ||
            !same(x.absorption_coefficient, y.absorption_coefficient))
            differ("material " + std::to_string(i));
    }
    if (a.meshes.size() != b.meshes.size()) differ("mesh count");
    for (size_t i = 0; i < std::min(a.meshes.size(), b.meshes.size()); ++i) {
        const rt::MeshDesc &x = a.meshes[i], &y = b.meshes[i];
        bool positions = x.positions.size() == y.positions.size();
        for (size_t k = 0; positions && k < x.positions.size(); ++k) positions = same(x.positions[k], y.positions[k]);
        const bool sources = same_file
                                 ? x.source == y.source
                                 : (x.source.rfind("/Scene", 0) == 0 ? x.source == y.source
                                                                     : canonical(x.source) == canonical(y.source));
        if (x.material != y.material || x.shading != y.shading || !positions || x.indices != y.indices || !sources)
            differ("mesh " + std::to_string(i) + " (" + x.source + " vs " + y.source + ")");
    }
    if (a.all<rt::SphereDesc>().size() != b.all<rt::SphereDesc>().size()) differ("sphere count");
    for (size_t i = 0; i < std::min(a.all<rt::SphereDesc>().size(), b.all<rt::SphereDesc>().size()); ++i)
        if (a.all<rt::SphereDesc>()[i].material != b.all<rt::SphereDesc>()[i].material ||
            !same(a.all<rt::SphereDesc>()[i].center, b.all<rt::SphereDesc>()[i].center) ||
            a.all<rt::SphereDesc>()[i].radius != b.all<rt::SphereDesc>()[i].radius)
            differ("sphere " + std::to_string(i));
    if (a.all<rt::PlaneDesc>().size() != b.all<rt::PlaneDesc>().size()) differ("plane count");
    for (size_t i = 0; i < std::min(a.all<rt::PlaneDesc>().size(), b.all<rt::PlaneDesc>().size()); ++i)
        if (a.all<rt::PlaneDesc>()[i].material != b.all<rt::PlaneDesc>()[i].material ||
            !same(a.all<rt::PlaneDesc>()[i].point, b.all<rt::PlaneDesc>()[i].point) ||
            !same(a.all<rt::PlaneDesc>()[i].normal, b.all<rt::PlaneDesc>()[i].normal))
            differ("plane " + std::to_string(i));
    const std::vector<rt::InstanceDesc>&ia = a.all<rt::InstanceDesc>(), &ib = b.all<rt::InstanceDesc>();
    if (ia.size() != ib.size()) differ("instance count");
    for (size_t i = 0; i < std::min(ia.size(), ib.size()); ++i)
        if (ia[i].mesh != ib[i].mesh || ia[i].material != ib[i].material ||
            !std::equal(&ia[i].transform.m[0][0], &ia[i].transform.m[0][0] + 12, &ib[i].transform.m[0][0]))
            differ("instance " + std::to_string(i));
    why << distribution_differences(a, b);
    if (why.str().empty()) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << why.str();
}

// Loads a scene held in memory, or returns the error.
struct Loaded {
    rt::SceneDesc scene;
    std::string error;
};

template <class F>
Loaded attempt(F f) {
    Loaded l;
    try {
        l.scene = f();
    } catch (const rt::InputError& e) {
        l.error = e.what();
    }
    return l;
}

std::vector<std::string> official_scenes(const std::string& sub, const std::string& ext) {
    std::vector<std::string> out;
    const std::string root = shared_dir();
    if (root.empty()) return out;
    for (const std::string& f : list_files(root + "/scenes/" + sub))
        if (fs::path(f).extension() == ext) out.push_back(root + "/scenes/" + sub + "/" + f);
    return out;
}

// The scenes of an assignment's manifest whose inputs are complete, each once.
std::vector<std::string> complete_scenes(const std::string& hw) {
    const std::string dir = shared_dir() + "/scenes/" + hw;
    std::vector<std::string> out;
    for (const std::string& line : split_lines(read_text(dir + "/MANIFEST.tsv"))) {
        std::vector<std::string> cols;
        std::istringstream fields(line);
        for (std::string c; std::getline(fields, c, '\t');) cols.push_back(c);
        if (!line.empty() && line[0] != '#' && cols.size() >= 4 && cols[3].rfind("complete", 0) == 0 &&
            std::find(out.begin(), out.end(), dir + "/" + cols[0]) == out.end())
            out.push_back(dir + "/" + cols[0]);
    }
    return out;
}

}  // namespace

// ---- Round trips of the official scenes ------------------------------------------------

// Assignment 3's elements (NumSamples, the lens, area lights, MotionBlur, Roughness) through
// glTF (.gltf and .glb in turn) and through XML: the same values, exactly, and the same
// images, byte for byte.
TEST(ConvertRoundTrip, EveryCompleteHw3SceneThroughGltfAndXml) {
    SKIP_UNLESS_SHARED("assignment 3's scenes");
    const std::vector<std::string> scenes = complete_scenes("hw3");
    EXPECT_GE(scenes.size(), 8u);
    for (size_t i = 0; i < scenes.size(); ++i) {
        const std::string& path = scenes[i];
        SCOPED_TRACE(path);
        TempDir tmp;
        const rt::SceneDesc a = rt::load_scene(path);
        rt::convert_file(path, tmp / "s.xml");
        const rt::SceneDesc x = rt::load_scene(tmp / "s.xml");
        EXPECT_TRUE(same_scene(a, x, false));
        EXPECT_TRUE(same_images(a, x, 4));
#ifndef RT_NO_GLTF
        const std::string gltf = tmp / (i % 2 ? "s.glb" : "s.gltf");
        rt::convert_file(path, gltf);
        rt::ConvertOptions all;
        all.camera = 0;
        rt::convert_file(gltf, tmp / "back.json", all);
        const rt::SceneDesc g = rt::load_scene(tmp / "back.json");
        EXPECT_EQ(distribution_differences(a, g), "");
        EXPECT_TRUE(same_images(a, g, 4));
#endif
    }
}

TEST(ConvertRoundTrip, EveryOfficialJsonSceneThroughXml) {
    SKIP_UNLESS_SHARED("the official JSON scenes");
    const std::vector<std::string> scenes = official_scenes("hw1", ".json");
    EXPECT_GE(scenes.size(), 20u);
    for (const std::string& path : scenes) {
        SCOPED_TRACE(path);
        const std::string text = read_text(path);
        const std::string xml = rt::json_to_xml_text(text, path);
        const Loaded a = attempt([&] { return rt::parse_scene(text, path); });
        const Loaded b = attempt([&] { return rt::parse_scene_xml(xml, path); });
        EXPECT_EQ(a.error, b.error);  // scenes whose PLY files are missing fail alike
        if (a.error.empty() && b.error.empty()) {
            EXPECT_TRUE(same_scene(a.scene, b.scene));
        }
    }
}

TEST(ConvertRoundTrip, EveryOfficialXmlSceneThroughJson) {
    SKIP_UNLESS_SHARED("the official XML scenes");
    const std::vector<std::string> scenes = official_scenes("xml2021", ".xml");
    EXPECT_EQ(scenes.size(), 13u);
    for (const std::string& path : scenes) {
        SCOPED_TRACE(path);
        const std::string xml = read_text(path);
        const std::string text = rt::xml_to_json_text(xml, path);
        const Loaded a = attempt([&] { return rt::parse_scene_xml(xml, path); });
        const Loaded b = attempt([&] { return rt::parse_scene(text, path); });
        EXPECT_EQ(a.error, "");
        EXPECT_EQ(a.error, b.error);
        if (a.error.empty() && b.error.empty()) {
            EXPECT_TRUE(same_scene(a.scene, b.scene));
        }
        // And once more around: the JSON is a fixed point.
        EXPECT_EQ(rt::xml_to_json_text(rt::json_to_xml_text(text, path), path), text);
    }
}

TEST(ConvertRoundTrip, FilesInAnotherFolderKeepTheirPlyFiles) {
    TempDir tmp;
    fs::create_directories(tmp / "src/ply");
    fs::create_directories(tmp / "dst/deeper");
    rt::write_ply(tmp / "src/ply/tri.ply", {0, 0, -2, 1, 0, -2, 0, 1, -2}, {0, 1, 2});
    const json scene = json::parse(R"({"Scene": {
        "Cameras": {"Camera": {"Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -1 1",
                               "NearDistance": "1", "ImageResolution": "8 8", "ImageName": "a.png"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1",
                                   "SpecularReflectance": "0 0 0"}},
        "Objects": {"Mesh": {"_id": "1", "Material": "1", "Faces": {"_plyFile": "ply/tri.ply"}}}}})");
    write_text(tmp / "src/scene.json", scene.dump(2));
    rt::convert_file(tmp / "src/scene.json", tmp / "dst/deeper/scene.xml");
    rt::convert_file(tmp / "dst/deeper/scene.xml", tmp / "dst/scene.json");
    EXPECT_TRUE(contains(read_text(tmp / "dst/deeper/scene.xml"), "plyFile=\"../../src/ply/tri.ply\""))
        << read_text(tmp / "dst/deeper/scene.xml");
    const rt::SceneDesc a = rt::load_scene(tmp / "src/scene.json");
    EXPECT_TRUE(same_scene(a, rt::load_scene(tmp / "dst/deeper/scene.xml"), false));
    EXPECT_TRUE(same_scene(a, rt::load_scene(tmp / "dst/scene.json"), false));
    EXPECT_EQ(a.meshes.at(0).indices.size(), 3u);
}

TEST(ConvertRoundTrip, OfficialPlySceneThroughTheCommandLine) {
    SKIP_UNLESS_SHARED("the official PLY scene");
    const std::string root = shared_dir();
    const std::string path = root + "/scenes/hw1/akif_uslu/ton_Roosendaal_smooth.json";
    TempDir tmp;
    RunResult r = run_program(rtconvert_path(), {"-q", path, tmp / "ton.xml"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err, "");
    r = run_program(rtconvert_path(), {"-q", tmp / "ton.xml", tmp / "ton.json"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const rt::SceneDesc a = rt::load_scene(path);
    EXPECT_TRUE(same_scene(a, rt::load_scene(tmp / "ton.xml"), false));
    EXPECT_TRUE(same_scene(a, rt::load_scene(tmp / "ton.json"), false));
}

// ---- Our own scenes ---------------------------------------------------------------------

TEST(OwnScenes, EveryOneLoadsAndRenders) {
    // scenes/ of this repository: from the folder the tests run in, or one above it.
    std::string dir;
    for (const char* up : {"", "../", "../../"})
        if (file_exists(std::string(up) + "scenes/showcase.json")) {
            dir = std::string(up) + "scenes";
            break;
        }
    ASSERT_FALSE(dir.empty()) << "scenes/ not found from " << fs::current_path();
    std::vector<std::string> scenes;
    for (const std::string& f : list_files(dir))
        if (fs::path(f).extension() == ".json") scenes.push_back(dir + "/" + f);
    EXPECT_GE(scenes.size(), 4u);
    for (const std::string& path : scenes) {
        SCOPED_TRACE(path);
        rt::SceneDesc d = rt::load_scene(path);
        EXPECT_TRUE(d.warnings.empty()) << d.warnings.at(0);
        for (rt::CameraDesc& c : d.cameras) {
            const int longest = std::max(c.width, c.height);
            c.width = std::max(1, c.width * 40 / longest);
            c.height = std::max(1, c.height * 40 / longest);
        }
        const rt::Scene s = rt::build_scene(d);
        EXPECT_EQ(s.report.degenerate_triangles, 0u);
        const rt::Image img = rt::render(s, 0, rt::RenderOptions{});
        EXPECT_GT(*std::max_element(img.rgb.begin(), img.rgb.end()), 100);
    }
}

#endif  // !defined(RT_NO_XML) && !defined(RT_NO_OBJ)
