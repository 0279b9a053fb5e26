// The converters (rt/convert/convert.h), OBJ: import of OBJ (+MTL) files written here
// (quads, negative indices, no normals, smoothing groups, with, without and with broken
// MTL files; the camera and light it adds; bad input as one-line errors), and scene ->
// OBJ + MTL export, read back with the importer.
#include <gtest/gtest.h>

// A build without pugixml or tinyobjloader (see mk/convert.mk) has none of this to test.
#if !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
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
using namespace convert_test;

namespace {

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
    SKIP_UNLESS_SHARED("the official cornellbox.xml");
    const std::string root = shared_dir();
    TempDir tmp;
    const std::string path = root + "/scenes/xml2021/cornellbox.xml";
    rt::convert_file(path, tmp / "cb.obj");
    const rt::SceneDesc src = rt::load_scene(path);
    const rt::SceneDesc back = (rt::convert_file(tmp / "cb.obj", tmp / "cb.json"), rt::load_scene(tmp / "cb.json"));
    EXPECT_EQ(triangle_count(back), triangle_count(src) + src.all<rt::SphereDesc>().size() * 2 * 128 * 63);
}

#endif  // !defined(RT_NO_XML) && !defined(RT_NO_OBJ)
