// The one table between the course's materials and glTF's physically based
// ones (pbrMetallicRoughness, KHR_materials_transmission, _ior, _volume), used by the
// export (MaterialDesc -> glTF) and the import (glTF -> MaterialDesc). docs/gltf.md
// gives the table and its reasons.
#pragma once
#include <nlohmann/json.hpp>

#include <limits>
#include <string>

#include "rt/materials/materials.h"

namespace rt {

// What glTF says of a material, as far as the course's format can use it.
struct PbrMaterial {
    double base[3] = {1, 1, 1};  // baseColorFactor, rgb (glTF's default)
    double metallic = 1, roughness = 1;
    double transmission = 0;  // KHR_materials_transmission transmissionFactor
    double ior = 1.5;         // KHR_materials_ior
    // KHR_materials_volume: the colour white light becomes after `attenuation_distance`.
    double attenuation[3] = {1, 1, 1};
    double attenuation_distance = std::numeric_limits<double>::infinity();
};

// The conductor glTF's metals become: the Fresnel reflectance of n = 1, k = 10 at normal
// incidence, 100/104, is close to 1, so MirrorReflectance carries the colour.
inline constexpr double kMetalRefractionIndex = 1, kMetalAbsorptionIndex = 10;

PbrMaterial pbr_of(const MaterialDesc& m);
MaterialDesc material_of(const PbrMaterial& p);
// Whether two descriptions agree to what a float-precision editor keeps (1e-4).
bool same_pbr(const PbrMaterial& a, const PbrMaterial& b);

// Blinn-Phong exponent <-> glTF roughness r (alpha = r^2; n = 2 / alpha^2 - 2, Walter et
// al. 2007), the exponent kept in [1, 1e6].
double roughness_of_exponent(double n);
double exponent_of_roughness(double r);

// A material as the course's JSON writes it (Materials/Material entry), exact numbers.
nlohmann::ordered_json material_entry(const MaterialDesc& m, size_t id);
// A material's exact values as glTF extras ("ceng795" of a glTF material), and back;
// false when `j` is not such an object.
nlohmann::json material_extras(const MaterialDesc& m);
bool material_from_extras(const nlohmann::json& j, MaterialDesc& m);

}  // namespace rt
