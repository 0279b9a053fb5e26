// The compressed glTF files pipelines write (src/convert/gltf_codecs.h, docs/gltf.md):
// EXT_meshopt_compression and KHR_draco_mesh_compression streams made here with
// libmeshoptimizer's and libdraco's own encoders decode to what was encoded, in every mode
// and filter; glTF Transform's own files (tests/fuzz/seeds/gltf/small_*.glb, made from
// small.glb) import as small.glb's surfaces; a truncated or corrupted stream, or one whose
// parameters lie, is one line naming the bufferView or primitive, with nothing written. A
// build without a library refuses the files that require it, naming the extension.
#include <gtest/gtest.h>

#if !defined(RT_NO_GLTF) && !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#ifndef RT_NO_MESHOPT
#include <meshoptimizer.h>
#endif
#ifndef RT_NO_DRACO
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#pragma GCC diagnostic pop
#endif

#include "convert_test_support.h"
#include "gltf_test_support.h"
#include "rt/convert/convert.h"
#include "rt/loader/shape_descs.h"
#include "test_support.h"

namespace fs = std::filesystem;
using nlohmann::json;
using namespace convert_test;

namespace {

const std::vector<float> kQuad = {0, 0, 0, 2, 0, 0, 2, 1, 0, 0, 1, 0};
const std::vector<uint32_t> kQuadFaces = {0, 1, 2, 0, 2, 3};
const std::vector<std::array<double, 9>> kQuadTriangles = {{0, 0, 0, 2, 0, 0, 2, 1, 0}, {0, 0, 0, 2, 1, 0, 0, 1, 0}};

template <class T>
std::vector<unsigned char> bytes_of(const std::vector<T>& v) {
    std::vector<unsigned char> out(v.size() * sizeof(T));
    std::memcpy(out.data(), v.data(), out.size());
    return out;
}

// The folder of glTF Transform's files: tests/fuzz/seeds/gltf at or above the current one.
std::string seeds() {
    for (fs::path p = fs::current_path(); !p.empty(); p = p.parent_path()) {
        if (fs::is_directory(p / "tests/fuzz/seeds/gltf")) return (p / "tests/fuzz/seeds/gltf").string();
        if (p == p.parent_path()) break;
    }
    return "";
}

// The box of the triangles' corners, and their summed area.
struct Surfaces {
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    double area = 0;
    size_t count = 0;
};
Surfaces surfaces(const std::vector<std::array<double, 9>>& tris) {
    Surfaces s;
    for (const auto& t : tris) {
        for (size_t k = 0; k < 9; ++k) {
            s.lo[k % 3] = std::min(s.lo[k % 3], t[k]);
            s.hi[k % 3] = std::max(s.hi[k % 3], t[k]);
        }
        const double e1[3] = {t[3] - t[0], t[4] - t[1], t[5] - t[2]}, e2[3] = {t[6] - t[0], t[7] - t[1], t[8] - t[2]};
        const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
        s.area += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    s.count = tris.size();
    return s;
}

}  // namespace

// ---- glTF Transform's files --------------------------------------------------------------

TEST(GltfPipelineFiles, GltfTransformsOutputsImportAsTheOriginal) {
    const std::string dir = seeds();
    ASSERT_FALSE(dir.empty()) << "tests/fuzz/seeds/gltf not found above " << fs::current_path();
    TempDir tmp;
    const Surfaces original = surfaces(world_triangles(import(tmp, dir + "/small.glb").scene));
    ASSERT_GT(original.count, 0u);
    double extent = 0;
    for (size_t k = 0; k < 3; ++k) extent = std::max(extent, original.hi[k] - original.lo[k]);
    for (const char* variant : {"quantize", "meshopt", "draco", "optimize"}) {
        SCOPED_TRACE(variant);
        const Surfaces s = surfaces(world_triangles(import(tmp, dir + "/small_" + variant + ".glb").scene));
        EXPECT_GT(s.count, 0u);
        // optimize joins the plane's square (a Plane again in the others) with the meshes
        // of its material: more surface, its box the plane's.
        if (std::string(variant) == "optimize") {
            EXPECT_GT(s.area, original.area);
            continue;
        }
        // The same triangles, within glTF Transform's 14 bits of the extent (Draco's too).
        const double tolerance = extent / (1 << 13);
        EXPECT_EQ(s.count, original.count);
        for (size_t k = 0; k < 3; ++k) {
            EXPECT_NEAR(s.lo[k], original.lo[k], tolerance) << k;
            EXPECT_NEAR(s.hi[k], original.hi[k], tolerance) << k;
        }
        EXPECT_NEAR(s.area, original.area, 1e-3 * original.area);
    }
}

namespace {

// What palette_scene.json's export through optimize must import as (below).
void check_palette_scene(const rt::SceneDesc& original, const Imported& back) {
    auto eq = [](const rt::Vec3& a, const rt::Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; };
    auto same = [&](const rt::MaterialDesc& a, const rt::MaterialDesc& b) {
        return a.type == b.type && eq(a.ambient, b.ambient) && eq(a.diffuse, b.diffuse) && eq(a.specular, b.specular) &&
               a.phong_exponent == b.phong_exponent;
    };
    const auto& spheres = back.scene.all<rt::SphereDesc>();
    ASSERT_EQ(spheres.size(), 3u);
    for (const rt::SphereDesc& o : original.all<rt::SphereDesc>()) {
        SCOPED_TRACE("sphere " + o.id);
        int found = 0;
        for (const rt::SphereDesc& s : spheres) {
            const rt::Vec3 c = s.transform.point(s.center);
            const double r = rt::length(s.transform.point(s.center + rt::Vec3{s.radius, 0, 0}) - c);
            if (rt::length(c - o.center) > 1e-3 || std::fabs(r - double(o.radius)) > 1e-3) continue;
            ++found;
            EXPECT_TRUE(same(back.scene.materials[s.material], original.materials[o.material]));
        }
        EXPECT_EQ(found, 1);
    }
    const auto& planes = back.scene.all<rt::PlaneDesc>();
    ASSERT_EQ(planes.size(), 1u);
    const rt::PlaneDesc& plane = original.all<rt::PlaneDesc>()[0];
    EXPECT_TRUE(eq(planes[0].point, plane.point));
    EXPECT_TRUE(eq(planes[0].normal, plane.normal));
    EXPECT_TRUE(same(back.scene.materials[planes[0].material], original.materials[plane.material]));
    // The meshes, each with its own material again, found by their world boxes: the two
    // whose materials differ only in AmbientReflectance too (one texel; the scene's
    // "materialBoxes" tell them apart).
    auto box = [](const rt::MeshDesc& m, const rt::Affine& to_world) {
        std::array<double, 6> b{HUGE_VAL, HUGE_VAL, HUGE_VAL, -HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
        for (const rt::Vec3& q : m.positions) {
            const rt::Vec3 p = to_world.point(q);
            const double c[3] = {p.x, p.y, p.z};
            for (size_t k = 0; k < 3; ++k) b[k] = std::min(b[k], c[k]), b[k + 3] = std::max(b[k + 3], c[k]);
        }
        return b;
    };
    auto world_of = [&](const rt::SceneDesc& scene, size_t mesh) {
        for (const rt::InstanceDesc& d : scene.all<rt::InstanceDesc>())
            if (d.mesh == mesh) return std::make_pair(box(scene.meshes[mesh], d.transform), d.material);
        return std::make_pair(box(scene.meshes[mesh], rt::Affine{}), scene.meshes[mesh].material);
    };
    ASSERT_EQ(back.scene.meshes.size(), original.meshes.size());
    for (size_t i = 0; i < original.meshes.size(); ++i) {
        SCOPED_TRACE("mesh " + original.meshes[i].id);
        const auto [want, material] = world_of(original, i);
        int found = 0;
        for (size_t j = 0; j < back.scene.meshes.size(); ++j) {
            const auto [got, got_material] = world_of(back.scene, j);
            bool at = true;
            // Quantised with the plane's square (side 107) they were joined with: a 14-bit
            // step is 0.0065.
            for (size_t k = 0; k < 6; ++k) at = at && std::fabs(got[k] - want[k]) < 0.01;
            if (!at) continue;
            ++found;
            EXPECT_TRUE(same(back.scene.materials[got_material], original.materials[material]));
        }
        EXPECT_EQ(found, 1);
    }
    // The area light, whose node optimize's prune dropped: the scene's extras keep it.
    ASSERT_EQ(back.scene.area_lights.size(), 1u);
    EXPECT_TRUE(eq(back.scene.area_lights[0].position, original.area_lights[0].position));
    EXPECT_TRUE(eq(back.scene.area_lights[0].radiance, original.area_lights[0].radiance));
}

}  // namespace

// tests/fuzz/seeds/gltf/palette_optimize.glb: tests/gltf/palette_scene.json (seven materials,
// two of them alike but for AmbientReflectance, three spheres, a plane sharing its material
// with a mesh, an area light) exported with --sphere-segments 16, then glTF Transform's
// optimize: its palette merges the materials into one, its join the spheres into one mesh
// and the plane into the mesh of its material, its prune drops the area light's node.
// palette_optimize_nojoin.glb: the same with --join false, where spheres of one radius share
// their POSITION but not their texture coordinates (their texels). tests/gltf/palette_optimize/:
// optimize's .gltf, its palette a PNG file beside it.
TEST(GltfPipelineFiles, OptimizesPaletteAndJoinComeBackAsTheScenesMaterialsSpheresAndPlane) {
    const std::string dir = seeds();
    ASSERT_FALSE(dir.empty()) << "tests/fuzz/seeds/gltf not found above " << fs::current_path();
    const rt::SceneDesc original = rt::load_scene(dir + "/../../../gltf/palette_scene.json");
    for (const char* file : {"palette_optimize.glb", "palette_optimize_nojoin.glb",
                             "../../../gltf/palette_optimize/palette_optimize.gltf"}) {
        SCOPED_TRACE(file);
        TempDir tmp;
        check_palette_scene(original, import(tmp, dir + "/" + file));
    }
}

#ifndef RT_NO_MESHOPT
namespace {

// A meshopt-compressed glTF: the compressed streams in buffer 0, the views on the fallback
// buffer 1, which has no uri (as glTF Transform writes them).
struct MeshoptFile : GltfFile {
    size_t fallback = 0;

    // `raw`, `count` elements of `stride` bytes, compressed by `mode`'s encoder; the view.
    int compressed(const std::vector<unsigned char>& raw, size_t count, size_t stride, const std::string& mode,
                   const std::string& filter = "NONE") {
        std::vector<unsigned char> enc;
        if (mode == "ATTRIBUTES") {
            enc.resize(meshopt_encodeVertexBufferBound(count, stride));
            enc.resize(meshopt_encodeVertexBuffer(enc.data(), enc.size(), raw.data(), count, stride));
        } else {
            std::vector<unsigned int> indices(count);
            unsigned int vertices = 0;
            for (size_t i = 0; i < count; ++i) {
                uint32_t x = 0;
                std::memcpy(&x, &raw[i * stride], stride);
                indices[i] = x;
                vertices = std::max(vertices, x + 1);
            }
            enc.resize(mode == "TRIANGLES" ? meshopt_encodeIndexBufferBound(count, vertices)
                                           : meshopt_encodeIndexSequenceBound(count, vertices));
            enc.resize(mode == "TRIANGLES"
                           ? meshopt_encodeIndexBuffer(enc.data(), enc.size(), indices.data(), count)
                           : meshopt_encodeIndexSequence(enc.data(), enc.size(), indices.data(), count));
        }
        bin.resize((bin.size() + 3) / 4 * 4);
        const size_t at = bin.size();
        bin.insert(bin.end(), enc.begin(), enc.end());
        json ext = {{"buffer", 0},          {"byteOffset", at}, {"byteLength", enc.size()},
                    {"byteStride", stride}, {"count", count},   {"mode", mode}};
        if (filter != "NONE") ext["filter"] = filter;
        json v = {{"buffer", 1},
                  {"byteOffset", fallback},
                  {"byteLength", count * stride},
                  {"extensions", {{"EXT_meshopt_compression", ext}}}};
        if (mode == "ATTRIBUTES") v["byteStride"] = stride;
        j["bufferViews"].push_back(v);
        fallback += (count * stride + 3) / 4 * 4;
        more_buffers = {
            {{"byteLength", fallback}, {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}}};
        j["extensionsUsed"] = j["extensionsRequired"] = {"EXT_meshopt_compression", "KHR_mesh_quantization"};
        return int(j["bufferViews"].size() - 1);
    }
    int accessor(int view, int component, size_t count, const char* type, bool normalized = false) {
        j["accessors"].push_back(
            {{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}});
        if (normalized) j["accessors"].back()["normalized"] = true;
        return int(j["accessors"].size() - 1);
    }
    // The quad: positions and 32-bit TRIANGLES indices; its mesh.
    int quad() {
        const int p = accessor(compressed(bytes_of(kQuad), 4, 12, "ATTRIBUTES"), 5126, 4, "VEC3");
        const int i = accessor(compressed(bytes_of(kQuadFaces), 6, 4, "TRIANGLES"), 5125, 6, "SCALAR");
        j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", i}}}}});
        return int(j["meshes"].size() - 1);
    }
};

}  // namespace

TEST(GltfMeshopt, EveryModeAndFilterDecodesToWhatWasEncoded) {
    TempDir tmp;
    MeshoptFile f;
    // The quad, with octahedral normals (all +z: a flat mesh, which garbage would not be).
    const int quad = f.quad();
    std::vector<float> up;
    for (int i = 0; i < 4; ++i) up.insert(up.end(), {0, 0, 1, 0});
    std::vector<unsigned char> oct(4 * 4);
    meshopt_encodeFilterOct(oct.data(), 4, 4, 8, up.data());
    f.j["meshes"][size_t(quad)]["primitives"][0]["attributes"]["NORMAL"] =
        f.accessor(f.compressed(oct, 4, 4, "ATTRIBUTES", "OCTAHEDRAL"), 5120, 4, "VEC3", true);
    f.node({{"mesh", quad}});
    // The quad again, its positions through the exponential filter, 16-bit INDICES.
    std::vector<unsigned char> exp(4 * 12);
    meshopt_encodeFilterExp(exp.data(), 4, 12, 24, kQuad.data());
    const std::vector<uint16_t> faces16(kQuadFaces.begin(), kQuadFaces.end());
    const int p = f.accessor(f.compressed(exp, 4, 12, "ATTRIBUTES", "EXPONENTIAL"), 5126, 4, "VEC3");
    const int i = f.accessor(f.compressed(bytes_of(faces16), 6, 2, "INDICES"), 5123, 6, "SCALAR");
    f.j["meshes"].push_back({{"primitives", {{{"attributes", {{"POSITION", p}}}, {"indices", i}}}}});
    // Two GPU instances of it, turned by quaternions through the quaternion filter: none,
    // and a quarter turn about z.
    const float s = float(std::sqrt(0.5));
    const std::vector<float> quats = {0, 0, 0, 1, 0, 0, s, s};
    std::vector<unsigned char> q(2 * 8);
    meshopt_encodeFilterQuat(q.data(), 2, 8, 16, quats.data());
    const int rotation = f.accessor(f.compressed(q, 2, 8, "ATTRIBUTES", "QUATERNION"), 5122, 2, "VEC4", true);
    f.j["extensionsUsed"].push_back("EXT_mesh_gpu_instancing");
    f.node({{"mesh", 1},
            {"translation", {0, 0, -5}},
            {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"ROTATION", rotation}}}}}}}});
    for (const bool glb : {false, true}) {
        SCOPED_TRACE(glb ? "glb" : "gltf");
        const Imported im = import(tmp, glb ? f.write_glb(tmp) : f.write(tmp));
        ASSERT_EQ(im.scene.meshes.size(), 2u);
        EXPECT_EQ(im.scene.meshes[0].shading, rt::ShadingMode::Flat);
        const auto tris = world_triangles(im.scene);
        ASSERT_EQ(tris.size(), 6u);
        // The first quad exactly; the instances at z -5, one of them turned (x, y) -> (-y, x).
        std::vector<std::array<double, 9>> want = kQuadTriangles;
        for (const auto& t : kQuadTriangles) {
            std::array<double, 9> a = t, b = t;
            for (size_t k = 0; k < 3; ++k) {
                a[3 * k + 2] = b[3 * k + 2] = -5;
                b[3 * k] = -t[3 * k + 1], b[3 * k + 1] = t[3 * k];
            }
            want.push_back(a);
            want.push_back(b);
        }
        std::sort(want.begin(), want.end());
        for (size_t t = 0; t < 6; ++t)
            for (size_t k = 0; k < 9; ++k) EXPECT_NEAR(tris[t][k], want[t][k], 1e-3) << t << " " << k;
    }
}

TEST(GltfMeshopt, TruncatedCorruptOrLyingStreamsAreOneLineNamingTheView) {
    TempDir tmp;
    MeshoptFile good;
    good.node({{"mesh", good.quad()}});
    const std::string at = "/bufferViews/0/extensions/EXT_meshopt_compression: ";
    auto ext = [](MeshoptFile& f) -> json& { return f.j["bufferViews"][0]["extensions"]["EXT_meshopt_compression"]; };
    struct Case {
        const char* name;
        void (*spoil)(MeshoptFile&, json&);
        const char* says;
    };
    const std::vector<Case> cases = {
        {"truncated", [](MeshoptFile&, json& e) { e["byteLength"] = e["byteLength"].get<size_t>() - 8; },
         "its ATTRIBUTES stream ("},
        {"corrupt", [](MeshoptFile& f, json&) { f.bin[0] = 0; },  // its header byte
         "does not decode: truncated or corrupt"},
        {"count", [](MeshoptFile&, json& e) { e["count"] = 5; },
         "count x byteStride must be the bufferView's byteLength"},
        {"mode", [](MeshoptFile&, json& e) { e["mode"] = "QUADS"; }, "mode must be ATTRIBUTES, TRIANGLES or INDICES"},
        {"stride", [](MeshoptFile&, json& e) { e["byteStride"] = 6; }, "ATTRIBUTES needs a byteStride of 4 to 256"},
        {"filter", [](MeshoptFile&, json& e) { e["filter"] = "QUATERNION"; },
         "filter QUATERNION does not take a byteStride of 12"},
        {"past", [](MeshoptFile&, json& e) { e["byteOffset"] = 1000; }, "run past the end of buffer 0"},
        {"ratio",
         [](MeshoptFile& f, json& e) {
             e["count"] = 100000;
             f.j["bufferViews"][0]["byteLength"] = 1200000;
         },
         "cannot hold 100000 elements of 12 bytes: it is corrupt"}};
    for (const Case& c : cases)
        for (const bool glb : {false, true}) {
            SCOPED_TRACE(std::string(c.name) + (glb ? " glb" : " gltf"));
            MeshoptFile f = good;
            c.spoil(f, ext(f));
            const std::string name = std::string(c.name) + (glb ? ".glb" : ".gltf");
            const std::string e = refused(tmp, glb ? f.write_glb(tmp, name) : f.write(tmp, name));
            EXPECT_TRUE(contains(e, name + ": " + at)) << e;
            EXPECT_TRUE(contains(e, c.says)) << e;
        }
    // A view into the fallback without compression reads bytes that are nowhere.
    MeshoptFile plain = good;
    plain.j["bufferViews"][1].erase("extensions");
    const std::string e = refused(tmp, plain.write(tmp, "plain.gltf"));
    EXPECT_TRUE(contains(e, "/bufferViews/1: its buffer 1 is a fallback of EXT_meshopt_compression without bytes"))
        << e;
}
#else
TEST(GltfMeshopt, ABuildWithoutTheLibraryRefusesTheFileNamingTheExtension) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    f.j["extensionsRequired"] = {"EXT_meshopt_compression"};
    const std::string e = refused(tmp, f.write(tmp, "meshopt.gltf"));
    EXPECT_TRUE(contains(e,
                         "/extensionsRequired/0: the file requires extension EXT_meshopt_compression, which this "
                         "build of rtconvert does not read (it was made without libmeshoptimizer-dev)"))
        << e;
}
#endif

#ifndef RT_NO_DRACO
namespace {

// A glTF of one Draco-compressed quad (the stream in buffer 0, its accessors without
// bufferViews, counts as the stream holds), encoded sequentially without quantisation
// (lossless) or by edgebreaker with 14-bit positions (glTF Transform's default).
GltfFile draco_quad(bool quantised) {
    draco::TriangleSoupMeshBuilder builder;
    builder.Start(2);
    const int pos = builder.AddAttribute(draco::GeometryAttribute::POSITION, 3, draco::DT_FLOAT32);
    for (size_t t = 0; t < 2; ++t)
        builder.SetAttributeValuesForFace(pos, draco::FaceIndex(uint32_t(t)), &kQuad[3 * kQuadFaces[3 * t]],
                                          &kQuad[3 * kQuadFaces[3 * t + 1]], &kQuad[3 * kQuadFaces[3 * t + 2]]);
    std::unique_ptr<draco::Mesh> mesh = builder.Finalize();
    draco::Encoder encoder;
    if (quantised) {
        encoder.SetAttributeQuantization(draco::GeometryAttribute::POSITION, 14);
    } else {
        encoder.SetEncodingMethod(draco::MESH_SEQUENTIAL_ENCODING);
    }
    draco::EncoderBuffer out;
    EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
    // The counts the stream holds, as a writer records them.
    draco::DecoderBuffer in;
    in.Init(out.data(), out.size());
    std::unique_ptr<draco::Mesh> back = draco::Decoder().DecodeMeshFromBuffer(&in).value();
    GltfFile f;
    f.view(out.data(), out.size());
    f.j["accessors"] = {{{"componentType", 5125}, {"count", back->num_faces() * 3}, {"type", "SCALAR"}},
                        {{"componentType", 5126}, {"count", back->num_points()}, {"type", "VEC3"}}};
    const json ext = {
        {"bufferView", 0},
        {"attributes", {{"POSITION", back->GetNamedAttribute(draco::GeometryAttribute::POSITION)->unique_id()}}}};
    f.j["meshes"] = {{{"primitives",
                       {{{"attributes", {{"POSITION", 1}}},
                         {"indices", 0},
                         {"extensions", {{"KHR_draco_mesh_compression", ext}}}}}}}};
    f.j["extensionsUsed"] = f.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    f.node({{"mesh", 0}});
    return f;
}

}  // namespace

TEST(GltfDraco, FacesAndPositionsDecodeToWhatWasEncoded) {
    TempDir tmp;
    for (const bool quantised : {false, true})
        for (const bool glb : {false, true}) {
            SCOPED_TRACE(std::string(quantised ? "edgebreaker, 14 bits" : "sequential") + (glb ? " glb" : " gltf"));
            GltfFile f = draco_quad(quantised);
            const auto tris = world_triangles(import(tmp, glb ? f.write_glb(tmp) : f.write(tmp)).scene);
            ASSERT_EQ(tris.size(), 2u);
            // Lossless, or within 14 bits of the extent 2 (a triangle's corners may start
            // anywhere: compared as sets of corners).
            const Surfaces s = surfaces(tris), want = surfaces(kQuadTriangles);
            for (size_t k = 0; k < 3; ++k) {
                EXPECT_NEAR(s.lo[k], want.lo[k], quantised ? 2.0 / (1 << 13) : 0);
                EXPECT_NEAR(s.hi[k], want.hi[k], quantised ? 2.0 / (1 << 13) : 0);
            }
            EXPECT_NEAR(s.area, want.area, quantised ? 1e-3 : 0);
        }
}

TEST(GltfDraco, TruncatedCorruptOrLyingStreamsAreOneLineNamingThePrimitive) {
    TempDir tmp;
    const std::string at = "/meshes/0/primitives/0/extensions/KHR_draco_mesh_compression: ";
    struct Case {
        const char* name;
        void (*spoil)(GltfFile&);
        const char* says;
    };
    const std::vector<Case> cases = {
        {"truncated", [](GltfFile& f) { f.j["bufferViews"][0]["byteLength"] = f.bin.size() / 2; },
         "does not decode: truncated or corrupt (Draco: "},
        {"corrupt", [](GltfFile& f) { f.bin[0] = 'X'; },  // its magic DRACO
         "does not decode: truncated or corrupt (Draco: "},
        {"count", [](GltfFile& f) { f.j["accessors"][1]["count"] = f.j["accessors"][1]["count"].get<int>() + 1; },
         "accessor 1 has count"},
        {"attribute",
         [](GltfFile& f) {
             f.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["attributes"]["POSITION"] =
                 7;
         },
         "attributes/POSITION: the stream has no attribute 7"},
        {"view",
         [](GltfFile& f) {
             f.j["meshes"][0]["primitives"][0]["extensions"]["KHR_draco_mesh_compression"]["bufferView"] = 9;
         },
         "bufferView 9 does not exist"}};
    for (const Case& c : cases)
        for (const bool glb : {false, true}) {
            SCOPED_TRACE(std::string(c.name) + (glb ? " glb" : " gltf"));
            GltfFile f = draco_quad(true);
            c.spoil(f);
            const std::string name = std::string(c.name) + (glb ? ".glb" : ".gltf");
            const std::string e = refused(tmp, glb ? f.write_glb(tmp, name) : f.write(tmp, name));
            EXPECT_TRUE(contains(e, name + ": " + at)) << e;
            EXPECT_TRUE(contains(e, c.says)) << e;
        }
}
#else
TEST(GltfDraco, ABuildWithoutTheLibraryRefusesTheFileNamingTheExtension) {
    TempDir tmp;
    GltfFile f;
    f.node({{"mesh", f.mesh(kTriangle, {0, 1, 2})}});
    f.j["extensionsRequired"] = {"KHR_draco_mesh_compression"};
    const std::string e = refused(tmp, f.write(tmp, "draco.gltf"));
    EXPECT_TRUE(contains(e,
                         "/extensionsRequired/0: the file requires extension KHR_draco_mesh_compression, which "
                         "this build of rtconvert does not read (it was made without libdraco-dev)"))
        << e;
}
#endif

#endif
