// glTF materials -> the course's (gltf_import.h, docs/gltf.md).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "gltf_extras.h"
#include "gltf_import.h"
#include "rt/convert/gltf_materials.h"

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using Warn = std::function<void(const std::string&)>;

// The material's PBR factors; what the format lacks is warned of, with `mp` its place.
PbrMaterial pbr(const tinygltf::Material& m, const std::string& mp, const Warn& warn) {
    PbrMaterial p;
    const auto& pbr = m.pbrMetallicRoughness;
    for (size_t k = 0; k < 3 && k < pbr.baseColorFactor.size(); ++k) p.base[k] = pbr.baseColorFactor[k];
    p.metallic = pbr.metallicFactor;
    p.roughness = pbr.roughnessFactor;
    auto ext = [&](const char* name) {
        const auto it = m.extensions.find(name);
        return it == m.extensions.end() ? json() : rtgltf::to_json(it->second);
    };
    const json t = ext("KHR_materials_transmission"), i = ext("KHR_materials_ior"), v = ext("KHR_materials_volume");
    if (t.is_object()) p.transmission = t.value("transmissionFactor", 0.0);
    if (i.is_object()) p.ior = i.value("ior", 1.5);
    if (v.is_object()) {
        p.attenuation_distance = v.value("attenuationDistance", HUGE_VAL);
        V3 a;
        if (vec3(v.value("attenuationColor", json()), a)) std::copy(a.begin(), a.end(), p.attenuation);
    }
    std::vector<std::string> textures;
    if (pbr.baseColorTexture.index >= 0) textures.push_back("base colour");
    if (pbr.metallicRoughnessTexture.index >= 0) textures.push_back("metallic-roughness");
    if (m.normalTexture.index >= 0) textures.push_back("normal");
    if (m.emissiveTexture.index >= 0) textures.push_back("emissive");
    if (m.occlusionTexture.index >= 0) textures.push_back("occlusion");
    if (!textures.empty()) {
        std::string list;
        for (const std::string& s : textures) list += (list.empty() ? "" : ", ") + s;
        warn(mp + ": textures are not in the format (" + list + "): its factors are used");
    }
    if (m.emissiveFactor.size() == 3 && (m.emissiveFactor[0] > 0 || m.emissiveFactor[1] > 0 || m.emissiveFactor[2] > 0))
        warn(mp + ": emission is not in the format: left out");
    if (m.alphaMode == "BLEND" || (pbr.baseColorFactor.size() == 4 && pbr.baseColorFactor[3] < 1))
        warn(mp + ": alpha is not in the format (glass is KHR_materials_transmission): opaque");
    return p;
}

}  // namespace

ojson import_materials(const tinygltf::Model& model, const std::string& path, bool with_default, SceneImport& out) {
    const Warn warn = [&](const std::string& what) { out.warnings.push_back(path + ": " + what); };
    ojson list = ojson::array();
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& m = model.materials[i];
        const std::string mp = "/materials/" + std::to_string(i);
        const PbrMaterial p = pbr(m, mp, warn);
        MaterialDesc exact;
        const bool from_extras = material_from_extras(ours_in(m.extras), exact) && same_pbr(pbr_of(exact), p);
        const MaterialDesc d = from_extras ? exact : material_of(p);
        ojson entry = material_entry(d, i + 1);
        // Roughness, which glTF has no place for: kept through edits of the PBR values.
        read_extras(kMaterialExtras, ours_in(m.extras), path + ": " + mp + "/extras/" + kGltfExtrasKey, false, entry);
        list.push_back(std::move(entry));
        out.notes.push_back("material " + std::to_string(i + 1) + " (" + (m.name.empty() ? "unnamed" : m.name) +
                            "): " + material_type_name(d.type) +
                            (from_extras ? ", the exported course values" : ", from its PBR values"));
    }
    if (with_default) {
        list.push_back(default_material(model.materials.size() + 1));
        out.notes.push_back("material " + std::to_string(model.materials.size() + 1) +
                            ": default grey, for primitives without a material");
    }
    return list;
}

#endif  // RT_NO_GLTF
}  // namespace rt
