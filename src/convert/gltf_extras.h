// Internal: the course's values that glTF has no place for at all (assignment 3: a camera's
// samples and lens, an area light, an object's MotionBlur, a material's Roughness), kept in
// "ceng795" extras (docs/gltf.md). One table per element, for both directions: the export
// writes each field from the scene's desc, the import checks each as the loader would
// (a bad value is an error naming it) and writes it under the course's key.
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <cstddef>
#include <string>

#include "rt/loader/scene_desc.h"

namespace rt {

// What a value must be: the loader's check of its key.
enum class ExtraValue {
    Samples,      // NumSamples: a whole number from 1 to kMaxSamples
    Positive,     // a number > 0
    NonNegative,  // a number >= 0
    Vector,       // three numbers
    Direction,    // three numbers, not all 0
    Colour,       // three numbers >= 0
};

template <class Desc>
struct ExtraField {
    const char* key;         // in the element's "ceng795" extras
    const char* course_key;  // in the scene file
    ExtraValue value;
    // The desc's value as the extras hold it; null when the scene file has none (the key is
    // left out, and the import writes none).
    nlohmann::json (*of)(const Desc&);
};

// On the glTF camera; on an area light's node (its "areaLight" object); on the node that
// shows an object (a mesh, triangle, instance or sphere: its MotionBlur); on the material.
extern const std::array<ExtraField<CameraDesc>, 3> kCameraExtras;
extern const std::array<ExtraField<AreaLightDesc>, 4> kAreaLightExtras;
extern const std::array<ExtraField<Vec3>, 1> kMotionExtras;
extern const std::array<ExtraField<MaterialDesc>, 1> kMaterialExtras;

// Export: the fields of `d` that have a value, as an object (empty when none has).
template <class Desc, size_t N>
nlohmann::json extras_of(const std::array<ExtraField<Desc>, N>& fields, const Desc& d) {
    nlohmann::json out = nlohmann::json::object();
    for (const ExtraField<Desc>& f : fields)
        if (nlohmann::json v = f.of(d); !v.is_null()) out[f.key] = std::move(v);
    return out;
}

// Import, one field: the value `extras` holds under `key`, checked, as the course's text
// ("1 2 3") in `entry` under `course_key`. Throws InputError "<where>/<key>: <what>" for a
// bad value, and "<where>: has no <key>" when `required` and it is absent. `where` names
// the file and the extras object: "in.gltf: /cameras/0/extras/ceng795".
void read_extra(const char* key, const char* course_key, ExtraValue value, const nlohmann::json& extras,
                const std::string& where, bool required, nlohmann::ordered_json& entry);

// Import, a table: every field of it that `extras` holds (all of them when `required`).
template <class Desc, size_t N>
void read_extras(const std::array<ExtraField<Desc>, N>& fields, const nlohmann::json& extras, const std::string& where,
                 bool required, nlohmann::ordered_json& entry) {
    for (const ExtraField<Desc>& f : fields) read_extra(f.key, f.course_key, f.value, extras, where, required, entry);
}

}  // namespace rt
