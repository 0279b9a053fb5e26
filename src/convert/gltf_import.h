// Internal: what the glTF import's two files share (gltf_import.cpp: nodes, meshes,
// cameras, lights; gltf_import_materials.cpp: materials): the reading of extras, and the
// materials' import.
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <string>
#include <vector>

#include "gltf_io.h"
#include "rt/loader/scene_desc.h"
#include "scene_import.h"

namespace rt {

// The JSON the import writes (in the course's key order) and reads, and a point in double.
using ojson = nlohmann::ordered_json;
using json = nlohmann::json;
using V3 = std::array<double, 3>;

// Extras are read only when they hold what the loader accepts (numbers within +-1e30,
// colours not negative); `out` is left alone otherwise.
inline bool number(const json& j, double& out, double lo = -kMaxMagnitude, double hi = kMaxMagnitude) {
    if (!j.is_number() || !(j.get<double>() >= lo && j.get<double>() <= hi)) return false;
    out = j.get<double>();
    return true;
}
inline bool vec3(const json& j, V3& out, double lo = -kMaxMagnitude) {
    V3 v;
    if (!j.is_array() || j.size() != 3) return false;
    for (size_t i = 0; i < 3; ++i)
        if (!number(j[i], v[i], lo)) return false;
    out = v;
    return true;
}
inline bool colour(const json& j, V3& out) { return vec3(j, out, 0); }

#ifndef RT_NO_GLTF
// The course's materials of the model's materials (docs/gltf.md, rt/convert/gltf_materials.h):
// each from the export's exact values while its extras still agree with its PBR factors,
// else by the table; then, with `with_default` (for primitives without one), a default
// grey. Warnings of what the format lacks (textures, emission, alpha) and a note per
// material go to `out`; `path` names the file in them.
// Then one per palette texel of `texels` (gltf_palette.h), with the _id M + 2 + its index
// (M materials in the file): the exported material of the scene's extras ("materials") or
// the glTF material's own whose PBR values the texel holds, else the table's material of
// the glTF material's factors times the texel. `scene_extras`: the "ceng795" extras of the
// scene converted, `scene_at` its pointer ("/scenes/0").
struct PaletteTexel;
// The materials the export kept in the scene's "ceng795" extras ("materials"), in order.
std::vector<json> exported_materials(const json& scene_extras);
// The materials of `listed` (the exported ones, then the texel's glTF material's own
// extras) whose PBR values the table maps to the texel's (to 1 level of its 8 bits) and to
// the material's other factors: the closest, several where they tie (materials that differ
// only where glTF has no place, as AmbientReflectance), in the order of `listed`.
std::vector<int> texel_matches(const tinygltf::Model& model, const PaletteTexel& t, const std::vector<json>& listed);
ojson import_materials(const tinygltf::Model& model, const std::string& path, bool with_default,
                       const std::vector<PaletteTexel>& texels, const json& scene_extras, const std::string& scene_at,
                       SceneImport& out);
#endif

}  // namespace rt
