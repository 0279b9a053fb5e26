// Shared by the glTF tests (tests/test_convert_gltf*.cpp): glTF files written by hand, and
// their import read back.
#pragma once
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "convert_test_support.h"
#include "rt/convert/convert.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/scene_desc.h"
#include "rt/loader/shape_descs.h"
#include "test_support.h"

namespace convert_test {

using nlohmann::json;

// ---- glTF files written by hand ------------------------------------------------------------

// A buffer of floats then uint32 indices, and a glTF naming it "data.bin".
struct GltfFile {
    std::vector<unsigned char> bin;
    json j = {{"asset", {{"version", "2.0"}}},
              {"buffers", json::array()},
              {"bufferViews", json::array()},
              {"accessors", json::array()},
              {"meshes", json::array()},
              {"nodes", json::array()},
              {"scenes", {{{"nodes", json::array()}}}}};

    int view(const void* data, size_t bytes) {
        const size_t offset = bin.size();
        bin.insert(bin.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + bytes);
        j["bufferViews"].push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", bytes}});
        return int(j["bufferViews"].size() - 1);
    }
    int positions(const std::vector<float>& p) {
        j["accessors"].push_back({{"bufferView", view(p.data(), p.size() * 4)},
                                  {"componentType", 5126},
                                  {"count", p.size() / 3},
                                  {"type", "VEC3"}});
        return int(j["accessors"].size() - 1);
    }
    int indices(const std::vector<uint32_t>& i) {
        j["accessors"].push_back({{"bufferView", view(i.data(), i.size() * 4)},
                                  {"componentType", 5125},
                                  {"count", i.size()},
                                  {"type", "SCALAR"}});
        return int(j["accessors"].size() - 1);
    }
    // A mesh of one triangle primitive; its index.
    int mesh(const std::vector<float>& p, const std::vector<uint32_t>& i, json extra = json::object()) {
        json prim = {{"attributes", {{"POSITION", positions(p)}}}, {"indices", indices(i)}};
        prim.update(extra);
        j["meshes"].push_back({{"primitives", {prim}}});
        return int(j["meshes"].size() - 1);
    }
    // A node; a root of the scene unless it is to be someone's child.
    int node(json n, bool root = true) {
        j["nodes"].push_back(n);
        const int index = int(j["nodes"].size() - 1);
        if (root) j["scenes"][0]["nodes"].push_back(index);
        return index;
    }
    // Buffers after buffer 0 (a meshopt fallback, say).
    json more_buffers = json::array();

    std::string write(const TempDir& tmp, const std::string& name = "in.gltf") {
        j["buffers"] = {{{"uri", "data.bin"}, {"byteLength", bin.size()}}};
        for (const json& b : more_buffers) j["buffers"].push_back(b);
        std::ofstream(tmp / "data.bin", std::ios::binary)
            .write(reinterpret_cast<const char*>(bin.data()), long(bin.size()));
        std::ofstream(tmp / name) << j.dump(1);
        return tmp / name;
    }
    // The same as one .glb: buffer 0 its BIN chunk.
    std::string write_glb(const TempDir& tmp, const std::string& name = "in.glb") {
        j["buffers"] = {{{"byteLength", bin.size()}}};
        for (const json& b : more_buffers) j["buffers"].push_back(b);
        std::string text = j.dump();
        text.append((4 - text.size() % 4) % 4, ' ');
        std::string chunk(bin.begin(), bin.end());
        chunk.append((4 - chunk.size() % 4) % 4, '\0');
        std::string out = "glTF";
        auto u32 = [&](size_t v) {
            const uint32_t x = uint32_t(v);
            out.append(reinterpret_cast<const char*>(&x), 4);
        };
        u32(2);
        u32(12 + 8 + text.size() + 8 + chunk.size());
        u32(text.size());
        out += "JSON" + text;
        u32(chunk.size());
        out += std::string("BIN\0", 4) + chunk;
        std::ofstream(tmp / name, std::ios::binary) << out;
        return tmp / name;
    }
};

inline const std::vector<float> kTriangle = {0, 0, 0, 1, 0, 0, 0, 1, 0};

struct Imported {
    rt::ConvertResult result;
    rt::SceneDesc scene;
    json tree;
};

inline Imported import(const TempDir& tmp, const std::string& gltf, rt::ConvertOptions o = {}) {
    Imported im;
    im.result = rt::convert_file(gltf, tmp / "out.json", o);
    im.scene = rt::load_scene(tmp / "out.json");
    std::ifstream in(tmp / "out.json");
    im.tree = json::parse(in);
    return im;
}

// Every triangle of the scene's meshes and instances in world space, each as its three
// corners (x y z, 9 numbers), the list sorted: the same for the same surfaces, whatever the
// order a writer put them in.
inline std::vector<std::array<double, 9>> world_triangles(const rt::SceneDesc& s) {
    std::vector<std::array<double, 9>> out;
    auto add = [&](const rt::MeshDesc& m, const rt::Affine& to_world) {
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3) {
            std::array<double, 9> tri;
            for (size_t k = 0; k < 3; ++k) {
                const rt::Vec3 p = to_world.point(m.positions[m.indices[t + k]]);
                tri[3 * k] = double(p.x), tri[3 * k + 1] = double(p.y), tri[3 * k + 2] = double(p.z);
            }
            out.push_back(tri);
        }
    };
    for (const rt::MeshDesc& m : s.meshes)
        if (!m.instanced) add(m, m.transform);  // else drawn by an InstanceDesc of its own
    for (const rt::InstanceDesc& i : s.all<rt::InstanceDesc>()) add(s.meshes[i.mesh], i.transform);
    std::sort(out.begin(), out.end());
    return out;
}

// The error of converting `in`, with the checks every error line passes: one line naming
// the file, nothing written.
inline std::string refused(const TempDir& tmp, const std::string& in) {
    const std::string e = error_of(in, tmp / "bad.json");
    EXPECT_FALSE(e.empty());
    EXPECT_EQ(e.find('\n'), std::string::npos) << e;
    EXPECT_TRUE(contains(e, std::filesystem::path(in).filename().string())) << e;
    EXPECT_FALSE(std::filesystem::exists(tmp / "bad.json"));
    EXPECT_FALSE(std::filesystem::exists(tmp / "bad_1.ply"));
    return e;
}

}  // namespace convert_test
