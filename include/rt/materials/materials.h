// The registry of materials in the renderer: every kind of material the scene format
// has, in the order of their formats (MaterialFormats, rt/loader/material_desc.h), each
// described once in its own file (material.h says what a kind provides). The integrator's
// secondary rays, --trace and the exports are derived from this list; see
// docs/extending.md.
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

// The kinds, in MaterialType order.
using Materials = KindList<PlainMaterial, MirrorMaterial, ConductorMaterial, DielectricMaterial>;

// ---- Derived from the list ----------------------------------------------------------

// A kind's MaterialType: its place in Materials, which is its format's place in
// MaterialFormats.
template <class M>
inline constexpr MaterialType material_type_of = MaterialType(IndexIn<M, Materials>::value);

// Materials and MaterialFormats list the same kinds in the same order.
template <class M>
using FormatOf = typename M::Format;
static_assert(same_order<FormatOf>(Materials{}, MaterialFormats{}),
              "Materials lists the kinds of MaterialFormats, each by its Format, in order");

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

// Whether the lights shade a hit on the material's back face.
inline bool shaded_from_inside(MaterialType t) {
    return visit_material<bool>(t, [](auto m) { return decltype(m)::kShadedFromInside; });
}
// Whether the material sends rays through its surface.
inline bool refracts(MaterialType t) {
    return visit_material<bool>(t, [](auto m) { return decltype(m)::kRefracts; });
}

}  // namespace rt
