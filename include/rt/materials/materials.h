// The registry of materials: every kind of material the scene format has, each
// described once in its own file (material.h says what a kind provides). The loader's
// _type words and keys, the integrator's secondary rays, --trace and the MTL export
// are derived from this list; see docs/extending.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <type_traits>

#include "rt/materials/conductor.h"
#include "rt/materials/dielectric.h"
#include "rt/materials/mirror.h"
#include "rt/materials/plain.h"

namespace rt {

enum class MaterialType : uint32_t { Plain, Mirror, Conductor, Dielectric };

template <class... M>
struct MaterialList {
    static constexpr size_t size = sizeof...(M);
};
// The kinds, in MaterialType order.
using Materials = MaterialList<PlainMaterial, MirrorMaterial, ConductorMaterial, DielectricMaterial>;

// ---- Derived from the list ----------------------------------------------------------

template <class M, class L>
struct MaterialIndex;
template <class M, class... T>
struct MaterialIndex<M, MaterialList<M, T...>> : std::integral_constant<size_t, 0> {};
template <class M, class U, class... T>
struct MaterialIndex<M, MaterialList<U, T...>>
    : std::integral_constant<size_t, 1 + MaterialIndex<M, MaterialList<T...>>::value> {};

// A kind's MaterialType: its place in Materials.
template <class M>
inline constexpr MaterialType material_type_of = MaterialType(MaterialIndex<M, Materials>::value);
static_assert(material_type_of<PlainMaterial> == MaterialType::Plain &&
                  material_type_of<MirrorMaterial> == MaterialType::Mirror &&
                  material_type_of<ConductorMaterial> == MaterialType::Conductor &&
                  material_type_of<DielectricMaterial> == MaterialType::Dielectric,
              "MaterialType lists the kinds of Materials, in its order");
inline constexpr size_t kMaterialTypeCount = Materials::size;

// f(M{}) for each kind M, in order (a default-constructed M as a tag).
template <class F, class... M>
void for_each_material_in(MaterialList<M...>, F&& f) {
    (f(M{}), ...);
}
template <class F>
void for_each_material(F&& f) {
    for_each_material_in(Materials{}, f);
}

// f(M{}) for the kind M of `type`.
template <class R, class F, class... M>
R visit_material_in(MaterialList<M...>, MaterialType type, F&& f) {
    if constexpr (std::is_void_v<R>) {
        ((type == material_type_of<M> ? (f(M{}), true) : false) || ...);
    } else {
        R r{};
        ((type == material_type_of<M> ? (r = f(M{}), true) : false) || ...);
        return r;
    }
}
template <class R, class F>
R visit_material(MaterialType type, F&& f) {
    return visit_material_in<R>(Materials{}, type, f);
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
