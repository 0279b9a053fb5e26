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

// f(K{}) for each kind K, in order (a default-constructed K as a tag).
template <class F, class... K>
void for_each_kind(KindList<K...>, F&& f) {
    (f(K{}), ...);
}

// f(K{}) for the kind at place `index` (none when index >= size: R{}).
template <class R, class F, class... K>
R visit_kind(KindList<K...>, size_t index, F&& f) {
    size_t i = 0;
    if constexpr (std::is_void_v<R>) {
        ((index == i++ ? (f(K{}), true) : false) || ...);
    } else {
        R r{};
        ((index == i++ ? (r = f(K{}), true) : false) || ...);
        return r;
    }
}

}  // namespace rt
