// The converters (rt/convert/convert.h) and assignment 3's elements: a camera's NumSamples
// and lens, area lights, MotionBlur on every kind that takes it, Roughness on every
// material kind. A scene with all of them goes through glTF (.gltf, .glb) and XML and comes
// back with the same values, rendering the same images byte for byte; edits of a glTF in a
// modelling tool win where glTF has a place (an area light's node), the rest stays; a bad
// extras value is a one-line error naming it, with nothing written; a glTF without these
// extras imports as before; the OBJ export names them in comments. The official scenes of
// assignment 3: tests/test_convert_round_trip.cpp.
#include <gtest/gtest.h>

// A build without tinygltf, pugixml or tinyobjloader (see mk/convert.mk) has none of this.
#if !defined(RT_NO_GLTF) && !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "convert_test_support.h"
#include "rt/convert/convert.h"
#include "rt/loader/load_scene.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace convert_test;

namespace {

// Every element of assignment 3 on every kind that takes it: three cameras (a lens and 9
// samples, NumSamples 1, a focus distance alone), three area lights (normals not of unit
// length, along +z, and one whose normalised form normalises to other bits), Roughness on every material kind but one,
// MotionBlur on a mesh, a transformed mesh, a triangle, a sphere and an instance, beside still ones and a plane.
const char* kScene = R"({"Scene": {
  "BackgroundColor": "5 10 20", "MaxRecursionDepth": "3",
  "Cameras": {"Camera": [
    {"_id": "1", "Position": "0 0 6", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -0.75 0.75",
     "NearDistance": "2", "ImageResolution": "32 24", "ImageName": "lens.png",
     "NumSamples": "9", "FocusDistance": "6", "ApertureSize": "0.3"},
    {"_id": "2", "Position": "0.5 0 6", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -0.75 0.75",
     "NearDistance": "2", "ImageResolution": "32 24", "ImageName": "centre.png", "NumSamples": "1"},
    {"_id": "3", "_type": "lookAt", "Position": "1 1 6", "GazePoint": "0 0 0", "Up": "0 1 0", "FovY": "40",
     "NearDistance": "1", "ImageResolution": "32 24", "ImageName": "focus.png", "FocusDistance": "5"}]},
  "Lights": {"AmbientLight": "10 10 10",
    "PointLight": {"_id": "1", "Position": "0 4 4", "Intensity": "400 400 400"},
    "AreaLight": [
      {"_id": "1", "Position": "0 3 1", "Normal": "0 0 2", "Size": "1", "Radiance": "30 30 30"},
      {"_id": "2", "Position": "-2 2 2", "Normal": "0.591 -0.010 0.806", "Size": "0.5", "Radiance": "50 40 30"},
      {"_id": "3", "Position": "2 2 -1", "Normal": "1 1 0", "Size": "0.8", "Radiance": "20 30 40"}]},
  "Materials": {"Material": [
    {"_id": "1", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.6 0.5 0.4",
     "SpecularReflectance": "0.2 0.2 0.2", "PhongExponent": "20", "Roughness": "0.2"},
    {"_id": "2", "_type": "mirror", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0.1 0.1 0.1",
     "SpecularReflectance": "0 0 0", "MirrorReflectance": "0.9 0.9 0.9", "Roughness": "0.1"},
    {"_id": "3", "_type": "conductor", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
     "SpecularReflectance": "1 1 1", "MirrorReflectance": "1 0.86 0.57", "RefractionIndex": "0.37",
     "AbsorptionIndex": "2.82", "Roughness": "0.05"},
    {"_id": "4", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
     "SpecularReflectance": "1 1 1", "RefractionIndex": "1.5", "AbsorptionCoefficient": "0.5 0 0",
     "Roughness": "0.3"},
    {"_id": "5", "AmbientReflectance": "0.2 0.2 0.2", "DiffuseReflectance": "0.7 0.7 0.7",
     "SpecularReflectance": "0 0 0"}]},
  "Transformations": {"Translation": {"_id": "1", "_data": "0.2 0 -0.5"},
                      "Scaling": {"_id": "1", "_data": "1 0.5 1"},
                      "Rotation": {"_id": "1", "_data": "30 0 1 0"}},
  "VertexData": {"_data": "-1 -1 0  1 -1 0  1 1 0  -1 1 0  0.5 0.5 0.5  0 -2 0  -2 0 -1  -1 0 -1  -1.5 1 -1  1.5 -0.5 0.3",
                 "_type": "xyz"},
  "Objects": {
    "Mesh": [
      {"_id": "1", "Material": "2", "Faces": {"_data": "1 2 3 1 3 4"}, "MotionBlur": "0 0 -0.5"},
      {"_id": "2", "Material": "3", "Faces": {"_data": "7 8 9"}, "Transformations": "t1 r1", "MotionBlur": "0.1 0 0"},
      {"_id": "3", "_shadingMode": "smooth", "Material": "5", "Faces": {"_data": "1 2 3"}}],
    "Triangle": {"_id": "1", "Material": "1", "Indices": "7 8 9", "MotionBlur": "0 0.2 0"},
    "Sphere": [
      {"_id": "1", "Material": "4", "Center": "5", "Radius": "0.4", "MotionBlur": "0.3 0 0"},
      {"_id": "2", "Material": "5", "Center": "10", "Radius": "0.3", "Transformations": "s1"}],
    "MeshInstance": [
      {"_id": "4", "_baseMeshId": "3", "Material": "1", "Transformations": "t1", "MotionBlur": "0 0.1 0.1"},
      {"_id": "5", "_baseMeshId": "3", "Transformations": "r1"}],
    "Plane": {"_id": "1", "Material": "5", "Point": "6", "Normal": "0 1 0"}}}})";

// The keys of the export's extras that hold assignment 3's values (src/convert/gltf_extras.h).
const std::vector<std::string> kExtrasKeys = {"numSamples", "focusDistance", "apertureSize", "motionBlur",
                                              "roughness",  "areaLight",     "areaLights"};

json read_json(const std::string& path) { return json::parse(read_text(path)); }

// The scene in tmp/scene.json, exported to tmp/<name>.
std::string exported(const TempDir& tmp, const std::string& name, const std::string& scene = kScene) {
    write_text(tmp / "scene.json", scene);
    rt::convert_file(tmp / "scene.json", tmp / name);
    return tmp / name;
}

// The index of the glTF node called `name`.
size_t node_named(const json& g, const std::string& name) {
    for (size_t i = 0; i < g["nodes"].size(); ++i)
        if (g["nodes"][i].value("name", "") == name) return i;
    ADD_FAILURE() << "no node " << name;
    return 0;
}

// `f` applied to every "ceng795" extras object of the glTF.
void for_each_ours(json& v, const std::function<void(json&)>& f) {
    if (v.is_object()) {
        if (v.contains("extras") && v["extras"].is_object() && v["extras"].contains("ceng795"))
            f(v["extras"]["ceng795"]);
        for (auto& child : v.items()) for_each_ours(child.value(), f);
    } else if (v.is_array()) {
        for (json& child : v) for_each_ours(child, f);
    }
}

}  // namespace

TEST(ConvertDistribution, EveryElementOnEveryKindComesBack) {
    TempDir tmp;
    write_text(tmp / "scene.json", kScene);
    const rt::SceneDesc a = rt::load_scene(tmp / "scene.json");
    ASSERT_TRUE(a.warnings.empty()) << a.warnings.front();
    rt::ConvertOptions all;
    all.camera = 0;
    for (const char* name : {"s.gltf", "s.glb", "s.xml"}) {
        SCOPED_TRACE(name);
        const rt::ConvertResult r = rt::convert_file(tmp / "scene.json", tmp / name);
        const bool xml = fs::path(name).extension() == ".xml";
        if (!xml) rt::convert_file(tmp / name, tmp / "back.json", all);
        const rt::SceneDesc b = rt::load_scene(tmp / (xml ? name : "back.json"));
        EXPECT_TRUE(b.warnings.empty()) << b.warnings.front();
        EXPECT_EQ(distribution_differences(a, b), "");
        // The values are what the file says (not defaults on both sides).
        ASSERT_EQ(b.cameras.size(), 3u);
        EXPECT_EQ(b.cameras[0].num_samples, 9);
        EXPECT_EQ(b.cameras[1].num_samples, 1);
        EXPECT_EQ(b.cameras[2].num_samples, 0);
        EXPECT_EQ(b.cameras[2].focus_distance, 5);
        ASSERT_EQ(b.area_lights.size(), 3u);
        EXPECT_TRUE(same(b.area_lights[1].normal, {rt::Real(0.591), rt::Real(-0.010), rt::Real(0.806)}));
        EXPECT_EQ(b.materials[3].roughness, rt::Real(0.3));
        EXPECT_EQ(b.materials[4].roughness, 0);
        EXPECT_EQ(b.all<rt::InstanceDesc>().size(), 6u);  // meshes 1 to 3, the triangle, the two instances
        // Each camera at its own samples: 9; 1, the pixel's centre; none, the centre too.
        EXPECT_TRUE(same_images(a, b, 0));
        if (!xml) {
            EXPECT_TRUE(any_contains(r.notes, "3 area lights: glTF has none"));
        }
    }
}

TEST(ConvertDistribution, EditsInAModellingToolWinWhereGltfHasAPlace) {
    TempDir tmp;
    json g = read_json(exported(tmp, "s.gltf"));
    // An area light moved, another scaled up; a material recoloured, a camera moved.
    g["nodes"][node_named(g, "AreaLight 1")]["translation"] = {0.5, 3, 1};
    g["nodes"][node_named(g, "AreaLight 2")]["scale"] = {2, 2, 2};
    g["materials"][1]["pbrMetallicRoughness"]["baseColorFactor"] = {0.5, 0.5, 1, 1};
    g["nodes"][node_named(g, "Camera 1")]["translation"] = {0, 0, 8};
    // And a plane set moving, which the format cannot say.
    g["nodes"][node_named(g, "Plane 1")]["extras"]["ceng795"]["motionBlur"] = {1, 0, 0};
    write_text(tmp / "s.gltf", g.dump());
    rt::ConvertOptions all;
    all.camera = 0;
    const rt::ConvertResult r = rt::convert_file(tmp / "s.gltf", tmp / "back.json", all);
    const rt::SceneDesc b = rt::load_scene(tmp / "back.json");
    ASSERT_EQ(b.area_lights.size(), 3u);
    EXPECT_TRUE(same(b.area_lights[0].position, {0.5, 3, 1}));
    EXPECT_TRUE(same(b.area_lights[0].normal, {0, 0, 1}));  // the node's -z axis, turned half about x
    EXPECT_TRUE(same(b.area_lights[0].radiance, {30, 30, 30}));
    EXPECT_EQ(b.area_lights[0].size, 1);
    EXPECT_TRUE(any_contains(r.notes, "area light 1: placed by its node /nodes/"));
    EXPECT_NEAR(b.area_lights[1].size, 2, 1e-6);  // its node's scale now
    EXPECT_TRUE(same(b.area_lights[1].position, {-2, 2, 2}));
    const rt::Vec3 n = rt::normalize(rt::Vec3{0.591, -0.010, 0.806}), m = rt::normalize(b.area_lights[1].normal);
    EXPECT_NEAR(dot(n, m), 1, 1e-6);  // from the node's -z axis now
    EXPECT_TRUE(any_contains(r.notes, "area light 3: the exported values"));
    // What glTF has no place for stays: Roughness, the samples and lens, the motion.
    EXPECT_TRUE(any_contains(r.notes, "material 2 (Material 2): conductor, from its PBR values"));
    EXPECT_EQ(b.materials[1].roughness, rt::Real(0.1));
    EXPECT_TRUE(same(b.cameras[0].position, {0, 0, 8}));
    EXPECT_EQ(b.cameras[0].num_samples, 9);
    EXPECT_EQ(b.cameras[0].aperture_size, rt::Real(0.3));
    EXPECT_TRUE(same(b.all<rt::SphereDesc>()[0].motion, {rt::Real(0.3), 0, 0}));
    EXPECT_TRUE(any_contains(r.warnings, "/extras/ceng795/motionBlur: a plane does not move in the format: left out"));
    EXPECT_TRUE(b.all<rt::PlaneDesc>().at(0).motion.x == 0);
}

TEST(ConvertDistribution, BadExtrasNameTheElementAndWriteNothing) {
    TempDir tmp;
    const json good = read_json(exported(tmp, "s.gltf"));
    const std::string camera = "/cameras/0/extras/ceng795", material = "/materials/1/extras/ceng795";
    auto node = [&](const std::string& name) { return "/nodes/" + std::to_string(node_named(good, name)); };
    auto ours = [&](json& g, const std::string& element) -> json& {
        return g[json::json_pointer(element + "/extras/ceng795")];
    };
    struct Case {
        std::function<void(json&)> edit;
        std::string message;  // after "bad.gltf: "
    };
    const std::string area1 = node("AreaLight 1") + "/extras/ceng795/areaLight";
    const std::vector<Case> cases = {
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"]["numSamples"] = 0; },
         camera + "/numSamples: must be a whole number from 1 to 1048576, got 0"},
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"]["numSamples"] = 2.5; },
         camera + "/numSamples: must be a whole number from 1 to 1048576, got 2.5"},
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"]["numSamples"] = "9"; },
         camera + "/numSamples: must be a whole number from 1 to 1048576, got \"9\""},
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"]["focusDistance"] = -1; },
         camera + "/focusDistance: must be a number above 0, at most 1e30, got -1"},
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"]["apertureSize"] = -0.3; },
         camera + "/apertureSize: must be a number from 0 to 1e30, got -0.3"},
        {[](json& g) { g["cameras"][0]["extras"]["ceng795"].erase("focusDistance"); },
         camera + "/apertureSize: a lens (above 0) needs a focusDistance"},
        {[&](json& g) {
             ours(g, node("Sphere 1"))["motionBlur"] = {1, 2};
         },
         node("Sphere 1") + "/extras/ceng795/motionBlur: must be 3 numbers from -1e30 to 1e30, got [1,2]"},
        {[&](json& g) {
             ours(g, node("MeshInstance 4"))["motionBlur"] = {0, 1e31, 0};
         },
         node("MeshInstance 4") + "/extras/ceng795/motionBlur: must be 3 numbers"},
        {[&](json& g) { ours(g, node("Mesh 1"))["motionBlur"] = "0 0 -0.5"; },
         node("Mesh 1") + "/extras/ceng795/motionBlur: must be 3 numbers from -1e30 to 1e30, got \"0 0 -0.5\""},
        {[&](json& g) { ours(g, node("AreaLight 1"))["areaLight"]["size"] = 0; },
         area1 + "/size: must be a number above 0, at most 1e30, got 0"},
        {[&](json& g) {
             ours(g, node("AreaLight 1"))["areaLight"]["normal"] = {0, 0, 0};
         },
         area1 + "/normal: must be 3 numbers from -1e30 to 1e30, not all 0"},
        {[&](json& g) {
             ours(g, node("AreaLight 2"))["areaLight"]["radiance"] = {-1, 0, 0};
         },
         node("AreaLight 2") + "/extras/ceng795/areaLight/radiance: must be 3 numbers from 0 to 1e30"},
        {[&](json& g) { ours(g, node("AreaLight 1"))["areaLight"].erase("radiance"); }, area1 + ": has no radiance"},
        {[&](json& g) { ours(g, node("AreaLight 1"))["areaLight"] = 5; }, area1 + ": must be an object"},
        {[](json& g) { g["materials"][1]["extras"]["ceng795"]["roughness"] = -0.1; },
         material + "/roughness: must be a number from 0 to 1e30, got -0.1"},
        {[](json& g) { g["materials"][1]["extras"]["ceng795"]["roughness"] = true; },
         material + "/roughness: must be a number from 0 to 1e30, got true"},
    };
    rt::ConvertOptions all;
    all.camera = 0;
    for (const Case& c : cases) {
        SCOPED_TRACE(c.message);
        for (const char* leftover : {"bad.json", "bad_1.ply"}) fs::remove(tmp / leftover);  // a failed case's
        json g = good;
        c.edit(g);
        write_text(tmp / "bad.gltf", g.dump());
        const std::string e = error_of(tmp / "bad.gltf", tmp / "bad.json", all);
        EXPECT_EQ(e.rfind(tmp / "bad.gltf: " + c.message, 0), 0u) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        EXPECT_FALSE(fs::exists(tmp / "bad.json"));
        EXPECT_FALSE(fs::exists(tmp / "bad_1.ply"));
    }
    // The command line: exit status 1, one error line.
    json g = good;
    g["cameras"][0]["extras"]["ceng795"]["numSamples"] = 0;
    write_text(tmp / "bad.gltf", g.dump());
    const RunResult r = run_program(rtconvert_path(), {"-q", "bad.gltf", "bad.json"}, tmp.path());
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "error: bad.gltf: " + camera + "/numSamples: must be a whole number from 1 to 1048576, got 0\n");
}

TEST(ConvertDistribution, GltfWithoutTheseExtrasImportsAsBefore) {
    TempDir tmp;
    // A scene without assignment 3's elements: none of their extras is written.
    json plain = json::parse(kScene);
    for (json& c : plain["Scene"]["Cameras"]["Camera"])
        for (const char* key : {"NumSamples", "FocusDistance", "ApertureSize"}) c.erase(key);
    plain["Scene"]["Lights"].erase("AreaLight");
    for (json& m : plain["Scene"]["Materials"]["Material"]) m.erase("Roughness");
    for (auto& kind : plain["Scene"]["Objects"].items()) {
        json& list = kind.value();
        if (!list.is_array()) list = json::array({list});
        for (json& o : list) o.erase("MotionBlur");
    }
    const std::string plain_gltf = read_text(exported(tmp, "plain.gltf", plain.dump()));
    for (const std::string& key : kExtrasKeys) EXPECT_FALSE(contains(plain_gltf, "\"" + key + "\"")) << key;

    // The full scene's glTF, and the same without those extras (as a tool that drops them
    // writes it): the same scene file but for the keys they make.
    const json full = read_json(exported(tmp, "full.gltf"));
    json stripped = full;
    for_each_ours(stripped, [](json& ours) {
        for (const std::string& key : kExtrasKeys) ours.erase(key);
    });
    fs::create_directories(tmp / "a");
    fs::create_directories(tmp / "b");
    write_text(tmp / "a/s.gltf", full.dump());
    write_text(tmp / "b/s.gltf", stripped.dump());
    for (const char* d : {"a", "b"}) fs::copy_file(tmp / "full.bin", tmp / (std::string(d) + "/full.bin"));
    rt::ConvertOptions all;
    all.camera = 0;
    rt::convert_file(tmp / "a/s.gltf", tmp / "a/back.json", all);
    rt::convert_file(tmp / "b/s.gltf", tmp / "b/back.json", all);
    json with = read_json(tmp / "a/back.json");
    const json without = read_json(tmp / "b/back.json");
    with["Scene"]["Lights"].erase("AreaLight");
    for (json& c : with["Scene"]["Cameras"]["Camera"])
        for (const char* key : {"NumSamples", "FocusDistance", "ApertureSize"}) c.erase(key);
    for (json& m : with["Scene"]["Materials"]["Material"]) m.erase("Roughness");
    for (auto& kind : with["Scene"]["Objects"].items())
        for (json& o : kind.value()) o.erase("MotionBlur");
    EXPECT_EQ(with, without);
    EXPECT_FALSE(contains(read_text(tmp / "b/back.json"), "MotionBlur"));
    const rt::SceneDesc d = rt::load_scene(tmp / "b/back.json");
    EXPECT_TRUE(d.area_lights.empty());
    EXPECT_EQ(d.cameras.at(0).num_samples, 0);
    EXPECT_EQ(d.materials.at(1).roughness, 0);
}

TEST(ConvertDistribution, ObjExportNamesThemInComments) {
    TempDir tmp;
    write_text(tmp / "scene.json", kScene);
    rt::convert_file(tmp / "scene.json", tmp / "s.obj");
    const std::string obj = read_text(tmp / "s.obj"), mtl = read_text(tmp / "s.mtl");
    EXPECT_TRUE(contains(obj, ", image lens.png, NumSamples 9, ApertureSize 0.3, FocusDistance 6\n")) << obj;
    EXPECT_TRUE(
        contains(obj, "# area light 2: position -2 2 2, normal 0.591 -0.01 0.806, size 0.5, radiance 50 40 30\n"));
    EXPECT_TRUE(contains(obj, "o sphere_1\n# MotionBlur 0.3 0 0\n"));
    EXPECT_TRUE(contains(mtl, ", Roughness 0.05\n"));
}

#endif  // !RT_NO_GLTF && !RT_NO_XML && !RT_NO_OBJ
