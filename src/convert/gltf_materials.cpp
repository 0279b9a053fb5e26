// The table between the course's materials and glTF's (gltf_materials.h, docs/gltf.md).
#include "rt/convert/gltf_materials.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "rt/loader/scene_desc.h"
#include "scene_import.h"

namespace rt {
namespace {

double clamp01(double x) { return std::isfinite(x) ? std::min(std::max(x, 0.0), 1.0) : 0.0; }

// Fresnel reflectance of a conductor n + ik at normal incidence.
double conductor_f0(double n, double k) { return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k); }

std::array<double, 3> arr(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

bool close(double a, double b) {
    if (std::isinf(a) || std::isinf(b)) return a == b;
    return std::fabs(a - b) <= 1e-4 * std::max(1.0, std::fabs(a));
}

}  // namespace

double roughness_of_exponent(double n) { return std::pow(2 / (std::max(n, 0.0) + 2), 0.25); }

double exponent_of_roughness(double r) {
    const double alpha = r * r;
    if (alpha <= 0) return 1e6;
    return std::min(std::max(2 / (alpha * alpha) - 2, 1.0), 1e6);
}

namespace {

// Each kind's glTF form, by the kinds of Materials: a kind without one does not compile
// (pbr_of).
void pbr_of_kind(PlainMaterial, const MaterialDesc& m, PbrMaterial& p) {
    p.metallic = 0;
    for (int i = 0; i < 3; ++i) p.base[i] = clamp01(double(m.diffuse[i]));
}

void pbr_of_kind(MirrorMaterial, const MaterialDesc& m, PbrMaterial& p) {
    p.metallic = 1;
    for (int i = 0; i < 3; ++i) p.base[i] = clamp01(double(m.mirror[i]));
}

// The same reflectance at normal incidence as the course's conductor.
void pbr_of_kind(ConductorMaterial, const MaterialDesc& m, PbrMaterial& p) {
    p.metallic = 1;
    const double f = conductor_f0(double(m.refraction_index), double(m.absorption_index)) /
                     conductor_f0(kMetalRefractionIndex, kMetalAbsorptionIndex);
    for (int i = 0; i < 3; ++i) p.base[i] = clamp01(double(m.mirror[i]) * f);
}

void pbr_of_kind(DielectricMaterial, const MaterialDesc& m, PbrMaterial& p) {
    p.metallic = 0;
    p.transmission = 1;
    p.ior = double(m.refraction_index);
    // Beer's law: white light keeps exp(-c) of itself over one unit of distance.
    if (m.absorption_coefficient[0] > 0 || m.absorption_coefficient[1] > 0 || m.absorption_coefficient[2] > 0) {
        p.attenuation_distance = 1;
        for (int i = 0; i < 3; ++i) p.attenuation[i] = std::exp(-double(m.absorption_coefficient[i]));
    }
}

}  // namespace

PbrMaterial pbr_of(const MaterialDesc& m) {
    PbrMaterial p;
    p.roughness = roughness_of_exponent(double(m.phong_exponent));
    visit_material<void>(m.type, [&](auto k) { pbr_of_kind(k, m, p); });
    return p;
}

MaterialDesc material_of(const PbrMaterial& p) {
    MaterialDesc m;
    m.phong_exponent = Real(exponent_of_roughness(clamp01(p.roughness)));
    const double gloss = 1 - clamp01(p.roughness);
    const double metallic = clamp01(p.metallic);
    for (int i = 0; i < 3; ++i) {
        const double base = clamp01(p.base[i]);
        m.diffuse[i] = Real(base * (1 - metallic));
        m.ambient[i] = m.diffuse[i];
        m.specular[i] = Real(gloss * (metallic >= 0.5 ? base : 1));
        m.mirror[i] = Real(base);
    }
    if (p.transmission >= 0.5) {
        m.type = MaterialType::Dielectric;
        m.ambient = m.diffuse = Vec3{0, 0, 0};
        m.mirror = Vec3{1, 1, 1};
        m.refraction_index = Real(p.ior > 0 && std::isfinite(p.ior) ? p.ior : 1.5);
        if (std::isfinite(p.attenuation_distance) && p.attenuation_distance > 0)
            for (int i = 0; i < 3; ++i)
                m.absorption_coefficient[i] =
                    Real(-std::log(std::max(clamp01(p.attenuation[i]), 1e-6)) / p.attenuation_distance);
    } else if (metallic >= 0.5) {
        m.type = MaterialType::Conductor;
        m.refraction_index = Real(kMetalRefractionIndex);
        m.absorption_index = Real(kMetalAbsorptionIndex);
    } else {
        m.type = MaterialType::Plain;
        m.mirror = Vec3{1, 1, 1};
    }
    return m;
}

bool same_pbr(const PbrMaterial& a, const PbrMaterial& b) {
    bool same = close(a.metallic, b.metallic) && close(a.roughness, b.roughness) &&
                close(a.transmission, b.transmission) && close(a.attenuation_distance, b.attenuation_distance);
    if (a.transmission > 0 || b.transmission > 0) same = same && close(a.ior, b.ior);
    for (int i = 0; i < 3; ++i) same = same && close(a.base[i], b.base[i]) && close(a.attenuation[i], b.attenuation[i]);
    return same;
}

nlohmann::ordered_json material_entry(const MaterialDesc& m, size_t id) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    j["_id"] = std::to_string(id);
    visit_material_format<void>(m.type, [&](auto k) {
        using M = decltype(k);
        if (M::kTypeWord) j["_type"] = M::kTypeWord;
    });
    j["AmbientReflectance"] = course_vec(arr(m.ambient));
    j["DiffuseReflectance"] = course_vec(arr(m.diffuse));
    j["SpecularReflectance"] = course_vec(arr(m.specular));
    j["PhongExponent"] = course_number(double(m.phong_exponent));
    // The kind's own keys (rt/materials/), each a field of MaterialDesc.
    visit_material_format<void>(m.type, [&](auto k) {
        for (const char* key : decltype(k)::kKeys) {
            if (!std::strcmp(key, "MirrorReflectance")) j[key] = course_vec(arr(m.mirror));
            if (!std::strcmp(key, "RefractionIndex")) j[key] = course_number(double(m.refraction_index));
            if (!std::strcmp(key, "AbsorptionIndex")) j[key] = course_number(double(m.absorption_index));
            if (!std::strcmp(key, "AbsorptionCoefficient")) j[key] = course_vec(arr(m.absorption_coefficient));
        }
    });
    return j;
}

nlohmann::json material_extras(const MaterialDesc& m) {
    return {{"type", material_type_name(m.type)},
            {"ambient", arr(m.ambient)},
            {"diffuse", arr(m.diffuse)},
            {"specular", arr(m.specular)},
            {"phongExponent", double(m.phong_exponent)},
            {"mirror", arr(m.mirror)},
            {"refractionIndex", double(m.refraction_index)},
            {"absorptionIndex", double(m.absorption_index)},
            {"absorptionCoefficient", arr(m.absorption_coefficient)}};
}

bool material_from_extras(const nlohmann::json& j, MaterialDesc& m) {
    if (!j.is_object()) return false;
    auto number = [&](const char* key, Real& out, double lo) {
        const auto it = j.find(key);
        if (it == j.end() || !it->is_number()) return false;
        const double v = it->get<double>();
        if (!(v >= lo && v <= kMaxMagnitude)) return false;
        out = Real(v);
        return true;
    };
    auto colour = [&](const char* key, Vec3& out) {
        const auto it = j.find(key);
        if (it == j.end() || !it->is_array() || it->size() != 3) return false;
        for (int i = 0; i < 3; ++i) {
            if (!(*it)[size_t(i)].is_number()) return false;
            const double v = (*it)[size_t(i)].get<double>();
            if (!(v >= 0 && v <= kMaxMagnitude)) return false;
            out[i] = Real(v);
        }
        return true;
    };
    const auto type = j.find("type");
    if (type == j.end() || !type->is_string()) return false;
    bool known = false;
    for_each_material_format([&](auto k) {
        using M = decltype(k);
        if (*type == M::kName) {
            m.type = material_type_of_format<M>;
            known = true;
        }
    });
    return known && colour("ambient", m.ambient) && colour("diffuse", m.diffuse) && colour("specular", m.specular) &&
           number("phongExponent", m.phong_exponent, 0) && colour("mirror", m.mirror) &&
           number("refractionIndex", m.refraction_index, 1e-300) && number("absorptionIndex", m.absorption_index, 0) &&
           colour("absorptionCoefficient", m.absorption_coefficient);
}

}  // namespace rt
