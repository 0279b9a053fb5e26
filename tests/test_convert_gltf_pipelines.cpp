// glTF files every tool accepts, and what pipelines add (docs/gltf.md): the exports leave
// zfar out and name the scene by its file; quantised attributes (KHR_mesh_quantization) are
// dequantised exactly under their node's transform; GPU instances (EXT_mesh_gpu_instancing)
// are instances; an unread required extension is the one line, before anything else fails.
// The compressed files: tests/test_convert_gltf_codecs.cpp.
#include <gtest/gtest.h>

#if !defined(RT_NO_GLTF) && !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "convert_test_support.h"
#include "gltf_test_support.h"
#include "rt/convert/convert.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/shape_descs.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace convert_test;

namespace {

// A course scene of one triangle, one camera, one light.
std::string tiny_scene(const TempDir& tmp) {
    std::ofstream(tmp / "tiny.json") << R"({"Scene": {"BackgroundColor": "0 0 0", "MaxRecursionDepth": "1",
        "Cameras": {"Camera": {"_id": "1", "Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
            "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "8 8", "ImageName": "t.png"}},
        "Lights": {"AmbientLight": "10 10 10", "PointLight": {"_id": "1", "Position": "0 0 5", "Intensity": "100 100 100"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1",
            "SpecularReflectance": "0 0 0", "PhongExponent": "1"}},
        "VertexData": {"_data": "0 0 0 1 0 0 0 1 0"},
        "Objects": {"Triangle": {"_id": "1", "Material": "1", "Indices": "1 2 3"}}}})";
    return tmp / "tiny.json";
}

// The JSON of a .gltf, or of a .glb's JSON chunk.
json gltf_json(const std::string& path) {
    const std::string bytes = read_text(path);
    if (bytes.compare(0, 4, "glTF") != 0) return json::parse(bytes);
    uint32_t length;
    std::memcpy(&length, bytes.data() + 12, 4);
    return json::parse(bytes.substr(20, length));
}

}  // namespace

// ---- Exports the validator accepts ---------------------------------------------------------

TEST(GltfExportValid, NoZfarAndTheSceneNamedByItsFile) {
    TempDir tmp;
    for (const char* out : {"t.gltf", "t.glb"}) {
        SCOPED_TRACE(out);
        rt::convert_file(tiny_scene(tmp), tmp / out);
        const json j = gltf_json(tmp / out);
        ASSERT_EQ(j["cameras"].size(), 1u);
        EXPECT_FALSE(j["cameras"][0]["perspective"].contains("zfar"));  // glTF's infinite projection
        EXPECT_GT(j["cameras"][0]["perspective"]["znear"].get<double>(), 0);
        EXPECT_EQ(j["scenes"][0]["name"], "tiny.json");  // not the author's folders
        // And it reads back as the same triangle.
        const Imported im = import(tmp, tmp / out);
        ASSERT_EQ(world_triangles(im.scene).size(), 1u);
    }
    // The .glb's chunks are 4-byte aligned and its header's length is the file's.
    const std::string glb = read_text(tmp / "t.glb");
    uint32_t total, json_length;
    std::memcpy(&total, glb.data() + 8, 4);
    std::memcpy(&json_length, glb.data() + 12, 4);
    EXPECT_EQ(total, glb.size());
    EXPECT_EQ(json_length % 4, 0u);
    EXPECT_EQ(glb.compare(20 + json_length + 4, 4, std::string("BIN\0", 4)), 0);
}

// ---- KHR_mesh_quantization --------------------------------------------------------------

TEST(GltfQuantized, EveryComponentTypeDequantisedUnderItsNodesTransform) {
    TempDir tmp;
    struct Case {
        int component;
        bool normalized;
        std::vector<int> values;  // one triangle, x y z per corner
        std::vector<double> expected;
    };
    const std::vector<Case> cases = {
        {5122, true, {0, 0, 0, 32767, 0, 0, 0, -32768, 16384}, {0, 0, 0, 1, 0, 0, 0, -1, 16384.0 / 32767}},
        {5123, true, {0, 0, 0, 65535, 0, 0, 0, 13107, 0}, {0, 0, 0, 1, 0, 0, 0, 0.2, 0}},
        {5120, true, {0, 0, 0, 127, 0, 0, 0, -128, 64}, {0, 0, 0, 1, 0, 0, 0, -1, 64.0 / 127}},
        {5121, true, {0, 0, 0, 255, 0, 0, 0, 51, 0}, {0, 0, 0, 1, 0, 0, 0, 0.2, 0}},
        {5122, false, {0, 0, 0, 300, 0, 0, 0, -7, 2}, {0, 0, 0, 300, 0, 0, 0, -7, 2}},
        {5121, false, {0, 0, 0, 3, 0, 0, 0, 200, 1}, {0, 0, 0, 3, 0, 0, 0, 200, 1}}};
    for (const Case& c : cases) {
        SCOPED_TRACE(std::to_string(c.component) + (c.normalized ? " normalized" : ""));
        GltfFile f;
        const size_t size = c.component == 5120 || c.component == 5121 ? 1 : 2;
        std::vector<unsigned char> bytes;
        for (size_t i = 0; i < c.values.size(); ++i) {
            if (i % 3 == 0) bytes.resize((i / 3) * 4 * size);  // a 4-byte stride, as writers pad
            const int16_t v = int16_t(c.values[i]);
            const unsigned char* b = reinterpret_cast<const unsigned char*>(&v);
            bytes.insert(bytes.end(), b, b + size);
        }
        bytes.resize(3 * 4 * size);
        const int view = f.view(bytes.data(), bytes.size());
        f.j["bufferViews"][size_t(view)]["byteStride"] = 4 * size;
        f.j["accessors"].push_back(
            {{"bufferView", view}, {"componentType", c.component}, {"count", 3}, {"type", "VEC3"}});
        if (c.normalized) f.j["accessors"].back()["normalized"] = true;
        f.j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}});
        f.j["extensionsUsed"] = f.j["extensionsRequired"] = {"KHR_mesh_quantization"};
        // glTF Transform's dequantisation: a scale and an offset on the node.
        f.node({{"mesh", 0}, {"translation", {1, 2, 3}}, {"scale", {2, 2, 2}}});
        const Imported im = import(tmp, f.write(tmp));
        const auto tris = world_triangles(im.scene);
        ASSERT_EQ(tris.size(), 1u);
        std::vector<std::array<double, 3>> want, got;
        for (size_t k = 0; k < 3; ++k) {
            want.push_back({1 + 2 * c.expected[3 * k], 2 + 2 * c.expected[3 * k + 1], 3 + 2 * c.expected[3 * k + 2]});
            got.push_back({tris[0][3 * k], tris[0][3 * k + 1], tris[0][3 * k + 2]});
        }
        std::sort(want.begin(), want.end());
        std::sort(got.begin(), got.end());
        for (size_t k = 0; k < 3; ++k)
            for (size_t a = 0; a < 3; ++a)  // to the precision's rounding of the loaded scene
                EXPECT_NEAR(got[k][a], want[k][a], 8 * std::numeric_limits<rt::Real>::epsilon() * 5) << k << " " << a;
    }
}

TEST(GltfQuantized, AQuantisedPlaneIsStillThePlane) {
    // An exported plane (a quad, its extras the plane) as quantize writes it: positions in
    // [-1, 1] that no longer pass through the extras' point, the node moving and scaling them
    // back. It comes back as the plane, not as the finite quad.
    TempDir tmp;
    GltfFile f;
    const int16_t q[] = {-32767, 0, -32767, 0, 32767, 0, -32767, 0, 32767, 0, 32767, 0, -32767, 0, 32767, 0};
    const int view = f.view(q, sizeof q);
    f.j["bufferViews"][size_t(view)]["byteStride"] = 8;
    f.j["accessors"].push_back({{"bufferView", view},
                                {"componentType", 5122},
                                {"normalized", true},
                                {"count", 4},
                                {"type", "VEC3"},
                                {"min", {-1, 0, -1}},
                                {"max", {1, 0, 1}}});
    f.j["accessors"].push_back({{"bufferView", f.view(std::vector<uint32_t>{0, 2, 1, 0, 3, 2}.data(), 24)},
                                {"componentType", 5125},
                                {"count", 6},
                                {"type", "SCALAR"}});
    const json plane = {{"ceng795", {{"plane", {{"point", {0, -0.5, 0}}, {"normal", {0, 1, 0}}}}}}};
    f.j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}, {"extras", plane}});
    f.j["extensionsUsed"] = f.j["extensionsRequired"] = {"KHR_mesh_quantization"};
    f.node({{"mesh", 0}, {"translation", {-0.0875, -0.5, -1.15}}, {"scale", {18.2, 18.2, 18.2}}});
    const Imported im = import(tmp, f.write(tmp));
    EXPECT_TRUE(world_triangles(im.scene).empty());
    const auto planes = im.scene.all<rt::PlaneDesc>();
    ASSERT_EQ(planes.size(), 1u);
    // In the world (the loader applies its node's transformation): through y = -0.5,
    // facing +y.
    EXPECT_NEAR(double(planes[0].point.y), -0.5, 1e-6);
    EXPECT_NEAR(double(rt::normalize(planes[0].normal).y), 1, 1e-9);
    // Off the plane by more than the 14 bits quantize keeps: the quad it is.
    int16_t bent[16];
    std::memcpy(bent, q, sizeof q);
    bent[1] = 200;  // the first corner's y: 0.006 of the half extent
    GltfFile g = f;
    g.bin.clear();
    g.j["bufferViews"] = json::array();
    g.view(bent, sizeof bent);
    g.j["bufferViews"][0]["byteStride"] = 8;
    g.view(std::vector<uint32_t>{0, 2, 1, 0, 3, 2}.data(), 24);
    g.j["accessors"][0]["max"][1] = 200.0 / 32767;
    TempDir tmp2;
    const Imported quad = import(tmp2, g.write(tmp2));
    EXPECT_TRUE(quad.scene.all<rt::PlaneDesc>().empty());
    EXPECT_EQ(world_triangles(quad.scene).size(), 2u);
}

TEST(GltfJoined, SpheresJoinedIntoOneMeshAreSpheresAgain) {
    // optimize's join merges exported spheres of one material into one mesh, keeping the
    // extras of one: each part that shares no vertex with the rest and lies on a sphere is
    // that sphere. Here two icosahedra (their 12 corners on the sphere) of radius 1 and 2.
    const double t = (1 + std::sqrt(5.0)) / 2, s = 1 / std::sqrt(1 + t * t);
    const double ico[12][3] = {{-1, t, 0},  {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
    const uint32_t faces[] = {0, 11, 5,  0, 5,  1, 0, 1, 7, 0, 7,  10, 0, 10, 11, 1, 5, 9, 5, 11,
                              4, 11, 10, 2, 10, 7, 6, 7, 1, 8, 3,  9,  4, 3,  4,  2, 3, 2, 6, 3,
                              6, 8,  3,  8, 9,  4, 9, 5, 2, 4, 11, 6,  2, 10, 8,  6, 7, 9, 8, 1};
    auto joined = [&](double push) {
        std::vector<float> p;
        std::vector<uint32_t> idx;
        const double centre[2][3] = {{0, 0, 0}, {5, 1, 0}}, radius[2] = {1, 2};
        for (int k = 0; k < 2; ++k) {
            for (int v = 0; v < 12; ++v)
                for (int a = 0; a < 3; ++a)
                    p.push_back(float(centre[k][a] + radius[k] * s * ico[v][a] * (k == 1 && v == 3 ? 1 + push : 1)));
            for (uint32_t f : faces) idx.push_back(uint32_t(12 * k) + f);
        }
        GltfFile f;
        f.mesh(p, idx);
        f.j["meshes"][0]["extras"] = {{"ceng795", {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}}}};
        f.node({{"mesh", 0}, {"translation", {0, 0, -3}}});
        return f;
    };
    TempDir tmp;
    const Imported im = import(tmp, joined(0).write(tmp));
    EXPECT_TRUE(world_triangles(im.scene).empty());
    const auto spheres = im.scene.all<rt::SphereDesc>();
    ASSERT_EQ(spheres.size(), 2u);
    const double want[2][4] = {{0, 0, -3, 1}, {5, 1, -3, 2}};
    for (size_t k = 0; k < 2; ++k) {
        const rt::Vec3 c = spheres[k].transform.point(spheres[k].center);  // in float: 1e-5
        EXPECT_NEAR(double(c.x), want[k][0], 1e-5) << k;
        EXPECT_NEAR(double(c.y), want[k][1], 1e-5) << k;
        EXPECT_NEAR(double(c.z), want[k][2], 1e-5) << k;
        EXPECT_NEAR(double(spheres[k].radius), want[k][3], 1e-5) << k;
    }
    // A corner 1% off its sphere: not a sphere, so the mesh as it is.
    TempDir tmp2;
    const Imported bent = import(tmp2, joined(0.01).write(tmp2));
    EXPECT_TRUE(bent.scene.all<rt::SphereDesc>().empty());
    EXPECT_EQ(world_triangles(bent.scene).size(), 40u);
}

TEST(GltfJoined, ABoxJoinedWithASphereStaysAMesh) {
    // A box's 8 corners lie on a sphere; its faces do not: joined with an exported sphere's
    // mesh (its extras a sphere's), the box stays triangles.
    std::vector<float> p;
    for (int c = 0; c < 8; ++c) p.insert(p.end(), {c & 1 ? 1.f : -1.f, c & 2 ? 1.f : -1.f, c & 4 ? 1.f : -1.f});
    const std::vector<uint32_t> idx = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4,
                                       2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    GltfFile f;
    f.mesh(p, idx);
    f.j["meshes"][0]["extras"] = {{"ceng795", {{"sphere", {{"center", {5, 0, 0}}, {"radius", 1}}}}}};
    f.node({{"mesh", 0}, {"translation", {0, 0, -3}}});
    TempDir tmp;
    const Imported im = import(tmp, f.write(tmp));
    EXPECT_TRUE(im.scene.all<rt::SphereDesc>().empty());
    EXPECT_EQ(world_triangles(im.scene).size(), 12u);
}

TEST(GltfJoined, AFlattenedEllipsoidIsASphereUnderItsMapAgain) {
    // optimize's flatten moves a sphere under a non-uniform scaling (an ellipsoid) into world
    // space: a UV sphere of 16 segments under `map`, written in world space with a sphere's
    // extras, comes back as a sphere whose transformation puts it on the same ellipsoid.
    const rt::Affine map =
        rt::Affine::translation(1, 2, -6) * rt::Affine::rotation(30, 0, 0, 1) * rt::Affine::scaling(1, 2, 0.5);
    std::vector<float> p;
    std::vector<uint32_t> idx;
    const int n = 16;
    for (int i = 0; i <= n / 2; ++i)
        for (int j = 0; j < n; ++j) {
            const double th = M_PI * i / (n / 2), ph = 2 * M_PI * j / n;
            const rt::Vec3 q = map.point({std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)});
            p.insert(p.end(), {float(q.x), float(q.y), float(q.z)});
        }
    for (int i = 0; i < n / 2; ++i)
        for (int j = 0; j < n; ++j) {
            const uint32_t a = uint32_t(i * n + j), b = uint32_t(i * n + (j + 1) % n);
            idx.insert(idx.end(), {a, a + uint32_t(n), b, b, a + uint32_t(n), b + uint32_t(n)});
        }
    GltfFile f;
    f.mesh(p, idx);
    f.j["meshes"][0]["extras"] = {{"ceng795", {{"sphere", {{"center", {0, 0, 0}}, {"radius", 1}}}}}};
    f.node({{"mesh", 0}});
    TempDir tmp;
    const Imported im = import(tmp, f.write(tmp));
    const auto spheres = im.scene.all<rt::SphereDesc>();
    ASSERT_EQ(spheres.size(), 1u);
    EXPECT_TRUE(world_triangles(im.scene).empty());
    // Points of the imported sphere, mapped back by the inverse of `map`, are on the unit
    // sphere (to the floats the vertices were written in).
    const rt::Affine back = map.inverse();
    for (int k = 0; k < 50; ++k) {
        const double th = 0.37 * k, ph = 1.13 * k;
        const rt::Vec3 u{std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph)};
        const rt::Vec3 q = spheres[0].transform.point(spheres[0].center + u * spheres[0].radius);
        EXPECT_NEAR(double(rt::length(back.point(q))), 1.0, 1e-5) << k;
    }
}

TEST(GltfQuantized, ANonNumericComponentTypeIsRefusedNamingTheAccessor) {
    TempDir tmp;
    GltfFile f;
    const std::vector<uint32_t> ints = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const int view = f.view(ints.data(), ints.size() * 4);
    f.j["accessors"].push_back({{"bufferView", view}, {"componentType", 5125}, {"count", 3}, {"type", "VEC3"}});
    f.j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}});
    f.node({{"mesh", 0}});
    const std::string e = refused(tmp, f.write(tmp, "ints.gltf"));
    EXPECT_TRUE(contains(e, "/accessors/0: has component type 5125")) << e;
}

// ---- EXT_mesh_gpu_instancing -------------------------------------------------------------

TEST(GltfGpuInstancing, EachInstanceIsTheMeshUnderItsOwnMatrix) {
    TempDir tmp;
    GltfFile f;
    const int mesh = f.mesh(kTriangle, {0, 1, 2});
    const std::vector<float> t = {0, 0, 0, 10, 0, 0, 0, 10, 0};
    const int view = f.view(t.data(), t.size() * 4);
    f.j["accessors"].push_back({{"bufferView", view}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}});
    const int translation = int(f.j["accessors"].size() - 1);
    f.j["extensionsUsed"] = {"EXT_mesh_gpu_instancing"};
    f.node({{"mesh", mesh},
            {"translation", {0, 0, -1}},
            {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", translation}}}}}}}});
    const Imported im = import(tmp, f.write(tmp));
    EXPECT_FALSE(any_contains(im.result.warnings, "EXT_mesh_gpu_instancing"));
    EXPECT_EQ(im.scene.meshes.size(), 1u);
    EXPECT_EQ(im.tree["Scene"]["Objects"]["MeshInstance"].size(), 2u);  // and the Mesh
    const auto tris = world_triangles(im.scene);
    ASSERT_EQ(tris.size(), 3u);
    // Sorted: the instance at the origin, at y 10, at x 10; each moved by the node's -1 in z.
    EXPECT_EQ(tris[0], (std::array<double, 9>{0, 0, -1, 1, 0, -1, 0, 1, -1}));
    EXPECT_EQ(tris[1], (std::array<double, 9>{0, 10, -1, 1, 10, -1, 0, 11, -1}));
    EXPECT_EQ(tris[2], (std::array<double, 9>{10, 0, -1, 11, 0, -1, 10, 1, -1}));
}

// ---- A file that requires what rtconvert does not read ---------------------------------------

TEST(GltfExtensions, AnUnreadRequiredExtensionIsNamedBeforeAnythingElseFails) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    f.j["extensionsRequired"] = {"KHR_mesh_quantization", "KHR_texture_basisu"};
    f.write(tmp, "basisu.gltf");
    // Its buffer is missing too: the extension is what the line names.
    fs::remove(tmp / "data.bin");
    const std::string e = refused(tmp, tmp / "basisu.gltf");
    EXPECT_TRUE(contains(e,
                         "basisu.gltf: /extensionsRequired/1: the file requires extension KHR_texture_basisu, "
                         "which rtconvert does not read"))
        << e;
}

#endif
