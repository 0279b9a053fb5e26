// The registry of materials: every kind of material the scene format has, each
// described once in its own file (material.h says what a kind provides). The loader's
// _type words and keys, the integrator's secondary rays, --trace and the MTL export
// are derived from this list; see docs/extending.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "rt/core/kind_list.h"
#include "rt/materials/conductor.h"
#include "rt/materials/dielectric.h"
#include "rt/materials/mirror.h"
#include "rt/materials/plain.h"

namespace rt {

enum class MaterialType : uint32_t { Plain, Mirror, Conductor, Dielectric };

// The kinds, in MaterialType order.
using Materials = KindList<PlainMaterial, MirrorMaterial, ConductorMaterial, DielectricMaterial>;

// ---- Derived from the list ----------------------------------------------------------

// A kind's MaterialType: its place in Materials.
template <class M>
inline constexpr MaterialType material_type_of = MaterialType(IndexIn<M, Materials>::value);
static_assert(material_type_of<PlainMaterial> == MaterialType::Plain &&
                  material_type_of<MirrorMaterial> == MaterialType::Mirror &&
                  material_type_of<ConductorMaterial> == MaterialType::Conductor &&
                  material_type_of<DielectricMaterial> == MaterialType::Dielectric,
              "MaterialType lists the kinds of Materials, in its order");
inline constexpr size_t kMaterialTypeCount = Materials::size;

// f(M{}) for each kind M, in order (a default-constructed M as a tag).
template <class F>
[[gnu::always_inline]] inline void for_each_material(F&& f) {
    for_each_kind(Materials{}, f);
}

// f(M{}) for the kind M of `type`.
template <class R, class F>
[[gnu::always_inline]] inline R visit_material(MaterialType type, F&& f) {
    return visit_kind<R>(Materials{}, size_t(type), f);
}

// "plain", "mirror", ...
inline const char* material_type_name(MaterialType t) {
    return visit_material<const char*>(t, [](auto m) { return decltype(m)::kName; });
}
// Whether the lights shade a hit on the material's back face.
inline bool shaded_from_inside(MaterialType t) {
    return visit_material<bool>(t, [](auto m) { return decltype(m)::kShadedFromInside; });
}
// Whether the material sends rays through its surface.
inline bool refracts(MaterialType t) {
    return visit_material<bool>(t, [](auto m) { return decltype(m)::kRefracts; });
}

}  // namespace rt
