// The converters (rt/convert/convert.h, ./rtconvert): lossless XML <-> JSON round trips of
// every official scene, OBJ (+MTL) import on OBJ files written here (quads, negative
// indices, no normals, smoothing groups, with, without and with broken MTL files),
// scene -> OBJ + MTL export, and the command line's errors.
#include <gtest/gtest.h>

// A build without pugixml or tinyobjloader (see mk/convert.mk) has none of this to test.
#if !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rt/convert/convert.h"
#include "rt/core/error.h"
#include "rt/geometry/scene.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

// ---- SceneDesc equality, field by field ---------------------------------------------

bool same(const rt::Vec3& a, const rt::Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

std::string str(const rt::Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
}

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
    if (a.all<rt::Sphere>().size() != b.all<rt::Sphere>().size()) differ("sphere count");
    for (size_t i = 0; i < std::min(a.all<rt::Sphere>().size(), b.all<rt::Sphere>().size()); ++i)
        if (a.all<rt::Sphere>()[i].material != b.all<rt::Sphere>()[i].material ||
            !same(a.all<rt::Sphere>()[i].center, b.all<rt::Sphere>()[i].center) ||
            a.all<rt::Sphere>()[i].radius != b.all<rt::Sphere>()[i].radius)
            differ("sphere " + std::to_string(i));
    if (a.all<rt::Plane>().size() != b.all<rt::Plane>().size()) differ("plane count");
    for (size_t i = 0; i < std::min(a.all<rt::Plane>().size(), b.all<rt::Plane>().size()); ++i)
        if (a.all<rt::Plane>()[i].material != b.all<rt::Plane>()[i].material ||
            !same(a.all<rt::Plane>()[i].point, b.all<rt::Plane>()[i].point) ||
            !same(a.all<rt::Plane>()[i].normal, b.all<rt::Plane>()[i].normal))
            differ("plane " + std::to_string(i));
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

// ---- OBJ helpers -----------------------------------------------------------------

// Converts tmp/<obj> to tmp/out.json and loads it.
struct Imported {
    rt::ConvertResult result;
    rt::SceneDesc scene;
};

Imported import(const TempDir& tmp, const std::string& obj, const rt::ConvertOptions& o = {}) {
    Imported im;
    im.result = rt::convert_file(tmp / obj, tmp / "out.json", o);
    im.scene = rt::load_scene(tmp / "out.json");
    return im;
}

std::string import_error(const TempDir& tmp, const std::string& obj) {
    try {
        rt::convert_file(tmp / obj, tmp / "out.json");
    } catch (const rt::InputError& e) {
        return e.what();
    }
    return "";
}

size_t triangle_count(const rt::SceneDesc& d) {
    size_t n = 0;
    for (const rt::MeshDesc& m : d.meshes) n += m.indices.size() / 3;
    return n;
}

bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
    for (const std::string& l : lines)
        if (contains(l, part)) return true;
    return false;
}

// A triangle of mesh m as points.
std::array<rt::Vec3, 3> tri(const rt::MeshDesc& m, size_t t) {
    return {m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]]};
}

const char* kCube = R"(# a unit cube of quads, counter-clockwise seen from outside
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f -8 -4 -1 -5
f 4 8 7 3
)";

}  // namespace

// ---- Round trips of the official scenes ------------------------------------------------

TEST(ConvertRoundTrip, EveryOfficialJsonSceneThroughXml) {
    const std::vector<std::string> scenes = official_scenes("hw1", ".json");
    if (scenes.empty()) GTEST_SKIP() << "../shared not found (set RT_SHARED_DIR)";
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
    const std::vector<std::string> scenes = official_scenes("xml2021", ".xml");
    if (scenes.empty()) GTEST_SKIP() << "../shared not found (set RT_SHARED_DIR)";
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
    const std::string root = shared_dir();
    if (root.empty()) GTEST_SKIP() << "../shared not found (set RT_SHARED_DIR)";
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

// ---- OBJ import ---------------------------------------------------------------------

TEST(ObjImport, QuadsAreFanSplitAndNegativeIndicesResolved) {
    TempDir tmp;
    write_text(tmp / "cube.obj", kCube);
    const Imported im = import(tmp, "cube.obj");
    const rt::SceneDesc& d = im.scene;
    ASSERT_EQ(d.meshes.size(), 1u);
    const rt::MeshDesc& m = d.meshes[0];
    EXPECT_EQ(m.shading, rt::ShadingMode::Flat) << "no normals, no smoothing group";
    ASSERT_EQ(m.indices.size(), 36u);
    EXPECT_EQ(m.positions.size(), 8u);
    // The fifth face, "f -8 -4 -1 -5" = "f 1 5 8 4", split as (1 5 8) (1 8 4).
    const auto t8 = tri(m, 8), t9 = tri(m, 9);
    EXPECT_TRUE(same(t8[0], {0, 0, 0}) && same(t8[1], {0, 0, 1}) && same(t8[2], {0, 1, 1}));
    EXPECT_TRUE(same(t9[0], {0, 0, 0}) && same(t9[1], {0, 1, 1}) && same(t9[2], {0, 1, 0}));
    // Every face still points out of the cube.
    for (size_t t = 0; t < 12; ++t) {
        const auto p = tri(m, t);
        const rt::Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
        const rt::Vec3 c = (p[0] + p[1] + p[2]) / rt::Real(3) - rt::Vec3{0.5, 0.5, 0.5};
        EXPECT_GT(dot(n, c), 0) << "triangle " << t;
    }
    // No MTL: one default material, no warnings.
    EXPECT_EQ(d.materials.size(), 1u);
    EXPECT_TRUE(im.result.warnings.empty()) << im.result.warnings.at(0);
    EXPECT_EQ(im.result.written, (std::vector<std::string>{tmp / "out.json", tmp / "out_1.ply"}));
    EXPECT_TRUE(contains(read_text(tmp / "out.json"), "\"_plyFile\": \"out_1.ply\""));
    EXPECT_EQ(d.cameras.at(0).image_name, "out.png");
}

TEST(ObjImport, PolygonsAndTrianglesMix) {
    TempDir tmp;
    write_text(tmp / "p.obj", "v 0 0 0\nv 2 0 0\nv 3 1 0\nv 1 2 0\nv -1 1 0\nf 1 2 3 4 5\nf 1 2 3\nf 3 4 5 1\n");
    const Imported im = import(tmp, "p.obj");
    EXPECT_EQ(triangle_count(im.scene), 3u + 1u + 2u);
    EXPECT_TRUE(any_contains(im.result.notes, "3 faces (2 polygons fan-split) -> 6 triangles"));
}

TEST(ObjImport, SmoothWhereNormalsOrSmoothingGroups) {
    TempDir tmp;
    write_text(tmp / "s.obj", R"(v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
vn 0 0 1
s off
f 1 2 3
f 1//1 3//1 4//1
s 1
f 1 3 4
s 2
f 1 2 4
s off
f 2 3 4
)");
    const Imported im = import(tmp, "s.obj");
    // flat (faces 1 and 5), normals, group 1, group 2: four meshes in order of first use.
    ASSERT_EQ(im.scene.meshes.size(), 4u);
    EXPECT_EQ(im.scene.meshes[0].shading, rt::ShadingMode::Flat);
    EXPECT_EQ(im.scene.meshes[0].indices.size(), 6u);
    for (size_t i = 1; i < 4; ++i) EXPECT_EQ(im.scene.meshes[i].shading, rt::ShadingMode::Smooth) << i;

    rt::ConvertOptions flat;
    flat.shading = rt::ObjShading::Flat;
    const Imported f = import(tmp, "s.obj", flat);
    ASSERT_EQ(f.scene.meshes.size(), 1u);
    EXPECT_EQ(f.scene.meshes[0].shading, rt::ShadingMode::Flat);
    rt::ConvertOptions smooth;
    smooth.shading = rt::ObjShading::Smooth;
    const Imported s = import(tmp, "s.obj", smooth);
    ASSERT_EQ(s.scene.meshes.size(), 1u);
    EXPECT_EQ(s.scene.meshes[0].shading, rt::ShadingMode::Smooth);
    EXPECT_EQ(s.scene.meshes[0].positions.size(), 4u) << "vertices are shared, so normals are smoothed across faces";
}

TEST(ObjImport, MaterialsFromMtl) {
    TempDir tmp;
    write_text(tmp / "m.mtl", R"(# four materials
newmtl red
Ka 0.1 0 0
Kd 0.8 0.1 0.1
Ks 0.3 0.3 0.3
Ns 50
illum 2

newmtl chrome
Ka 0 0 0
Kd 0.05 0.05 0.05
Ks 0.9 0.9 0.95
Ns 200
illum 3

newmtl polished
Kd 0 0 0
Ks 1 1 1
Ns 500

newmtl glass
Kd 0.9 0.9 0.9
Ks 0.5 0.5 0.5
Ni 1.33
d 0.2
Tf 0.5 1 1
illum 2

newmtl unused
Kd 1 1 1
)");
    write_text(tmp / "m.obj", R"(mtllib m.mtl
v 0 0 0
v 1 0 0
v 0 1 0
usemtl glass
f 1 2 3
usemtl red
f 1 2 3
usemtl chrome
f 1 2 3
usemtl polished
f 1 2 3
usemtl red
f 3 2 1
)");
    const Imported im = import(tmp, "m.obj");
    EXPECT_TRUE(im.result.warnings.empty()) << im.result.warnings.at(0);
    const std::vector<rt::MaterialDesc>& ms = im.scene.materials;
    ASSERT_EQ(ms.size(), 4u) << "only the materials in use, in order of first use";
    // glass: a dielectric, no diffuse term, Ni, Beer's law from Tf.
    EXPECT_EQ(ms[0].type, rt::MaterialType::Dielectric);
    EXPECT_EQ(ms[0].refraction_index, rt::Real(1.33));
    EXPECT_TRUE(same(ms[0].diffuse, {0, 0, 0}));
    // The file holds ln 2 to 1e-12; a float Real then rounds it, by at most half an ulp
    // (float's unit roundoff, epsilon / 2, times the value).
    const double real_rounding =
        std::is_same_v<rt::Real, float> ? double(std::numeric_limits<float>::epsilon()) / 2 * std::log(2.0) : 0;
    EXPECT_NEAR(double(ms[0].absorption_coefficient.x), std::log(2.0), 1e-12 + real_rounding);
    EXPECT_EQ(ms[0].absorption_coefficient.y, 0);
    // red: plain Blinn-Phong.
    EXPECT_EQ(ms[1].type, rt::MaterialType::Plain);
    EXPECT_TRUE(same(ms[1].ambient, {rt::Real(0.1), 0, 0}));
    EXPECT_TRUE(same(ms[1].diffuse, {rt::Real(0.8), rt::Real(0.1), rt::Real(0.1)}));
    EXPECT_TRUE(same(ms[1].specular, {rt::Real(0.3), rt::Real(0.3), rt::Real(0.3)}));
    EXPECT_EQ(ms[1].phong_exponent, 50);
    // chrome: illum 3 is a mirror reflecting Ks; polished: a mirror-like Ks over a black Kd.
    EXPECT_EQ(ms[2].type, rt::MaterialType::Mirror);
    EXPECT_TRUE(same(ms[2].mirror, {rt::Real(0.9), rt::Real(0.9), rt::Real(0.95)}));
    EXPECT_EQ(ms[3].type, rt::MaterialType::Mirror);
    EXPECT_TRUE(same(ms[3].mirror, {1, 1, 1}));
    // One mesh per material; both red faces in one.
    ASSERT_EQ(im.scene.meshes.size(), 4u);
    EXPECT_EQ(im.scene.meshes[1].material, 1u);
    EXPECT_EQ(im.scene.meshes[1].indices.size(), 6u);
}

TEST(ObjImport, MissingMtlGivesTheDefaultMaterialAndAWarning) {
    TempDir tmp;
    write_text(tmp / "a.obj", "mtllib nothere.mtl\nusemtl shiny\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const Imported im = import(tmp, "a.obj");
    ASSERT_EQ(im.scene.materials.size(), 1u);
    EXPECT_EQ(im.scene.materials[0].type, rt::MaterialType::Plain);
    EXPECT_TRUE(any_contains(im.result.warnings, "nothere.mtl not found: default material used"))
        << ::testing::PrintToString(im.result.warnings);
    for (const std::string& w : im.result.warnings) {
        EXPECT_EQ(w.rfind(tmp / "a.obj: ", 0), 0u) << w;
        EXPECT_EQ(w.find('\n'), std::string::npos) << w;
    }
}

TEST(ObjImport, UnknownMaterialNameIsAWarning) {
    TempDir tmp;
    write_text(tmp / "b.mtl", "newmtl known\nKd 1 0 0\n");
    write_text(tmp / "b.obj",
               "mtllib b.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl known\nf 1 2 3\nusemtl other\nf 3 2 1\n");
    const Imported im = import(tmp, "b.obj");
    EXPECT_EQ(im.scene.materials.size(), 2u);
    EXPECT_TRUE(any_contains(im.result.warnings, "'other'")) << ::testing::PrintToString(im.result.warnings);
}

TEST(ObjImport, CameraFramesTheModelAndTheLightLightsIt) {
    TempDir tmp;
    // A long, off-centre box: every corner must land inside the image.
    std::string obj = kCube;
    std::string moved;
    std::istringstream lines(obj);
    std::string line;
    while (std::getline(lines, line)) {
        if (line.rfind("v ", 0) == 0) {
            double x, y, z;
            std::istringstream(line.substr(2)) >> x >> y >> z;
            std::ostringstream v;
            v << "v " << (100 + 40 * x) << " " << (-7 + 3 * y) << " " << (12 + 5 * z);
            line = v.str();
        }
        moved += line + "\n";
    }
    write_text(tmp / "box.obj", moved);
    rt::ConvertOptions o;
    o.width = 64;
    o.height = 48;
    o.image_name = "box.ppm";
    const Imported im = import(tmp, "box.obj", o);
    const rt::CameraDesc& c = im.scene.cameras.at(0);
    EXPECT_EQ(c.image_name, "box.ppm");
    EXPECT_EQ(c.width, 64);
    const rt::Vec3 w = -normalize(c.gaze), u = normalize(cross(c.up, w)), v = cross(w, u);
    for (const rt::Vec3& p : im.scene.meshes.at(0).positions) {
        const rt::Vec3 d = p - c.position;
        const rt::Real z = -dot(d, w);
        ASSERT_GT(z, 0);
        const rt::Real x = dot(d, u) * c.near_distance / z, y = dot(d, v) * c.near_distance / z;
        EXPECT_TRUE(x > c.left && x < c.right && y > c.bottom && y < c.top) << str(p);
    }
    ASSERT_EQ(im.scene.point_lights.size(), 1u);
    EXPECT_GT(im.scene.ambient_light.x, 0);
    // It renders something: lit pixels and background.
    const rt::Scene s = rt::build_scene(im.scene);
    const rt::Image img = rt::render(s, 0, rt::RenderOptions{});
    int lit = 0;
    for (size_t p = 0; p < img.rgb.size(); p += 3) lit += img.rgb[p] > 60;
    EXPECT_GT(lit, 64 * 48 / 20);
    EXPECT_LT(lit, 64 * 48);
}

TEST(ObjImport, ConvertedFileRendersWithTheRenderer) {
    TempDir tmp;
    write_text(tmp / "cube.obj", kCube);
    RunResult r = run_program(rtconvert_path(), {"--size", "32x24", "cube.obj", "cube.xml"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.err, "wrote cube.xml")) << r.err;
    r = run_raytracer({"-q", "cube.xml"}, tmp.path());
    ASSERT_EQ(r.exit_code, 0) << r.err;
    rt::Image img;
    ASSERT_TRUE(load_png(tmp / "cube.png", img));
    EXPECT_EQ(img.width, 32);
}

TEST(ObjImport, BadInputIsOneLineError) {
    TempDir tmp;
    struct Case {
        std::string obj;
        std::string error;  // after "<tmp>/x.obj: "
    };
    const std::string v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    for (const Case& c : std::vector<Case>{
             {v3 + "f 1 2 3\nf 1 2 4\n", "line 5: vertex index out of range in 'f 1 2 4' (the file has 3 vertices)"},
             {v3 + "f 1 2 3\n\nf -4 1 2\n",
              "line 6: vertex index out of range in 'f -4 1 2' (the file has 3 vertices)"},
             {v3 + "f 1 2 3 9\n", "line 4: vertex index out of range in 'f 1 2 3 9' (the file has 3 vertices)"},
             {v3 + "vn 0 0 1\nf 1//1 2//2 3//1\n",
              "line 5: normal index out of range in 'f 1//1 2//2 3//1' (the file has 1 normals)"},
             {v3 + "f 0 1 2\n", "line 4: bad face: a vertex index is 0 or not a number"},
             {v3, "no faces"},
             {"", "no faces"},
         }) {
        SCOPED_TRACE(c.obj);
        write_text(tmp / "x.obj", c.obj);
        EXPECT_EQ(import_error(tmp, "x.obj"), tmp / "x.obj: " + c.error);
    }
    EXPECT_EQ(import_error(tmp, "missing.obj"), tmp / "missing.obj: cannot open: No such file or directory");
    // An MTL library that exists but cannot be read is an error, not a warning.
    fs::create_directories(tmp / "dir.mtl");
    write_text(tmp / "y.obj", "mtllib dir.mtl\n" + v3 + "f 1 2 3\n");
    EXPECT_EQ(import_error(tmp, "y.obj"), tmp / "dir.mtl: cannot read: not a regular file");
    EXPECT_FALSE(file_exists(tmp / "out.json"));
    EXPECT_FALSE(file_exists(tmp / "out_1.ply"));
}

// ---- Export to OBJ + MTL ------------------------------------------------------------

TEST(ObjExport, SceneToObjAndBack) {
    TempDir tmp;
    write_text(tmp / "s.json", R"({"Scene": {
        "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -1 1",
                               "NearDistance": "1", "ImageResolution": "8 8", "ImageName": "a.png"}},
        "Lights": {"PointLight": {"Position": "0 5 5", "Intensity": "100 100 100"}},
        "Materials": {"Material": [
            {"_id": "1", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.5 0.6 0.7",
             "SpecularReflectance": "0.2 0.2 0.2", "PhongExponent": "20"},
            {"_id": "2", "_type": "mirror", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "1 1 1", "MirrorReflectance": "0.8 0.8 0.8"},
            {"_id": "3", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "1 1 1", "RefractionIndex": "1.5", "AbsorptionCoefficient": "0.5 0 0"},
            {"_id": "4", "_type": "conductor", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "1 1 1", "MirrorReflectance": "1 0.86 0.57", "RefractionIndex": "0.37",
             "AbsorptionIndex": "2.82"}]},
        "VertexData": "-1 -1 0 1 -1 0 1 1 0 -1 1 0 3 3 3 0 -2 0",
        "Objects": {
            "Mesh": {"_id": "1", "_shadingMode": "smooth", "Material": "1", "Faces": "1 2 3 1 3 4"},
            "Triangle": {"_id": "1", "Material": "4", "Indices": "1 2 3"},
            "Sphere": {"_id": "1", "Material": "3", "Center": "5", "Radius": "0.5"},
            "Plane": {"_id": "1", "Material": "2", "Point": "6", "Normal": "0 2 0"}}}})");
    rt::ConvertOptions o;
    o.sphere_segments = 12;  // 6 rings: 2 * 12 * 5 = 120 triangles
    const rt::ConvertResult r = rt::convert_file(tmp / "s.json", tmp / "s.obj", o);
    EXPECT_EQ(r.written, (std::vector<std::string>{tmp / "s.obj", tmp / "s.mtl"}));
    const std::string obj = read_text(tmp / "s.obj");
    EXPECT_TRUE(contains(obj, "mtllib s.mtl\n"));
    EXPECT_TRUE(contains(obj, "# camera 1: position 0 0 5"));
    const std::string mtl = read_text(tmp / "s.mtl");
    EXPECT_TRUE(contains(mtl, "newmtl material_1\n"));
    EXPECT_TRUE(contains(mtl, "Kd 0.5 0.6 0.7\n"));

    // Read back with our importer.
    const rt::ConvertResult back = rt::convert_file(tmp / "s.obj", tmp / "back.json");
    EXPECT_TRUE(back.warnings.empty()) << back.warnings.at(0);
    const rt::SceneDesc d = rt::load_scene(tmp / "back.json");
    EXPECT_EQ(triangle_count(d), 2u + 1u + 120u + 2u);
    ASSERT_EQ(d.materials.size(), 4u);
    // Materials in order of first use: mesh (1), triangle (4), sphere (3), plane (2).
    EXPECT_EQ(d.materials[0].type, rt::MaterialType::Plain);
    EXPECT_TRUE(same(d.materials[0].diffuse, {rt::Real(0.5), rt::Real(0.6), rt::Real(0.7)}));
    EXPECT_EQ(d.materials[0].phong_exponent, 20);
    EXPECT_EQ(d.materials[1].type, rt::MaterialType::Mirror);  // a conductor comes back as a mirror of its colour
    EXPECT_TRUE(same(d.materials[1].mirror, {1, rt::Real(0.86), rt::Real(0.57)}));
    EXPECT_EQ(d.materials[2].type, rt::MaterialType::Dielectric);
    EXPECT_EQ(d.materials[2].refraction_index, rt::Real(1.5));
    EXPECT_NEAR(double(d.materials[2].absorption_coefficient.x), 0.5, 1e-6);
    EXPECT_EQ(d.materials[3].type, rt::MaterialType::Mirror);
    EXPECT_TRUE(same(d.materials[3].mirror, {rt::Real(0.8), rt::Real(0.8), rt::Real(0.8)}));

    ASSERT_EQ(d.meshes.size(), 4u);
    // The mesh, smooth, with its own vertices.
    EXPECT_EQ(d.meshes[0].shading, rt::ShadingMode::Smooth);
    EXPECT_EQ(d.meshes[0].positions.size(), 4u);
    EXPECT_TRUE(same(tri(d.meshes[0], 0)[0], {-1, -1, 0}));
    EXPECT_EQ(d.meshes[1].shading, rt::ShadingMode::Flat);
    // The sphere: on the surface, every face outwards.
    const rt::MeshDesc& sphere = d.meshes[2];
    EXPECT_EQ(sphere.shading, rt::ShadingMode::Smooth);
    EXPECT_EQ(sphere.positions.size(), 2u + 12u * 5u);
    for (const rt::Vec3& p : sphere.positions) EXPECT_NEAR(double(length(p - rt::Vec3{3, 3, 3})), 0.5, 1e-6);
    for (size_t t = 0; t < sphere.indices.size() / 3; ++t) {
        const auto p = tri(sphere, t);
        const rt::Vec3 n = cross(p[1] - p[0], p[2] - p[0]);
        EXPECT_GT(dot(n, (p[0] + p[1] + p[2]) / rt::Real(3) - rt::Vec3{3, 3, 3}), 0) << "triangle " << t;
    }
    // The plane: a large quad through the point, facing the normal.
    const rt::MeshDesc& plane = d.meshes[3];
    ASSERT_EQ(plane.indices.size(), 6u);
    for (size_t t = 0; t < 2; ++t) {
        const auto p = tri(plane, t);
        const rt::Vec3 n = normalize(cross(p[1] - p[0], p[2] - p[0]));
        EXPECT_NEAR(double(n.y), 1.0, 1e-6);
        for (const rt::Vec3& q : p) EXPECT_NEAR(double(q.y), -2.0, 1e-6);
    }
    rt::Real span = 0;
    for (const rt::Vec3& q : plane.positions) span = std::max(span, std::fabs(q.x));
    EXPECT_GT(span, 20);
}

TEST(ObjExport, OfficialXmlSceneExports) {
    const std::string root = shared_dir();
    if (root.empty()) GTEST_SKIP() << "../shared not found (set RT_SHARED_DIR)";
    TempDir tmp;
    const std::string path = root + "/scenes/xml2021/cornellbox.xml";
    rt::convert_file(path, tmp / "cb.obj");
    const rt::SceneDesc src = rt::load_scene(path);
    const rt::SceneDesc back = (rt::convert_file(tmp / "cb.obj", tmp / "cb.json"), rt::load_scene(tmp / "cb.json"));
    EXPECT_EQ(triangle_count(back), triangle_count(src) + src.all<rt::Sphere>().size() * 2 * 48 * 23);
}

// ---- The command line ------------------------------------------------------------------

TEST(ConvertCli, UsageAndHelp) {
    RunResult r = run_program(rtconvert_path(), {"--help"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_TRUE(contains(r.out, "usage: rtconvert"));
    r = run_program(rtconvert_path(), {"--version"});
    EXPECT_EQ(r.exit_code, 0);
    for (const std::vector<std::string>& args :
         std::vector<std::vector<std::string>>{{},
                                               {"a.xml"},
                                               {"a.xml", "b.json", "c.json"},
                                               {"--bogus", "a.xml", "b.json"},
                                               {"--shading", "wavy", "a.obj", "b.json"},
                                               {"--size", "10", "a.obj", "b.json"},
                                               {"--size"}}) {
        SCOPED_TRACE(::testing::PrintToString(args));
        r = run_program(rtconvert_path(), args);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_TRUE(contains(r.err, "usage: rtconvert")) << r.err;
    }
}

TEST(ConvertCli, BadInputIsOneLineAndWritesNothing) {
    TempDir tmp;
    write_text(tmp / "broken.xml", "<Scene>\n  <Cameras>\n</Scene>\n");
    write_text(tmp / "broken.json", "{\"Scene\": [1, }");
    write_text(tmp / "huge.json", "{\"Scene\": 1e999}");
    write_text(tmp / "ok.json", "{\"Scene\": {}}");
    write_text(tmp / "bad.obj", "v 0 0 0\nf 1 2 3\n");
    struct Case {
        std::vector<std::string> args;
        std::string error;
    };
    for (const Case& c : std::vector<Case>{
             {{"broken.xml", "out.json"}, "broken.xml: line 3, column 3: start-end tags mismatch"},
             {{"broken.json", "out.xml"}, "broken.json: parse error at line 1, column 15: "},
             {{"huge.json", "out.xml"},
              "huge.json: line 1, column 11: number overflow parsing '1e999' (not a finite number)"},
             {{"bad.obj", "out.json"},
              "bad.obj: line 2: vertex index out of range in 'f 1 2 3' (the file has 1 vertices)"},
             {{"missing.xml", "out.json"}, "missing.xml: cannot open: No such file or directory"},
             {{"ok.json", "out.txt"}, "out.txt: unknown output format (the name must end in .json, .xml or .obj)"},
             {{"ok.json", "ok.json"}, "ok.json: is the input file; choose another output name"},
             {{"ok.json", "no/such/dir/out.xml"}, "no/such/dir/out.xml: cannot write: No such file or directory"},
         }) {
        SCOPED_TRACE(c.error);
        const RunResult r = run_program(rtconvert_path(), c.args, tmp.path());
        EXPECT_EQ(r.exit_code, 1);
        const std::vector<std::string> lines = split_lines(r.err);
        ASSERT_EQ(lines.size(), 1u) << r.err;
        EXPECT_EQ(lines[0].substr(0, c.error.size() + 7), "error: " + c.error);
        EXPECT_EQ(list_files(tmp.path()),
                  (std::vector<std::string>{"bad.obj", "broken.json", "broken.xml", "huge.json", "ok.json"}));
    }
}

// One function formats JSON parse errors for both programs (rt/loader/scene_tree.h): a number
// beyond the double range gets the same one-line message, with its line and column,
// from the renderer and from the converter.
TEST(ConvertCli, NumberOverflowIsTheSameMessageInBothPrograms) {
    TempDir tmp;
    write_text(tmp / "huge.json", "{\"Scene\": {\n  \"ShadowRayEpsilon\": 1e999}}\n");
    const std::string expected =
        "error: huge.json: line 2, column 23: number overflow parsing '1e999' (not a finite number)";
    const RunResult render = run_raytracer({"huge.json"}, tmp.path());
    const RunResult convert = run_program(rtconvert_path(), {"huge.json", "out.xml"}, tmp.path());
    for (const RunResult* r : {&render, &convert}) {
        EXPECT_EQ(r->exit_code, 1);
        EXPECT_EQ(split_lines(r->err), std::vector<std::string>{expected}) << r->err;
    }
    EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"huge.json"});
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
