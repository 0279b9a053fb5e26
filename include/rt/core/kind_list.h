// A compile-time list of kinds, as the registries of shapes (rt/shapes/shapes.h) and of
// materials (rt/materials/materials.h) hold them: each kind's place in the list, a loop
// over the kinds and a dispatch on a place known at run time.
#pragma once
#include <cstddef>
#include <tuple>
#include <type_traits>

namespace rt {

template <class... K>
struct KindList {
    static constexpr size_t size = sizeof...(K);
    template <template <class> class F>
    using Tuple = std::tuple<F<K>...>;  // one F<K> per kind
};

// IndexIn<K, L>::value: K's place in the list L.
template <class K, class L>
struct IndexIn;
template <class K, class... T>
struct IndexIn<K, KindList<K, T...>> : std::integral_constant<size_t, 0> {};
template <class K, class U, class... T>
struct IndexIn<K, KindList<U, T...>> : std::integral_constant<size_t, 1 + IndexIn<K, KindList<T...>>::value> {};

// Whether two lists hold the same kinds in the same order, a kind K of the first seen as
// Of<K> (the renderer's registries against the loader's: a shape by its desc, a material
// by its format).
template <template <class> class Of, class... K, class... D>
constexpr bool same_order(KindList<K...>, KindList<D...>) {
    if constexpr (sizeof...(K) != sizeof...(D)) {
        return false;
    } else {
        return (std::is_same_v<Of<K>, D> && ...);
    }
}

// Whether the first list holds every kind of the second (a list kept in an order of its
// own, checked against a registry).
template <class B, class... A>
constexpr bool holds(KindList<A...>) {
    return (std::is_same_v<B, A> || ...);
}
template <class... A, class... B>
constexpr bool covers(KindList<A...> list, KindList<B...>) {
    return (holds<B>(list) && ...);
}

// The loop and the dispatch are forced inline: they sit in the traversal's and the
// shading's inner loops, where a call per kind costs (docs/performance.md).

// f(K{}) for each kind K, in order (a default-constructed K as a tag).
template <class F, class... K>
[[gnu::always_inline]] inline void for_each_kind(KindList<K...>, F&& f) {
    (f(K{}), ...);
}

// f(K{}) for the kind at place `index` (none when index >= size: R{}). Each kind's
// result is returned directly (no default-constructed R assigned afterwards), so a
// struct result is built once in the caller's slot: an R{} then overwritten piecewise
// costs store-forwarding stalls on the hot paths (surfaces, material bounces).
template <class R, class F, class K, class... Rest>
[[gnu::always_inline]] inline R visit_kind_at(size_t index, F& f) {
    if (index == 0) return f(K{});
    if constexpr (sizeof...(Rest) == 0) {
        if constexpr (std::is_void_v<R>)
            return;
        else
            return R{};
    } else {
        return visit_kind_at<R, F, Rest...>(index - 1, f);
    }
}
template <class R, class F, class... K>
[[gnu::always_inline]] inline R visit_kind(KindList<K...>, size_t index, F&& f) {
    return visit_kind_at<R, F, K...>(index, f);
}

}  // namespace rt
