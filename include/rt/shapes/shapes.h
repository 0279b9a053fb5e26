// The registry of shapes: every kind of shape the scene format has, in primitive-id
// order. Triangles (meshes and Objects/Triangle) are kind 0 and handled by the mesh
// code; the kinds after them are listed here, each described once in its own file
// (shape.h says what a kind provides). Everything per kind (loader keys and readers,
// arrays, id decoding, BVH storage, bounds, ray tests, surfaces, names, counts,
// --stats, OBJ export) is derived from this list; see docs/extending.md.
//
// Bounded kinds come before unbounded ones: ids [0, bounded count) are the BVH's.
// Ids are the closest-hit tie-break, so this order is part of the images.
#pragma once
#include <cstddef>
#include <cstdint>
#include <tuple>
#include <type_traits>
#include <utility>
#include <vector>

#include "rt/core/kind_list.h"
#include "rt/shapes/instance.h"
#include "rt/shapes/plane.h"
#include "rt/shapes/sphere.h"

namespace rt {

enum class ShapeKind : uint32_t { Triangle, Sphere, Instance, Plane };

template <class... S>
using ShapeList = KindList<S...>;
// The kinds after triangles, in ShapeKind order.
using Shapes = ShapeList<Sphere, Instance, Plane>;

// ---- Derived from the list ----------------------------------------------------------

// A kind's ShapeKind: 1 + its place in Shapes.
template <class S>
inline constexpr ShapeKind kind_of = ShapeKind(1 + IndexIn<S, Shapes>::value);
static_assert(kind_of<Sphere> == ShapeKind::Sphere && kind_of<Instance> == ShapeKind::Instance &&
                  kind_of<Plane> == ShapeKind::Plane,
              "ShapeKind lists the kinds of Shapes, in its order");

inline constexpr size_t kShapeKindCount = 1 + Shapes::size;  // triangles too
inline constexpr ShapeKind kShapeKinds[] = {ShapeKind::Triangle, ShapeKind::Sphere, ShapeKind::Instance,
                                            ShapeKind::Plane};
static_assert(std::size(kShapeKinds) == kShapeKindCount, "kShapeKinds lists every kind, in order");

// f(S{}) for each kind S of Shapes, in order (a default-constructed S as a tag).
template <class F>
[[gnu::always_inline]] inline void for_each_shape(F&& f) {
    for_each_kind(Shapes{}, f);
}

// Unbounded kinds follow bounded ones (the BVH's ids are [0, bounded count)).
template <class... S>
constexpr bool bounded_first(ShapeList<S...>) {
    bool seen_unbounded = false, ok = true;
    ((ok = ok && !(seen_unbounded && S::kBounded), seen_unbounded = seen_unbounded || !S::kBounded), ...);
    return ok;
}
static_assert(bounded_first(Shapes{}), "bounded kinds come first in Shapes");

// One array per kind: ShapeArrays<std::vector> holds a std::vector<S> for each S.
template <class S>
using VectorOf = std::vector<S>;
template <class S>
using DescVectorOf = std::vector<typename S::Desc>;
using ShapeVectors = Shapes::Tuple<VectorOf>;
using ShapeDescVectors = Shapes::Tuple<DescVectorOf>;

// f(S{}) for the kind S of `kind` (not Triangle, which the caller handles).
template <class R, class F>
[[gnu::always_inline]] inline R visit_shape(ShapeKind kind, F&& f) {
    return visit_kind<R>(Shapes{}, size_t(kind) - 1, f);
}

// The kind's name as the scene file writes it (Objects/<key>); "Triangle" for kind 0.
inline const char* shape_key(ShapeKind kind) {
    if (kind == ShapeKind::Triangle) return "Triangle";
    return visit_shape<const char*>(kind, [](auto s) { return decltype(s)::kKey; });
}

}  // namespace rt
