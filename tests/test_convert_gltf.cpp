// The converters (rt/convert/convert.h), glTF 2.0: the material table with hand-computed
// values; import of glTF files written here (instances, the node hierarchy as
// transformations, cameras, point lights, defaults, --bake-transforms, skipped primitives,
// the export's extras used only while they agree); export read back; bad input as
// one-line errors naming the element, with nothing written.
#include <gtest/gtest.h>

// A build without tinygltf, pugixml or tinyobjloader (see mk/convert.mk) has none of this.
#if !defined(RT_NO_GLTF) && !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "convert_test_support.h"
#include "gltf_test_support.h"
#include "rt/convert/convert.h"
#include "rt/convert/gltf_materials.h"
#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace convert_test;

// ---- The material table ---------------------------------------------------------------

TEST(GltfMaterials, RoughnessAndPhongExponentByHand) {
    // n = 2 / r^4 - 2: r = 0.5 is n = 30; r = 1 is n = 0, kept at 1.
    EXPECT_DOUBLE_EQ(rt::exponent_of_roughness(0.5), 30);
    EXPECT_DOUBLE_EQ(rt::roughness_of_exponent(30), 0.5);
    EXPECT_DOUBLE_EQ(rt::exponent_of_roughness(1), 1);
    EXPECT_DOUBLE_EQ(rt::exponent_of_roughness(0), 1e6);
    EXPECT_DOUBLE_EQ(rt::roughness_of_exponent(2), std::pow(0.5, 0.25));
}

TEST(GltfMaterials, ExportTableByHand) {
    rt::MaterialDesc plain;
    plain.type = rt::MaterialType::Plain;
    plain.diffuse = {0.2, 0.4, 1.5};
    plain.phong_exponent = 30;
    const rt::PbrMaterial p = rt::pbr_of(plain);
    EXPECT_EQ(p.metallic, 0);
    EXPECT_DOUBLE_EQ(p.roughness, 0.5);
    EXPECT_DOUBLE_EQ(p.base[0], double(rt::Real(0.2)));  // as the build holds it
    EXPECT_DOUBLE_EQ(p.base[2], 1);                      // clamped to glTF's range

    // A conductor: the normal-incidence reflectance kept. n = 2, k = 0: F0 = 1/9; the
    // import's metal (n 1, k 10) has F0 = 100/104.
    rt::MaterialDesc metal;
    metal.type = rt::MaterialType::Conductor;
    metal.mirror = {0.9, 0.9, 0.9};
    metal.refraction_index = 2;
    metal.absorption_index = 0;
    EXPECT_NEAR(rt::pbr_of(metal).base[0], double(rt::Real(0.9)) * (1.0 / 9) / (100.0 / 104), 1e-15);
    EXPECT_EQ(rt::pbr_of(metal).metallic, 1);

    rt::MaterialDesc glass;
    glass.type = rt::MaterialType::Dielectric;
    glass.refraction_index = 1.5;
    glass.absorption_coefficient = {0.1, 0, 2};
    const rt::PbrMaterial g = rt::pbr_of(glass);
    EXPECT_EQ(g.transmission, 1);
    EXPECT_EQ(g.ior, 1.5);
    EXPECT_EQ(g.attenuation_distance, 1);
    EXPECT_DOUBLE_EQ(g.attenuation[0], std::exp(-double(rt::Real(0.1))));
    EXPECT_DOUBLE_EQ(g.attenuation[1], 1);
    EXPECT_DOUBLE_EQ(g.attenuation[2], std::exp(-2.0));
}

rt::PbrMaterial pbr(std::array<double, 3> base, double metallic, double roughness) {
    rt::PbrMaterial p;
    std::copy(base.begin(), base.end(), p.base);
    p.metallic = metallic;
    p.roughness = roughness;
    return p;
}

TEST(GltfMaterials, ImportTableByHand) {
    const rt::MaterialDesc m = rt::material_of(pbr({1, 0.8, 0.3}, 1, 0.5));  // gold
    EXPECT_EQ(m.type, rt::MaterialType::Conductor);
    EXPECT_TRUE(same(m.mirror, {1, 0.8, 0.3}));
    EXPECT_EQ(m.refraction_index, 1);
    EXPECT_EQ(m.absorption_index, 10);
    EXPECT_TRUE(same(m.diffuse, {0, 0, 0}));
    EXPECT_TRUE(same(m.specular, {0.5, 0.4, 0.15}));
    EXPECT_EQ(m.phong_exponent, 30);

    rt::PbrMaterial glass;
    glass.metallic = 0;
    glass.transmission = 1;
    glass.ior = 1.33;
    glass.attenuation_distance = 2;
    glass.attenuation[0] = std::exp(-1.0);
    const rt::MaterialDesc g = rt::material_of(glass);
    EXPECT_EQ(g.type, rt::MaterialType::Dielectric);
    EXPECT_EQ(g.refraction_index, rt::Real(1.33));
    EXPECT_DOUBLE_EQ(g.absorption_coefficient.x, 0.5);  // -ln(e^-1) / 2
    EXPECT_EQ(g.absorption_coefficient.y, 0);
    EXPECT_TRUE(same(g.diffuse, {0, 0, 0}));

    const rt::MaterialDesc r = rt::material_of(pbr({0.8, 0.1, 0.1}, 0, 1));  // red, fully rough
    EXPECT_EQ(r.type, rt::MaterialType::Plain);
    EXPECT_TRUE(same(r.diffuse, {0.8, 0.1, 0.1}));
    EXPECT_TRUE(same(r.ambient, r.diffuse));
    EXPECT_TRUE(same(r.specular, {0, 0, 0}));  // fully rough: no highlight
}

TEST(GltfMaterials, ExtrasRoundTripExactly) {
    rt::MaterialDesc m;
    m.type = rt::MaterialType::Dielectric;
    m.ambient = {0.1, 0.2, 0.3};
    m.specular = {1.0 / 3, 0.5, 0.7};
    m.phong_exponent = 123.456;
    m.refraction_index = 1.55;
    m.absorption_coefficient = {0.01, 0.02, 0.03};
    rt::MaterialDesc back;
    ASSERT_TRUE(rt::material_from_extras(rt::material_extras(m), back));
    EXPECT_EQ(back.type, m.type);
    EXPECT_TRUE(same(back.specular, m.specular));
    EXPECT_EQ(back.phong_exponent, m.phong_exponent);
    EXPECT_TRUE(same(back.absorption_coefficient, m.absorption_coefficient));
    json broken = rt::material_extras(m);
    broken["type"] = "velvet";
    EXPECT_FALSE(rt::material_from_extras(broken, back));
    broken = rt::material_extras(m);
    broken["ambient"] = {1, -1, 0};
    EXPECT_FALSE(rt::material_from_extras(broken, back));
}

// ---- Import ---------------------------------------------------------------------------

TEST(GltfImport, MeshUsedTwiceIsOneMeshAndAnInstanceUnderTheHierarchy) {
    TempDir tmp;
    GltfFile f;
    const int mesh = f.mesh(kTriangle, {0, 1, 2});
    f.node({{"mesh", mesh}, {"translation", {1, 2, 3}}});
    const int child = f.node({{"mesh", mesh}, {"scale", {2, 2, 2}}}, false);
    f.node({{"children", {child}}, {"rotation", {0, 0, std::sqrt(0.5), std::sqrt(0.5)}}});  // 90 degrees about z
    const Imported im = import(tmp, f.write(tmp));
    ASSERT_EQ(im.scene.meshes.size(), 1u);
    ASSERT_EQ(im.scene.all<rt::InstanceDesc>().size(), 2u);  // the mesh drawn as itself, and the instance
    EXPECT_EQ(im.tree["Scene"]["Objects"]["MeshInstance"][0]["_baseMeshId"], "1");
    EXPECT_EQ(im.tree["Scene"]["Objects"]["MeshInstance"][0]["_resetTransform"], "true");
    // The child's list is its own matrix, then its parent's: "c2 c3".
    EXPECT_EQ(im.tree["Scene"]["Objects"]["MeshInstance"][0]["Transformations"], "c2 c3");
    const rt::Affine& a = im.scene.meshes[0].transform;
    EXPECT_EQ(a.m[0][3], 1);
    EXPECT_EQ(a.m[1][3], 2);
    EXPECT_EQ(a.m[2][3], 3);
    // Rz(90) * S(2): x -> 2y, y -> -2x.
    const rt::Affine& b = im.scene.all<rt::InstanceDesc>()[1].transform;
    const rt::Vec3 p = b.point({1, 0, 0}), q = b.point({0, 1, 0});
    EXPECT_NEAR(p.x, 0, 1e-15);
    EXPECT_NEAR(p.y, 2, 1e-15);
    EXPECT_NEAR(q.x, -2, 1e-15);
    EXPECT_NEAR(q.y, 0, 1e-15);
}

TEST(GltfImport, BakeTransformsMovesVerticesAndKeepsMirroredFacesOutward) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}, {"scale", {-1, 1, 1}}, {"translation", {0, 0, 5}}});
    rt::ConvertOptions o;
    o.bake_transforms = true;
    const Imported im = import(tmp, f.write(tmp), o);
    ASSERT_EQ(im.scene.meshes.size(), 1u);
    const rt::MeshDesc& m = im.scene.meshes[0];
    EXPECT_FALSE(m.instanced);
    EXPECT_FALSE(im.tree["Scene"].contains("Transformations"));
    EXPECT_TRUE(same(m.positions[1], {-1, 0, 5}));
    // The mirrored triangle keeps facing +z: its winding is reversed.
    const rt::Vec3 n = cross(m.positions[m.indices[1]] - m.positions[m.indices[0]],
                             m.positions[m.indices[2]] - m.positions[m.indices[0]]);
    EXPECT_GT(n.z, 0);
}

TEST(GltfImport, CameraLightAndTheirScale) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    f.j["cameras"] = {{{"type", "perspective"},
                       {"perspective", {{"yfov", 2 * std::atan(0.5)}, {"aspectRatio", 2.0}, {"znear", 0.1}}}}};
    // Turned 90 degrees about y: looks down -x.
    f.node({{"camera", 0}, {"translation", {4, 5, 6}}, {"rotation", {0, std::sqrt(0.5), 0, std::sqrt(0.5)}}});
    f.j["extensionsUsed"] = {"KHR_lights_punctual"};
    f.j["extensions"] = {{"KHR_lights_punctual",
                          {{"lights",
                            {{{"type", "point"}, {"color", {1, 0.5, 0}}, {"intensity", 100}},
                             {{"type", "spot"}, {"spot", json::object()}}}}}}};
    f.node({{"translation", {7, 8, 9}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    f.node({{"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    rt::ConvertOptions o;
    o.light_scale = 2;
    const Imported im = import(tmp, f.write(tmp), o);
    ASSERT_EQ(im.scene.cameras.size(), 1u);
    const rt::CameraDesc& c = im.scene.cameras[0];
    EXPECT_EQ(c.width, 1200);  // 600 high at the aspect ratio
    EXPECT_EQ(c.height, 600);
    EXPECT_TRUE(same(c.position, {4, 5, 6}));
    EXPECT_NEAR(c.gaze.x, -1, 1e-15);
    EXPECT_NEAR(c.gaze.z, 0, 1e-15);
    EXPECT_NEAR(c.up.y, 1, 1e-15);
    EXPECT_NEAR(c.top, 0.5, 1e-15);
    EXPECT_NEAR(c.right, 1, 1e-15);
    EXPECT_EQ(c.image_name, "out.png");
    ASSERT_EQ(im.scene.point_lights.size(), 1u);
    EXPECT_TRUE(same(im.scene.point_lights[0].intensity, {200, 100, 0}));
    EXPECT_TRUE(same(im.scene.point_lights[0].position, {7, 8, 9}));
    EXPECT_TRUE(any_contains(im.result.warnings, "/extensions/KHR_lights_punctual/lights/1: a spot light"));
}

TEST(GltfImport, WithoutCameraOrLightsTheModelIsFramedAndLit) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    const Imported im = import(tmp, f.write(tmp));
    ASSERT_EQ(im.scene.cameras.size(), 1u);
    ASSERT_EQ(im.scene.point_lights.size(), 1u);
    EXPECT_TRUE(same(im.scene.ambient_light, {25, 25, 25}));
    EXPECT_EQ(im.tree["Scene"]["Materials"]["Material"][0]["DiffuseReflectance"], "0.7 0.7 0.7");  // default grey
    // The camera looks at the triangle's bounding box centre.
    const rt::Vec3 to_centre = rt::Vec3{0.5, 0.5, 0} - im.scene.cameras[0].position;
    EXPECT_NEAR(dot(normalize(to_centre), normalize(im.scene.cameras[0].gaze)), 1, 1e-12);
}

TEST(GltfImport, InMemoryTheSameTreeButTheMeshNames) {
    TempDir tmp;
    GltfFile f;
    const int mesh = f.mesh(kTriangle, {0, 1, 2});
    f.node({{"mesh", mesh}, {"translation", {1, 2, 3}}});
    f.node({{"mesh", mesh}});
    const std::string path = f.write(tmp);
    std::ifstream in(path);
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    json text = json::parse(rt::gltf_to_json_text(bytes, path));
    const Imported im = import(tmp, path);
    EXPECT_EQ(text["Scene"]["Objects"]["Mesh"][0]["Faces"]["_plyFile"], "mesh_1.ply");
    text["Scene"]["Objects"]["Mesh"][0]["Faces"]["_plyFile"] = "out_1.ply";
    text["Scene"]["Cameras"]["Camera"][0]["ImageName"] = "out.png";
    EXPECT_EQ(text, im.tree);
}

TEST(GltfImport, NonTrianglePrimitivesAreSkippedWithAWarning) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 1, 2}, {{"mode", 1}})}});
    const Imported im = import(tmp, f.write(tmp));
    EXPECT_EQ(im.scene.meshes.size(), 1u);
    EXPECT_TRUE(any_contains(im.result.warnings, "/meshes/1/primitives/0: mode 1"));
}

// A tent of two triangles meeting at the ridge x = 0 (vertices 0..3), as a writer splits it:
// every triangle its own three vertices, with `normals` per vertex.
GltfFile tent(const std::vector<float>& normals) {
    GltfFile f;
    const std::vector<float> p = {-1, 0, 1, 0, 1, 1, 0, 1, -1, /**/ 0, 1, 1, 1, 0, 1, 0, 1, -1};
    json extra = {{"attributes", {{"POSITION", f.positions(p)}, {"NORMAL", f.positions(normals)}}}};
    f.node({{"mesh", f.mesh(p, {0, 1, 2, 3, 4, 5}, extra)}});
    return f;
}

TEST(GltfImport, SplitVerticesWithOneNormalAreJoinedCreasesAndFlatFacesAreNot) {
    const float s = float(std::sqrt(0.5)), up_a[3] = {-s, s, 0}, up_b[3] = {s, s, 0};
    auto normals = [](std::vector<std::array<float, 3>> n) {
        std::vector<float> out;
        for (const auto& v : n) out.insert(out.end(), v.begin(), v.end());
        return out;
    };
    {  // smooth: the ridge vertices carry the same normal (up), split only by the writer
        TempDir tmp;
        const Imported im = import(
            tmp,
            tent(normals({{up_a[0], up_a[1], 0}, {0, 1, 0}, {0, 1, 0}, {0, 1, 0}, {up_b[0], up_b[1], 0}, {0, 1, 0}}))
                .write(tmp));
        ASSERT_EQ(im.scene.meshes.size(), 1u);
        EXPECT_EQ(im.scene.meshes[0].shading, rt::ShadingMode::Smooth);
        EXPECT_EQ(im.scene.meshes[0].positions.size(), 4u);  // the ridge's two vertices joined
    }
    {  // a crease: each side's ridge vertices carry its own face's normal, but not all corners do
        TempDir tmp;
        const Imported im = import(tmp, tent(normals({{up_a[0], up_a[1], 0},
                                                      {up_a[0], up_a[1], 0},
                                                      {0, 1, 0},
                                                      {up_b[0], up_b[1], 0},
                                                      {up_b[0], up_b[1], 0},
                                                      {0, 1, 0}}))
                                            .write(tmp));
        EXPECT_EQ(im.scene.meshes[0].shading, rt::ShadingMode::Smooth);
        EXPECT_EQ(im.scene.meshes[0].positions.size(), 5u);  // only the third ridge vertex joined
    }
    {  // flat: every corner carries its triangle's own normal
        TempDir tmp;
        const Imported im = import(tmp, tent(normals({{up_a[0], up_a[1], 0},
                                                      {up_a[0], up_a[1], 0},
                                                      {up_a[0], up_a[1], 0},
                                                      {up_b[0], up_b[1], 0},
                                                      {up_b[0], up_b[1], 0},
                                                      {up_b[0], up_b[1], 0}}))
                                            .write(tmp));
        EXPECT_EQ(im.scene.meshes[0].shading, rt::ShadingMode::Flat);
        EXPECT_EQ(im.scene.meshes[0].positions.size(), 6u);
    }
}

TEST(GltfImport, BadInputNamesTheElementAndWritesNothing) {
    TempDir tmp;
    auto expect = [&](GltfFile f, const std::string& part, const std::string& name) {
        const std::string in = f.write(tmp, name);
        const std::string e = error_of(in, tmp / "bad.json");
        EXPECT_TRUE(contains(e, part)) << e;
        EXPECT_EQ(e.find('\n'), std::string::npos) << e;
        EXPECT_TRUE(contains(e, name)) << e;
        EXPECT_FALSE(fs::exists(tmp / "bad.json"));
        EXPECT_FALSE(fs::exists(tmp / "bad_1.ply"));
    };
    GltfFile base;
    base.node({{"mesh", base.mesh(kTriangle, {0, 1, 2})}});

    GltfFile out_of_range;
    out_of_range.node({{"mesh", out_of_range.mesh(kTriangle, {0, 1, 2})}});
    out_of_range.node({{"mesh", out_of_range.mesh(kTriangle, {0, 1, 3})}});
    expect(out_of_range, "/meshes/1/primitives/0: index 3 (element 2) is out of range: POSITION has 3 vertices",
           "range.gltf");

    GltfFile required = base;
    required.j["extensionsRequired"] = {"KHR_texture_basisu"};
    expect(required, "/extensionsRequired/0: the file requires extension KHR_texture_basisu", "req.gltf");

    GltfFile short_view = base;
    short_view.j["accessors"][0]["count"] = 4;
    expect(short_view, "/accessors/0: runs past the end of its bufferView", "view.gltf");

    GltfFile missing = base;
    missing.write(tmp, "missing.gltf");
    missing.j["buffers"][0]["uri"] = "gone.bin";
    std::ofstream(tmp / "missing.gltf") << missing.j.dump();
    const std::string e = error_of(tmp / "missing.gltf", tmp / "bad.json");
    EXPECT_TRUE(contains(e, "/buffers/0: its file gone.bin is missing")) << e;

    // A .glb cut short.
    rt::SceneDesc scene;
    const std::string glb = tmp / "whole.glb";
    base.write(tmp, "whole.gltf");
    rt::convert_file(tmp / "whole.gltf", tmp / "whole.json");
    rt::convert_file(tmp / "whole.json", glb);
    std::ifstream in(glb, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::ofstream(tmp / "cut.glb", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    const std::string cut = error_of(tmp / "cut.glb", tmp / "bad.json");
    EXPECT_TRUE(contains(cut, "cut.glb: truncated: its GLB header says " + std::to_string(bytes.size()))) << cut;
    EXPECT_FALSE(fs::exists(tmp / "bad.json"));
}

// ---- Export, and back -----------------------------------------------------------------

const char* kSmallScene = R"({"Scene": {
  "BackgroundColor": "1 2 3", "ShadowRayEpsilon": "0.0007", "MaxRecursionDepth": "4",
  "Cameras": {"Camera": {"_id": "1", "Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
     "NearPlane": "-0.3 0.3 -0.2 0.2", "NearDistance": "1", "ImageResolution": "30 20", "ImageName": "small.png"}},
  "Lights": {"AmbientLight": "10 20 30", "PointLight": {"_id": "1", "Position": "1 2 3", "Intensity": "300 200 100"}},
  "Materials": {"Material": [
     {"_id": "1", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.3 0.6 0.9",
      "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "17"},
     {"_id": "2", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
      "SpecularReflectance": "1 1 1", "PhongExponent": "50", "RefractionIndex": "1.45",
      "AbsorptionCoefficient": "0.2 0.1 0"}]},
  "Transformations": {"Translation": {"_id": "1", "_data": "0.1 0.2 0.3"}},
  "VertexData": {"_data": "0 0 0  1 0 0  0 1 0  0.3 0.1 0.7", "_type": "xyz"},
  "Objects": {
    "Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3"}, "Transformations": "t1"},
    "MeshInstance": {"_id": "2", "_baseMeshId": "1", "Material": "2", "Transformations": "t1"},
    "Sphere": {"_id": "1", "Material": "2", "Center": "4", "Radius": "0.25"},
    "Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 1 0"}}}})";

TEST(GltfExport, BackToTheSameSceneThroughExtras) {
    TempDir tmp;
    std::ofstream(tmp / "small.json") << kSmallScene;
    for (const char* name : {"small.gltf", "small.glb"}) {
        const rt::ConvertResult r = rt::convert_file(tmp / "small.json", tmp / name);
        EXPECT_EQ(r.written.size(), std::string(name) == "small.gltf" ? 2u : 1u);
        rt::ConvertOptions o;
        o.camera = 0;
        const rt::ConvertResult back = rt::convert_file(tmp / name, tmp / "back.json", o);
        const rt::SceneDesc a = rt::load_scene(tmp / "small.json"), b = rt::load_scene(tmp / "back.json");
        EXPECT_TRUE(same(a.background, b.background));
        EXPECT_EQ(a.shadow_ray_epsilon, b.shadow_ray_epsilon);
        EXPECT_EQ(a.max_recursion_depth, b.max_recursion_depth);
        EXPECT_TRUE(same(a.ambient_light, b.ambient_light));
        ASSERT_EQ(b.cameras.size(), 1u);
        EXPECT_EQ(b.cameras[0].left, rt::Real(-0.3));
        EXPECT_EQ(b.cameras[0].top, rt::Real(0.2));
        EXPECT_EQ(b.cameras[0].width, 30);
        EXPECT_EQ(b.cameras[0].image_name, "small.png");
        EXPECT_TRUE(same(b.point_lights[0].intensity, {300, 200, 100}));
        ASSERT_EQ(b.materials.size(), 2u);
        EXPECT_EQ(b.materials[1].type, rt::MaterialType::Dielectric);
        EXPECT_TRUE(same(b.materials[1].absorption_coefficient, {0.2, 0.1, 0}));
        EXPECT_EQ(b.materials[0].phong_exponent, 17);
        // The mesh, its instance (another material), the sphere and the plane, exact.
        ASSERT_EQ(b.meshes.size(), 1u);
        EXPECT_TRUE(same(b.meshes[0].positions[2], {0, 1, 0}));
        ASSERT_EQ(b.all<rt::InstanceDesc>().size(), 2u);
        EXPECT_EQ(b.all<rt::InstanceDesc>()[1].material, 1u);
        EXPECT_EQ(b.all<rt::InstanceDesc>()[1].transform.m[2][3], a.all<rt::InstanceDesc>()[1].transform.m[2][3]);
        ASSERT_EQ(b.all<rt::SphereDesc>().size(), 1u);
        EXPECT_TRUE(same(b.all<rt::SphereDesc>()[0].center, {0.3, 0.1, 0.7}));
        EXPECT_EQ(b.all<rt::SphereDesc>()[0].radius, 0.25);
        ASSERT_EQ(b.all<rt::PlaneDesc>().size(), 1u);
        EXPECT_TRUE(same(b.all<rt::PlaneDesc>()[0].normal, {0, 1, 0}));
        EXPECT_TRUE(any_contains(back.notes, "material 2 (Material 2): dielectric, the exported course values"));
    }
}

TEST(GltfExport, EditedValuesWinOverTheExtras) {
    TempDir tmp;
    std::ofstream(tmp / "small.json") << kSmallScene;
    rt::convert_file(tmp / "small.json", tmp / "small.gltf");
    json g = json::parse(std::ifstream(tmp / "small.gltf"));
    // In a modelling tool: the first material turned red, the camera moved, the sphere's
    // mesh pulled out of shape.
    g["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 0, 0, 1};
    for (json& n : g["nodes"])
        if (n.contains("camera")) n["translation"] = {0, 0, 9};
    std::ofstream(tmp / "small.gltf") << g.dump();
    const rt::ConvertResult r = rt::convert_file(tmp / "small.gltf", tmp / "back.json");
    const rt::SceneDesc b = rt::load_scene(tmp / "back.json");
    EXPECT_TRUE(any_contains(r.notes, "material 1 (Material 1): plain, from its PBR values"));
    EXPECT_TRUE(same(b.materials[0].diffuse, {1, 0, 0}));
    EXPECT_TRUE(same(b.cameras[0].position, {0, 0, 9}));
    EXPECT_EQ(b.cameras[0].left, -b.cameras[0].right);  // from glTF's symmetric frustum now
}

TEST(GltfExport, CameraNodeLooksWhereTheCameraLooks) {
    TempDir tmp;
    std::ofstream(tmp / "small.json") << kSmallScene;
    rt::convert_file(tmp / "small.json", tmp / "small.gltf");
    const json g = json::parse(std::ifstream(tmp / "small.gltf"));
    for (const json& n : g["nodes"])
        if (n.contains("camera")) {
            EXPECT_EQ(n["rotation"], json({0.0, 0.0, 0.0, 1.0}));  // gaze -z, up +y: glTF's own frame
            EXPECT_EQ(n["translation"], json({0.0, 0.0, 5.0}));
        }
    // yfov from the near plane: 2 atan(0.2).
    EXPECT_DOUBLE_EQ(g["cameras"][0]["perspective"]["yfov"].get<double>(), 2 * std::atan(double(rt::Real(0.2))));
    EXPECT_DOUBLE_EQ(g["cameras"][0]["perspective"]["aspectRatio"].get<double>(), 1.5);
}

#endif  // !RT_NO_GLTF && !RT_NO_XML && !RT_NO_OBJ
