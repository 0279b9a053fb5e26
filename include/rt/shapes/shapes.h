// The registry of shapes in the renderer: every kind of shape the scene format has, in
// primitive-id order, the same order as their descs (ShapeDescs, rt/loader/shape_descs.h).
// Triangles (meshes and Objects/Triangle) are kind 0 and handled by the mesh code; the
// kinds after them are listed here, each described once in its own file (shape.h says
// what a kind provides). Everything per kind (arrays, id decoding, BVH storage, bounds,
// ray tests, surfaces, names, counts, --stats, the exports) is derived from this list
// and ShapeDescs; see docs/extending.md.
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

template <class... S>
using ShapeList = KindList<S...>;
// The kinds after triangles, in ShapeKind order.
using Shapes = ShapeList<Sphere, Instance, Plane>;

// ---- Derived from the list ----------------------------------------------------------

// A kind's ShapeKind: 1 + its place in Shapes, which is its desc's place in ShapeDescs.
template <class S>
inline constexpr ShapeKind kind_of = ShapeKind(1 + IndexIn<S, Shapes>::value);

// Shapes and ShapeDescs list the same kinds in the same order.
template <class S>
using DescOf = typename S::Desc;
static_assert(same_order<DescOf>(Shapes{}, ShapeDescs{}),
              "Shapes lists the kinds of ShapeDescs, each by its Desc, in order");

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

// One array per kind: ShapeVectors holds a std::vector<S> for each S.
template <class S>
using VectorOf = std::vector<S>;
using ShapeVectors = Shapes::Tuple<VectorOf>;

// f(S{}) for the kind S of `kind` (not Triangle, which the caller handles).
template <class R, class F>
[[gnu::always_inline]] inline R visit_shape(ShapeKind kind, F&& f) {
    return visit_kind<R>(Shapes{}, size_t(kind) - 1, f);
}

}  // namespace rt
