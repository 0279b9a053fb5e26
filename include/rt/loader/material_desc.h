// The materials as the scene file writes them (spec 3, "Material"): one MaterialDesc for
// every kind, and per kind its format (its _type word, the keys it may carry and the
// reading of them), listed in MaterialType order. The renderer's form of each kind is in
// rt/materials/ (materials.h lists them in the same order); see docs/extending.md.
//
// A kind's format F provides, each used by the loader or the messages:
//   F::kName, F::kTypeWord   its name (--trace, exports) and its _type word in the scene
//                            file (nullptr: the kind of a material without _type)
//   F::kKeys, F::read        the keys its entries may carry beyond the common ones, and
//                            the reading of them (required keys, defaults)
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "rt/core/kind_list.h"
#include "rt/core/math.h"

namespace rt {

enum class MaterialType : uint32_t { Plain, Mirror, Conductor, Dielectric };

// A material as written in the file. The fields are the format's material keys; a kind
// reads those it uses (its format's read()).
struct MaterialDesc {
    MaterialType type{};
    Vec3 ambient, diffuse, specular;
    Real phong_exponent = 1;      // spec: PhongExponent; default 1 (reference-conventions.md)
    Vec3 mirror;                  // MirrorReflectance; ignored for Plain materials
    Real refraction_index = 1;    // conductors and dielectrics
    Real absorption_index = 0;    // conductors: imaginary part k of the complex index
    Vec3 absorption_coefficient;  // dielectrics: Beer's law c, per unit distance
    // Roughness: how far a mirror's, conductor's or dielectric's rays are perturbed (0:
    // sharp; docs/conventions.md, "Assignment 3"); ignored for Plain materials.
    Real roughness = 0;
    std::string id;  // its _id, for --trace
};

// No _type: Blinn-Phong only. MirrorReflectance is read (and checked) but not used: the
// akif_uslu scenes carry it on plain materials (reference-conventions.md, "Shading").
struct PlainMaterialFormat {
    static constexpr const char* kName = "plain";
    static constexpr const char* kTypeWord = nullptr;
    static constexpr const char* kKeys[] = {"MirrorReflectance", "Roughness"};
    template <class Reader>
    static void read(Reader& r, MaterialDesc& d) {
        d.mirror = r.color_or("MirrorReflectance", {1, 1, 1});
        d.roughness = r.non_negative_or("Roughness", 0);
    }
};

struct MirrorMaterialFormat {
    static constexpr const char* kName = "mirror";
    static constexpr const char* kTypeWord = "mirror";
    static constexpr const char* kKeys[] = {"MirrorReflectance", "Roughness"};
    template <class Reader>
    static void read(Reader& r, MaterialDesc& d) {
        d.mirror = r.color("MirrorReflectance");
        d.roughness = r.non_negative_or("Roughness", 0);
    }
};

struct ConductorMaterialFormat {
    static constexpr const char* kName = "conductor";
    static constexpr const char* kTypeWord = "conductor";
    static constexpr const char* kKeys[] = {"MirrorReflectance", "RefractionIndex", "AbsorptionIndex", "Roughness"};
    template <class Reader>
    static void read(Reader& r, MaterialDesc& d) {
        d.mirror = r.color("MirrorReflectance");
        d.refraction_index = r.positive("RefractionIndex");
        d.absorption_index = r.non_negative("AbsorptionIndex");
        d.roughness = r.non_negative_or("Roughness", 0);
    }
};

// MirrorReflectance defaults to 1 1 1 (the course's 2021 cornellbox_recursive glass has
// none).
struct DielectricMaterialFormat {
    static constexpr const char* kName = "dielectric";
    static constexpr const char* kTypeWord = "dielectric";
    static constexpr const char* kKeys[] = {"MirrorReflectance", "RefractionIndex", "AbsorptionCoefficient",
                                            "Roughness"};
    template <class Reader>
    static void read(Reader& r, MaterialDesc& d) {
        d.mirror = r.color_or("MirrorReflectance", {1, 1, 1});
        d.refraction_index = r.positive("RefractionIndex");
        d.absorption_coefficient = r.color_or("AbsorptionCoefficient", {0, 0, 0});
        d.roughness = r.non_negative_or("Roughness", 0);
    }
};

// ---- The list ------------------------------------------------------------------------

// The formats, in MaterialType order.
using MaterialFormats =
    KindList<PlainMaterialFormat, MirrorMaterialFormat, ConductorMaterialFormat, DielectricMaterialFormat>;

// A format's MaterialType: its place in MaterialFormats.
template <class F>
inline constexpr MaterialType material_type_of_format = MaterialType(IndexIn<F, MaterialFormats>::value);
static_assert(material_type_of_format<PlainMaterialFormat> == MaterialType::Plain &&
                  material_type_of_format<MirrorMaterialFormat> == MaterialType::Mirror &&
                  material_type_of_format<ConductorMaterialFormat> == MaterialType::Conductor &&
                  material_type_of_format<DielectricMaterialFormat> == MaterialType::Dielectric,
              "MaterialType lists the kinds of MaterialFormats, in its order");
inline constexpr size_t kMaterialTypeCount = MaterialFormats::size;

// f(F{}) for each format F, in order (a default-constructed F as a tag).
template <class F>
void for_each_material_format(F&& f) {
    for_each_kind(MaterialFormats{}, f);
}

// f(F{}) for the format F of `type`.
template <class R, class F>
R visit_material_format(MaterialType type, F&& f) {
    return visit_kind<R>(MaterialFormats{}, size_t(type), f);
}

// "plain", "mirror", ...
inline const char* material_type_name(MaterialType t) {
    return visit_material_format<const char*>(t, [](auto m) { return decltype(m)::kName; });
}

}  // namespace rt
