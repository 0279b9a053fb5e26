// Tests for the JSON scene loader (include/rt/loader/load_scene.h, src/loader/), valid input:
// parse_scene on JSON held in memory gives the spec's sample scene, defaults, single-object
// and array forms that agree, lookAt cameras, inline meshes, warnings for unknown keys,
// and numbers given as JSON numbers.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "loader_test_support.h"
#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/scene_desc.h"

namespace {

using namespace loader_test;
using rt::Real;
using rt::Vec3;

// Tolerance for extents worked out by hand (double by default; float with PRECISION=float).
const Real kClose = sizeof(Real) == sizeof(double) ? Real(1e-12) : Real(2e-6);

// The sample's VertexData, 0-based.
const Vec3 kSampleVerts[9] = {{-0.5, 0.5, -2}, {-0.5, -0.5, -2}, {0.5, -0.5, -2}, {0.5, 0.5, -2}, {0.75, 0.75, -2},
                              {1, 0.75, -2},   {0.875, 1, -2},   {-0.875, 1, -2}, {0, -0.5, 0}};

void expect_vec(Vec3 got, Vec3 want, const std::string& what) {
    EXPECT_EQ(got.x, want.x) << what;
    EXPECT_EQ(got.y, want.y) << what;
    EXPECT_EQ(got.z, want.z) << what;
}

// Vertex k of triangle f of a mesh, resolved through its local vertex list.
Vec3 corner(const rt::MeshDesc& m, size_t f, int k) { return m.positions.at(m.indices.at(3 * f + k)); }

// --- equality of descriptions ----------------------------------------------------------

void expect_same(const rt::SceneDesc& a, const rt::SceneDesc& b) {
    expect_vec(a.background, b.background, "background");
    EXPECT_EQ(a.shadow_ray_epsilon, b.shadow_ray_epsilon);
    EXPECT_EQ(a.intersection_test_epsilon, b.intersection_test_epsilon);
    EXPECT_EQ(a.max_recursion_depth, b.max_recursion_depth);
    expect_vec(a.ambient_light, b.ambient_light, "ambient light");
    ASSERT_EQ(a.cameras.size(), b.cameras.size());
    for (size_t i = 0; i < a.cameras.size(); ++i) {
        const rt::CameraDesc &x = a.cameras[i], &y = b.cameras[i];
        expect_vec(x.position, y.position, "camera position");
        expect_vec(x.gaze, y.gaze, "camera gaze");
        expect_vec(x.up, y.up, "camera up");
        EXPECT_EQ(x.left, y.left);
        EXPECT_EQ(x.right, y.right);
        EXPECT_EQ(x.bottom, y.bottom);
        EXPECT_EQ(x.top, y.top);
        EXPECT_EQ(x.near_distance, y.near_distance);
        EXPECT_EQ(x.width, y.width);
        EXPECT_EQ(x.height, y.height);
        EXPECT_EQ(x.image_name, y.image_name);
    }
    ASSERT_EQ(a.point_lights.size(), b.point_lights.size());
    for (size_t i = 0; i < a.point_lights.size(); ++i) {
        expect_vec(a.point_lights[i].position, b.point_lights[i].position, "light position");
        expect_vec(a.point_lights[i].intensity, b.point_lights[i].intensity, "light intensity");
    }
    ASSERT_EQ(a.materials.size(), b.materials.size());
    for (size_t i = 0; i < a.materials.size(); ++i) {
        const rt::MaterialDesc &x = a.materials[i], &y = b.materials[i];
        EXPECT_EQ(x.type, y.type);
        expect_vec(x.ambient, y.ambient, "ambient");
        expect_vec(x.diffuse, y.diffuse, "diffuse");
        expect_vec(x.specular, y.specular, "specular");
        EXPECT_EQ(x.phong_exponent, y.phong_exponent);
        expect_vec(x.mirror, y.mirror, "mirror");
        EXPECT_EQ(x.refraction_index, y.refraction_index);
        EXPECT_EQ(x.absorption_index, y.absorption_index);
        expect_vec(x.absorption_coefficient, y.absorption_coefficient, "absorption coefficient");
    }
    ASSERT_EQ(a.meshes.size(), b.meshes.size());
    for (size_t i = 0; i < a.meshes.size(); ++i) {
        const rt::MeshDesc &x = a.meshes[i], &y = b.meshes[i];
        EXPECT_EQ(x.material, y.material);
        EXPECT_EQ(x.shading, y.shading);
        ASSERT_EQ(x.indices.size(), y.indices.size());
        for (size_t f = 0; f < x.indices.size() / 3; ++f)
            for (int k = 0; k < 3; ++k) expect_vec(corner(x, f, k), corner(y, f, k), "mesh corner");
    }
    ASSERT_EQ(a.all<rt::SphereDesc>().size(), b.all<rt::SphereDesc>().size());
    for (size_t i = 0; i < a.all<rt::SphereDesc>().size(); ++i) {
        EXPECT_EQ(a.all<rt::SphereDesc>()[i].material, b.all<rt::SphereDesc>()[i].material);
        expect_vec(a.all<rt::SphereDesc>()[i].center, b.all<rt::SphereDesc>()[i].center, "sphere centre");
        EXPECT_EQ(a.all<rt::SphereDesc>()[i].radius, b.all<rt::SphereDesc>()[i].radius);
    }
    ASSERT_EQ(a.all<rt::PlaneDesc>().size(), b.all<rt::PlaneDesc>().size());
    for (size_t i = 0; i < a.all<rt::PlaneDesc>().size(); ++i) {
        EXPECT_EQ(a.all<rt::PlaneDesc>()[i].material, b.all<rt::PlaneDesc>()[i].material);
        expect_vec(a.all<rt::PlaneDesc>()[i].point, b.all<rt::PlaneDesc>()[i].point, "plane point");
        expect_vec(a.all<rt::PlaneDesc>()[i].normal, b.all<rt::PlaneDesc>()[i].normal, "plane normal");
    }
}

// --- valid input ---------------------------------------------------------------------------

TEST(LoaderValid, SpecSampleScene) {
    const rt::SceneDesc d = parse(kSample);
    EXPECT_EQ(d.path, kPath);
    ASSERT_EQ(d.cameras.size(), 1u);
    ASSERT_EQ(d.point_lights.size(), 1u);
    ASSERT_EQ(d.materials.size(), 1u);
    ASSERT_EQ(d.meshes.size(), 2u);  // the Mesh and the Triangle (a one-triangle mesh)
    ASSERT_EQ(d.all<rt::SphereDesc>().size(), 1u);
    ASSERT_EQ(d.all<rt::PlaneDesc>().size(), 1u);

    expect_vec(d.background, {0, 0, 0}, "background");
    EXPECT_EQ(d.shadow_ray_epsilon, Real(1e-3));
    EXPECT_EQ(d.intersection_test_epsilon, Real(1e-6));
    EXPECT_EQ(d.max_recursion_depth, 6);  // absent: default
    expect_vec(d.ambient_light, {25, 25, 25}, "ambient");

    const rt::CameraDesc& c = d.cameras[0];
    expect_vec(c.position, {0, 0, 0}, "position");
    expect_vec(c.gaze, {0, 0, -1}, "gaze");
    expect_vec(c.up, {0, 1, 0}, "up");
    EXPECT_EQ(c.left, -1);
    EXPECT_EQ(c.right, 1);
    EXPECT_EQ(c.bottom, -1);
    EXPECT_EQ(c.top, 1);
    EXPECT_EQ(c.near_distance, 1);
    EXPECT_EQ(c.width, 800);
    EXPECT_EQ(c.height, 800);
    EXPECT_EQ(c.image_name, "simple.png");

    expect_vec(d.point_lights[0].position, {0, 0, 0}, "light position");
    expect_vec(d.point_lights[0].intensity, {1000, 1000, 1000}, "intensity");

    const rt::MaterialDesc& m = d.materials[0];
    EXPECT_EQ(m.type, rt::MaterialType::Plain);
    expect_vec(m.ambient, {1, 1, 1}, "ka");
    expect_vec(m.diffuse, {1, 1, 1}, "kd");
    expect_vec(m.specular, {1, 1, 1}, "ks");
    EXPECT_EQ(m.phong_exponent, 1);

    // Faces "3 1 2 1 3 4" are 1-based: triangles (v3, v1, v2) and (v1, v3, v4).
    const rt::MeshDesc& mesh = d.meshes[0];
    EXPECT_EQ(mesh.material, 0u);
    EXPECT_EQ(mesh.shading, rt::ShadingMode::Flat);
    ASSERT_EQ(mesh.indices.size(), 6u);
    EXPECT_EQ(mesh.positions.size(), 4u) << "the mesh keeps the 4 vertices it uses";
    const int faces[2][3] = {{3, 1, 2}, {1, 3, 4}};
    for (size_t f = 0; f < 2; ++f)
        for (int k = 0; k < 3; ++k) expect_vec(corner(mesh, f, k), kSampleVerts[faces[f][k] - 1], "mesh corner");

    const rt::MeshDesc& tri = d.meshes[1];
    ASSERT_EQ(tri.indices.size(), 3u);
    EXPECT_EQ(tri.positions.size(), 3u);
    for (int k = 0; k < 3; ++k) expect_vec(corner(tri, 0, k), kSampleVerts[4 + k], "triangle corner");  // 5 6 7

    EXPECT_EQ(d.all<rt::SphereDesc>()[0].material, 0u);
    expect_vec(d.all<rt::SphereDesc>()[0].center, {-0.875, 1, -2}, "sphere centre (vertex 8)");
    EXPECT_EQ(d.all<rt::SphereDesc>()[0].radius, Real(0.3));
    expect_vec(d.all<rt::PlaneDesc>()[0].point, {0, -0.5, 0}, "plane point (vertex 9)");
    expect_vec(d.all<rt::PlaneDesc>()[0].normal, {0, 1, 0}, "plane normal");
    EXPECT_TRUE(d.warnings.empty()) << d.warnings.front();
}

const char* const kMinimal = R"({"Scene": {"Cameras": {"Camera": {"Position": "0 0 0", "Gaze": "0 0 -1",
    "Up": "0 1 0", "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "4 3", "ImageName": "m.png"}}}})";

TEST(LoaderValid, DefaultsWhenAbsent) {
    const rt::SceneDesc d = parse(kMinimal);
    EXPECT_EQ(d.max_recursion_depth, 6);
    EXPECT_EQ(d.shadow_ray_epsilon, Real(1e-3));
    EXPECT_EQ(d.intersection_test_epsilon, Real(1e-6));
    expect_vec(d.ambient_light, {0, 0, 0}, "ambient");
    expect_vec(d.background, {0, 0, 0}, "background");
    EXPECT_TRUE(d.point_lights.empty());
    EXPECT_TRUE(d.materials.empty());
    EXPECT_TRUE(d.meshes.empty());
    EXPECT_TRUE(d.all<rt::SphereDesc>().empty());
    EXPECT_TRUE(d.all<rt::PlaneDesc>().empty());
    EXPECT_EQ(d.cameras.at(0).width, 4);
    EXPECT_EQ(d.cameras.at(0).height, 3);

    // PhongExponent defaults to 1.
    json j = sample();
    j["Scene"]["Materials"]["Material"].erase("PhongExponent");
    EXPECT_EQ(parse(j.dump()).materials.at(0).phong_exponent, 1);
    // Lights present without AmbientLight: ambient 0.
    j["Scene"]["Lights"].erase("AmbientLight");
    expect_vec(parse(j.dump()).ambient_light, {0, 0, 0}, "ambient");
}

TEST(LoaderValid, ExplicitGlobals) {
    json j = sample();
    j["Scene"]["MaxRecursionDepth"] = "3";
    j["Scene"]["ShadowRayEpsilon"] = "0.25";
    j["Scene"]["BackgroundColor"] = "10 20 30";
    const rt::SceneDesc d = parse(j.dump());
    EXPECT_EQ(d.max_recursion_depth, 3);
    EXPECT_EQ(d.shadow_ray_epsilon, Real(0.25));
    expect_vec(d.background, {10, 20, 30}, "background");
    j["Scene"]["MaxRecursionDepth"] = "0";  // allowed: no bounces
    EXPECT_EQ(parse(j.dump()).max_recursion_depth, 0);
}

TEST(LoaderValid, SingleObjectAndArrayFormsAgree) {
    const rt::SceneDesc single = parse(kSample);
    json j = sample();
    json& s = j["Scene"];
    for (const char* key : {"Camera"}) s["Cameras"][key] = json::array({s["Cameras"][key]});
    s["Lights"]["PointLight"] = json::array({s["Lights"]["PointLight"]});
    s["Materials"]["Material"] = json::array({s["Materials"]["Material"]});
    for (const char* key : {"Mesh", "Triangle", "Sphere", "Plane"})
        s["Objects"][key] = json::array({s["Objects"][key]});
    const rt::SceneDesc arrays = parse(j.dump());
    expect_same(single, arrays);
    EXPECT_TRUE(arrays.warnings.empty());
}

TEST(LoaderValid, ArraysWithSeveralElements) {
    json j = sample();
    json& s = j["Scene"];
    json cam2 = s["Cameras"]["Camera"];
    cam2["_id"] = "2";
    cam2["ImageName"] = "second.png";
    s["Cameras"]["Camera"] = json::array({s["Cameras"]["Camera"], cam2});
    json m2 = s["Materials"]["Material"];
    m2["_id"] = "2";
    m2["DiffuseReflectance"] = "0.5 0.25 0.125";
    s["Materials"]["Material"] = json::array({s["Materials"]["Material"], m2});
    json sp2 = s["Objects"]["Sphere"];
    sp2["Material"] = "2";
    sp2["Center"] = "1";
    sp2["Radius"] = "2.5";
    s["Objects"]["Sphere"] = json::array({s["Objects"]["Sphere"], sp2});
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.cameras.size(), 2u);
    EXPECT_EQ(d.cameras[1].image_name, "second.png");
    ASSERT_EQ(d.materials.size(), 2u);
    expect_vec(d.materials[1].diffuse, {0.5, 0.25, 0.125}, "second material");
    ASSERT_EQ(d.all<rt::SphereDesc>().size(), 2u);
    EXPECT_EQ(d.all<rt::SphereDesc>()[1].material, 1u);  // "_id" 2 -> index 1
    expect_vec(d.all<rt::SphereDesc>()[1].center, kSampleVerts[0], "second sphere centre");
    EXPECT_EQ(d.all<rt::SphereDesc>()[1].radius, 2.5);
}

TEST(LoaderValid, MaterialIdsResolveById) {
    // Materials listed out of order: the object's "Material": "1" means the one with _id 1.
    json j = sample();
    json m1 = j["Scene"]["Materials"]["Material"];
    json m2 = m1;
    m2["_id"] = "2";
    m2["DiffuseReflectance"] = "0 0.5 0";
    j["Scene"]["Materials"]["Material"] = json::array({m2, m1});
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.materials.size(), 2u);
    const uint32_t sm = d.all<rt::SphereDesc>().at(0).material;
    ASSERT_LT(sm, 2u);
    expect_vec(d.materials[sm].diffuse, {1, 1, 1}, "the sphere's material is _id 1");
}

TEST(LoaderValid, MaterialTypes) {
    json j = sample();
    json mats = json::array();
    mats.push_back({{"_id", "1"},
                    {"_type", "mirror"},
                    {"AmbientReflectance", "0 0 0"},
                    {"DiffuseReflectance", "0 0 0"},
                    {"SpecularReflectance", "0 0 0"},
                    {"MirrorReflectance", "0.5 0.6 0.7"}});
    mats.push_back({{"_id", "2"},
                    {"_type", "conductor"},
                    {"AmbientReflectance", "0 0 0"},
                    {"DiffuseReflectance", "0 0 0"},
                    {"SpecularReflectance", "0 0 0"},
                    {"MirrorReflectance", "1 0.8 0.4"},
                    {"RefractionIndex", "0.37"},
                    {"AbsorptionIndex", "2.82"}});
    mats.push_back({{"_id", "3"},
                    {"_type", "dielectric"},
                    {"AmbientReflectance", "0 0 0"},
                    {"DiffuseReflectance", "0 0 0"},
                    {"SpecularReflectance", "0 0 0"},
                    {"RefractionIndex", "1.5"},
                    {"AbsorptionCoefficient", "0.01 0.02 0.03"}});
    j["Scene"]["Materials"]["Material"] = mats;
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.materials.size(), 3u);
    EXPECT_EQ(d.materials[0].type, rt::MaterialType::Mirror);
    expect_vec(d.materials[0].mirror, {0.5, 0.6, 0.7}, "mirror");
    EXPECT_EQ(d.materials[1].type, rt::MaterialType::Conductor);
    EXPECT_EQ(d.materials[1].refraction_index, Real(0.37));
    EXPECT_EQ(d.materials[1].absorption_index, Real(2.82));
    EXPECT_EQ(d.materials[2].type, rt::MaterialType::Dielectric);
    EXPECT_EQ(d.materials[2].refraction_index, 1.5);
    expect_vec(d.materials[2].absorption_coefficient, {0.01, 0.02, 0.03}, "absorption");
}

TEST(LoaderValid, LookAtCameraExtents) {
    // FovY 60, NearDistance 2, 400 x 200: top = 2 tan(30 deg) = 2 / sqrt(3) = 1.1547005,
    // right = top * 400 / 200 = 2.3094011; left and bottom mirror them.
    json j = sample();
    j["Scene"]["Cameras"]["Camera"] = {{"_id", "1"},
                                       {"_type", "lookAt"},
                                       {"Position", "1 2 3"},
                                       {"GazePoint", "1 2 -7"},
                                       {"Up", "0 1 0"},
                                       {"FovY", "60"},
                                       {"NearDistance", "2"},
                                       {"ImageResolution", "400 200"},
                                       {"ImageName", "look.png"}};
    const rt::SceneDesc d = parse(j.dump());
    const rt::CameraDesc& c = d.cameras.at(0);
    const Real top = 2 / std::sqrt(Real(3));
    EXPECT_NEAR(c.top, top, kClose);
    EXPECT_NEAR(c.bottom, -top, kClose);
    EXPECT_NEAR(c.right, 2 * top, kClose);
    EXPECT_NEAR(c.left, -2 * top, kClose);
    EXPECT_EQ(c.near_distance, 2);
    // Gaze = GazePoint - Position = (0, 0, -10).
    expect_vec(c.gaze, {0, 0, -10}, "gaze");
    expect_vec(c.position, {1, 2, 3}, "position");
    EXPECT_EQ(c.width, 400);
    EXPECT_EQ(c.height, 200);

    // Portrait: 200 x 400 gives right = top / 2.
    j["Scene"]["Cameras"]["Camera"]["ImageResolution"] = "200 400";
    const rt::CameraDesc p = parse(j.dump()).cameras.at(0);
    EXPECT_NEAR(p.top, top, kClose);
    EXPECT_NEAR(p.right, top / 2, kClose);
}

TEST(LoaderValid, EachInlineMeshGetsItsOwnVertices) {
    // Two meshes sharing VertexData entries 1 and 3, and a Triangle using 1 too.
    json j = sample();
    json m2 = j["Scene"]["Objects"]["Mesh"];
    m2["_id"] = "2";
    m2["Faces"]["_data"] = "1 3 9";
    m2["_shadingMode"] = "smooth";
    j["Scene"]["Objects"]["Mesh"] = json::array({j["Scene"]["Objects"]["Mesh"], m2});
    j["Scene"]["Objects"]["Triangle"]["Indices"] = "1 6 7";
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.meshes.size(), 3u);
    EXPECT_EQ(d.meshes[0].positions.size(), 4u);
    EXPECT_EQ(d.meshes[0].shading, rt::ShadingMode::Flat);
    EXPECT_EQ(d.meshes[1].positions.size(), 3u) << "only the vertices the mesh uses";
    EXPECT_EQ(d.meshes[1].shading, rt::ShadingMode::Smooth);
    EXPECT_EQ(d.meshes[2].positions.size(), 3u);
    expect_vec(corner(d.meshes[1], 0, 0), kSampleVerts[0], "mesh 2 corner 0");
    expect_vec(corner(d.meshes[1], 0, 1), kSampleVerts[2], "mesh 2 corner 1");
    expect_vec(corner(d.meshes[1], 0, 2), kSampleVerts[8], "mesh 2 corner 2");
    expect_vec(corner(d.meshes[2], 0, 0), kSampleVerts[0], "triangle corner 0");
    // Every index is local to its own mesh.
    for (const rt::MeshDesc& m : d.meshes)
        for (uint32_t i : m.indices) EXPECT_LT(i, m.positions.size());
    // A vertex used twice within one mesh is stored once: faces "1 2 3 1 3 4" use 4 vertices.
    j["Scene"]["Objects"]["Mesh"][0]["Faces"]["_data"] = "1 2 3 1 3 4";
    const rt::SceneDesc e = parse(j.dump());
    EXPECT_EQ(e.meshes[0].positions.size(), 4u);
    EXPECT_EQ(e.meshes[0].indices[0], e.meshes[0].indices[3]) << "both faces share vertex 1";
}

TEST(LoaderValid, UnknownKeysWarnButLoad) {
    json j = sample();
    j["Scene"]["TexCoordData"] = nullptr;
    j["Scene"]["Cameras"]["Camera"]["Exposure"] = "1";
    j["Scene"]["Objects"]["Sphere"]["Colour"] = "red";
    rt::SceneDesc d;
    ASSERT_NO_THROW(d = parse(j.dump()));
    ASSERT_GE(d.warnings.size(), 3u);
    auto mentioned = [&](const std::string& key) {
        for (const std::string& w : d.warnings)
            if (w.find(key) != std::string::npos) return true;
        return false;
    };
    EXPECT_TRUE(mentioned("TexCoordData"));
    EXPECT_TRUE(mentioned("Exposure"));
    EXPECT_TRUE(mentioned("Colour"));
    // The rest of the scene is unaffected.
    expect_same(d, parse(kSample));
}

TEST(LoaderValid, NumbersAsJsonNumbers) {
    json j = sample();
    json& s = j["Scene"];
    s["ShadowRayEpsilon"] = 0.001;
    s["MaxRecursionDepth"] = 6;
    s["Cameras"]["Camera"]["NearDistance"] = 1;
    s["Cameras"]["Camera"]["_id"] = 1;
    s["Materials"]["Material"]["PhongExponent"] = 1;
    s["Materials"]["Material"]["_id"] = 1;
    s["Objects"]["Sphere"]["Radius"] = 0.3;
    s["Objects"]["Sphere"]["Center"] = 8;
    s["Objects"]["Sphere"]["Material"] = 1;
    s["Objects"]["Plane"]["Point"] = 9;
    s["Objects"]["Mesh"]["Material"] = 1;
    s["Objects"]["Triangle"]["Material"] = 1;
    rt::SceneDesc d;
    ASSERT_NO_THROW(d = parse(j.dump()));
    expect_same(d, parse(kSample));
}

TEST(LoaderValid, NumberSyntax) {
    // Leading '+', exponents and extra whitespace are fine: "+1 -2e0  0.35E1" = (1, -2, 3.5).
    json j = sample();
    j["Scene"]["Cameras"]["Camera"]["Position"] = " +1\t-2e0  0.35E1 ";
    expect_vec(parse(j.dump()).cameras.at(0).position, {1, -2, 3.5}, "position");
}

TEST(LoaderValid, MalformedJsonNamesTheFile) {
    try {
        parse("{\"Scene\": {");
        FAIL() << "no exception";
    } catch (const rt::InputError& e) {
        EXPECT_EQ(std::string(e.what()).rfind(kPath + ": ", 0), 0u) << e.what();
    }
}

}  // namespace
