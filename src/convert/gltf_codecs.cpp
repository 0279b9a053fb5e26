// The extensions rtconvert reads, and the steps around tinygltf that read compressed files
// (gltf_codecs.h, docs/gltf.md).
#include "gltf_codecs.h"

#include <cmath>
#include <cstdint>
#include <set>

namespace rtgltf {
#ifndef RT_NO_GLTF
namespace {

using json = nlohmann::json;

constexpr const char* kMeshopt = "EXT_meshopt_compression";
constexpr const char* kDraco = "KHR_draco_mesh_compression";

// What the import reads (quantised attributes, GPU instances, lights, the materials'
// extensions), or may leave aside without changing what a scene shows.
const std::set<std::string> kRead = {
    "KHR_mesh_quantization", "EXT_mesh_gpu_instancing",         "KHR_lights_punctual",  "KHR_materials_transmission",
    "KHR_materials_ior",     "KHR_materials_emissive_strength", "KHR_materials_volume", "KHR_texture_transform"};

// The codecs, with the Debian package a build needs for each.
#ifdef RT_NO_MESHOPT
constexpr bool kHaveMeshopt = false;
#else
constexpr bool kHaveMeshopt = true;
#endif
#ifdef RT_NO_DRACO
constexpr bool kHaveDraco = false;
#else
constexpr bool kHaveDraco = true;
#endif

std::string not_read(const std::string& e) {
    if (e == kMeshopt) return "this build of rtconvert does not read (it was made without libmeshoptimizer-dev)";
    if (e == kDraco) return "this build of rtconvert does not read (it was made without libdraco-dev)";
    return "rtconvert does not read";
}

const json* member(const json& j, const char* key) { return j.is_object() && j.contains(key) ? &j[key] : nullptr; }

}  // namespace

bool understood(const std::string& e) {
    return kRead.count(e) || (e == kMeshopt && kHaveMeshopt) || (e == kDraco && kHaveDraco);
}

bool prepare(json& j, const std::string& path, Compressed& out, std::vector<std::string>& warnings) {
    if (!j.is_object()) return false;
    if (const json* required = member(j, "extensionsRequired"); required && required->is_array())
        for (size_t i = 0; i < required->size(); ++i)
            if ((*required)[i].is_string() && !understood((*required)[i].get<std::string>()))
                throw Error(path + ": /extensionsRequired/" + std::to_string(i) + ": the file requires extension " +
                            (*required)[i].get<std::string>() + ", which " +
                            not_read((*required)[i].get<std::string>()));
    if (const json* used = member(j, "extensionsUsed"); used && used->is_array())
        for (const json& e : *used)
            if (e.is_string() && !understood(e.get<std::string>()))
                warnings.push_back(path + ": extension " + e.get<std::string>() +
                                   " is not read: what it adds is left out");
    bool changed = false;
    // A fallback buffer without a uri has no bytes anywhere (its bufferViews are decoded).
    if (json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr; kHaveMeshopt && buffers && buffers->is_array())
        for (size_t i = 0; i < buffers->size(); ++i) {
            json& b = (*buffers)[i];
            const json* ext = member(b, "extensions");
            const json* ours = ext ? member(*ext, kMeshopt) : nullptr;
            if (b.contains("uri") || !ours || ours->value("fallback", false) != true) continue;
            out.fallbacks[int(i)] =
                b.value("byteLength", json(0)).is_number_unsigned() ? b["byteLength"].get<size_t>() : 0;
            b["uri"] = "data:application/octet-stream;base64,AA==";
            b["byteLength"] = 1;
            changed = true;
        }
    // A Draco primitive's indices accessor has no bufferView until the decoder makes one.
    if (json* meshes = j.contains("meshes") ? &j["meshes"] : nullptr; kHaveDraco && meshes && meshes->is_array())
        for (size_t m = 0; m < meshes->size(); ++m) {
            json* prims =
                (*meshes)[m].is_object() && (*meshes)[m].contains("primitives") ? &(*meshes)[m]["primitives"] : nullptr;
            for (size_t p = 0; prims && prims->is_array() && p < prims->size(); ++p) {
                json& prim = (*prims)[p];
                const json* ext = member(prim, "extensions");
                if (!ext || !member(*ext, kDraco) || !prim.contains("indices") || !prim["indices"].is_number_integer())
                    continue;
                out.draco_indices[{int(m), int(p)}] = prim["indices"].get<int>();
                prim.erase("indices");
                changed = true;
            }
        }
    return changed;
}

void decode(tinygltf::Model& model, const Compressed& set_aside, const std::string& path) {
    for (const auto& [b, length] : set_aside.fallbacks)
        if (size_t(b) < model.buffers.size()) model.buffers[size_t(b)].data.clear();
    for (const auto& [where, indices] : set_aside.draco_indices)
        if (size_t(where.first) < model.meshes.size() &&
            size_t(where.second) < model.meshes[size_t(where.first)].primitives.size())
            model.meshes[size_t(where.first)].primitives[size_t(where.second)].indices = indices;
    const size_t views = model.bufferViews.size();  // the decoders append theirs
#ifndef RT_NO_MESHOPT
    decode_meshopt(model, path);
#endif
#ifndef RT_NO_DRACO
    decode_draco(model, path);
#endif
    for (size_t i = 0; i < views; ++i)
        if (const auto it = set_aside.fallbacks.find(model.bufferViews[i].buffer); it != set_aside.fallbacks.end())
            throw Error(path + ": /bufferViews/" + std::to_string(i) + ": its buffer " + std::to_string(it->first) +
                        " is a fallback of " + kMeshopt + " without bytes, and the view is not compressed");
}

bool whole_number(const json& j, size_t& out) {
    if (j.is_number_integer() && j.get<int64_t>() >= 0) {
        out = size_t(j.get<int64_t>());
        return true;
    }
    if (!j.is_number_float() || !(j.get<double>() >= 0 && j.get<double>() < 9e15) ||
        j.get<double>() != std::floor(j.get<double>()))
        return false;
    out = size_t(j.get<double>());
    return true;
}

int append_view(tinygltf::Model& model, std::vector<unsigned char> bytes, size_t stride) {
    tinygltf::BufferView v;
    v.buffer = int(model.buffers.size());
    v.byteOffset = 0;
    v.byteLength = bytes.size();
    v.byteStride = stride;
    model.buffers.emplace_back();
    model.buffers.back().data = std::move(bytes);
    model.bufferViews.push_back(std::move(v));
    return int(model.bufferViews.size() - 1);
}

const unsigned char* bytes_of(const tinygltf::Model& model, int buffer, size_t offset, size_t length,
                              const std::string& where, const std::string& path) {
    if (buffer < 0 || size_t(buffer) >= model.buffers.size())
        throw Error(path + ": " + where + ": buffer " + std::to_string(buffer) + " does not exist");
    const std::vector<unsigned char>& data = model.buffers[size_t(buffer)].data;
    if (offset > data.size() || length > data.size() - offset)
        throw Error(path + ": " + where + ": bytes " + std::to_string(offset) + " to " +
                    std::to_string(offset + length) + " run past the end of buffer " + std::to_string(buffer) + " (" +
                    std::to_string(data.size()) + " bytes)");
    return data.data() + offset;
}
#endif  // RT_NO_GLTF

}  // namespace rtgltf
