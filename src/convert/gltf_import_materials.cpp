// glTF materials -> the course's (gltf_import.h, docs/gltf.md).
#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "gltf_extras.h"
#include "gltf_import.h"
#include "gltf_palette.h"
#include "rt/convert/gltf_materials.h"

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using Warn = std::function<void(const std::string&)>;

// The material's PBR factors; what the format lacks is warned of, with `mp` its place
// (its base colour and metallic-roughness textures not where they are `palette`s).
PbrMaterial pbr(const tinygltf::Material& m, const std::string& mp, const Warn& warn, bool palette = false) {
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
    if (pbr.baseColorTexture.index >= 0 && !palette) textures.push_back("base colour");
    if (pbr.metallicRoughnessTexture.index >= 0 && !palette) textures.push_back("metallic-roughness");
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

// The PBR values of a material's `factors` times its palette texel's.
PbrMaterial texel_pbr(PbrMaterial p, const PaletteTexel& t) {
    for (size_t k = 0; k < 3; ++k)
        if (t.base[k] >= 0) p.base[k] *= srgb_to_linear(t.base[k]);
    if (t.roughness >= 0) p.roughness *= t.roughness / 255.0;
    if (t.metallic >= 0) p.metallic *= t.metallic / 255.0;
    return p;
}

}  // namespace

std::vector<int> texel_matches(const tinygltf::Model& model, const PaletteTexel& t, const std::vector<json>& listed) {
    const PbrMaterial factors = pbr(model.materials[size_t(t.material)], "", [](const std::string&) {});
    const PbrMaterial p = texel_pbr(factors, t);
    // Whether `want` (linear, before the factor) is what the 8-bit `texel` holds.
    auto holds = [](double want, double factor, int texel, bool srgb) {
        if (texel < 0) return true;
        if (!(factor > 0)) return std::fabs(want) <= 1e-4;
        const double v = want / factor;
        return std::fabs((srgb ? linear_to_srgb(v) : v) * 255 - texel) <= 1;
    };
    double best = HUGE_VAL;
    std::vector<int> out;
    for (size_t i = 0; i < listed.size(); ++i) {
        MaterialDesc d;
        if (!material_from_extras(listed[i], d)) continue;
        PbrMaterial q = pbr_of(d);
        bool ok = holds(q.roughness, factors.roughness, t.roughness, false) &&
                  holds(q.metallic, factors.metallic, t.metallic, false);
        double distance = 0;
        for (size_t k = 0; k < 3; ++k) {
            ok = ok && holds(q.base[k], factors.base[k], t.base[k], true);
            distance += std::fabs(q.base[k] - p.base[k]);
        }
        if (!ok) continue;
        // The texel's values as the listed material's, the rest compared as any material's.
        if (t.base[0] >= 0) std::copy(p.base, p.base + 3, q.base);
        if (t.roughness >= 0) q.roughness = p.roughness;
        if (t.metallic >= 0) q.metallic = p.metallic;
        if (!same_pbr(q, p) || distance > best) continue;
        if (distance < best) out.clear();
        best = distance;
        out.push_back(int(i));
    }
    return out;
}

namespace {}  // namespace

std::vector<json> exported_materials(const json& scene_extras) {
    std::vector<json> out;
    if (scene_extras.is_object() && scene_extras.value("materials", json()).is_array())
        for (const json& j : scene_extras["materials"]) out.push_back(j);
    return out;
}

ojson import_materials(const tinygltf::Model& model, const std::string& path, bool with_default,
                       const std::vector<PaletteTexel>& texels, const json& scene_extras, const std::string& scene_at,
                       SceneImport& out) {
    const Warn warn = [&](const std::string& what) { out.warnings.push_back(path + ": " + what); };
    ojson list = ojson::array();
    for (size_t i = 0; i < model.materials.size(); ++i) {
        const tinygltf::Material& m = model.materials[i];
        const std::string mp = "/materials/" + std::to_string(i);
        const bool palette =
            std::any_of(texels.begin(), texels.end(), [&](const PaletteTexel& t) { return size_t(t.material) == i; });
        const PbrMaterial p = pbr(m, mp, warn, palette);
        MaterialDesc exact;
        const bool from_extras = material_from_extras(ours_in(m.extras), exact) && same_pbr(pbr_of(exact), p);
        const MaterialDesc d = from_extras ? exact : material_of(p);
        ojson entry = material_entry(d, i + 1);
        // Roughness, which glTF has no place for: kept through edits of the PBR values.
        read_extras(kMaterialExtras, ours_in(m.extras), path + ": " + mp + "/extras/" + kGltfExtrasKey, false, entry);
        list.push_back(std::move(entry));
        out.notes.push_back("material " + std::to_string(i + 1) + " (" + (m.name.empty() ? "unnamed" : m.name) +
                            "): " + material_type_name(d.type) +
                            (from_extras ? ", the exported course values" : ", from its PBR values") +
                            (palette ? "; its textures a palette: a material per texel, below" : ""));
    }
    if (with_default) {
        list.push_back(default_material(model.materials.size() + 1));
        out.notes.push_back("material " + std::to_string(model.materials.size() + 1) +
                            ": default grey, for primitives without a material");
    }
    const std::vector<json> exported = exported_materials(scene_extras);
    const Warn quiet = [](const std::string&) {};  // said of the material already
    for (size_t k = 0; k < texels.size(); ++k) {
        const PaletteTexel& t = texels[k];
        const tinygltf::Material& m = model.materials[size_t(t.material)];
        std::vector<json> listed = exported;
        listed.push_back(ours_in(m.extras));
        const std::vector<int> matches = texel_matches(model, t, listed);
        const int found = t.listed >= 0 ? t.listed : matches.empty() ? -1 : matches[0];
        MaterialDesc d;
        if (found < 0 || !material_from_extras(listed[size_t(found)], d))
            d = material_of(texel_pbr(pbr(m, "", quiet), t));
        const bool from_extras = found >= 0;
        const size_t id = model.materials.size() + 2 + k;
        ojson entry = material_entry(d, id);
        if (from_extras)  // its Roughness too, which no PBR value holds
            read_extras(kMaterialExtras, listed[size_t(found)],
                        path + ": " +
                            (size_t(found) < exported.size()
                                 ? scene_at + "/extras/" + kGltfExtrasKey + "/materials/" + std::to_string(found)
                                 : "/materials/" + std::to_string(t.material) + "/extras/" + kGltfExtrasKey),
                        false, entry);
        list.push_back(std::move(entry));
        out.notes.push_back("material " + std::to_string(id) + " (" + (m.name.empty() ? "unnamed" : m.name) +
                            ", a palette texel): " + material_type_name(d.type) +
                            (from_extras ? ", the exported course values" : ", from its PBR values and the texel"));
    }
    return list;
}

#endif  // RT_NO_GLTF
}  // namespace rt
