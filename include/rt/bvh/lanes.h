// Lane types of the BVH traversal's kernels: the box test (rt/bvh/box_test.h) and the
// leaves' edge stage (rt/geometry/leaf_test.h) are each written once, over a type O whose
// O::V holds O::kLanes values of one precision. Every type does the same IEEE
// operation in each lane, so every width gives the same bits (tests/test_lanes.cpp
// checks it for each type compiled in). OneLane is plain C++ (the reference and the
// fallback); the others are one register each, defined where the compiler targets
// their instructions. max and min return the second operand when either is NaN, as
// the SIMD instructions do. Loads read float bounds or Real coordinates; load and store
// take unaligned addresses except F32x4's load (node bounds, 16-byte aligned).
// Header-only: the kernels run in the traversal's inner loops and must inline there.
#pragma once

#if defined(__SSE2__)
// GCC 12's AVX-512 intrinsics start from _mm512_undefined_pd(), which
// -Wmaybe-uninitialized reports wherever they are inlined (GCC bug 105593, fixed
// in GCC 13 by the same pragmas inside the header).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif
#if defined(__wasm_simd128__)
#include <wasm_simd128.h>
#endif

namespace rt::traversal {

template <class T>
struct OneLane {
    using V = T;
    using Mask = bool;
    static constexpr int kLanes = 1;
    static V set1(T x) { return x; }
    static V load(const float* p) { return T(*p); }
    static void store(T* p, V x) { *p = x; }
    static V sub(V a, V b) { return a - b; }
    static V mul(V a, V b) { return a * b; }
    static V max(V a, V b) { return a > b ? a : b; }
    static V min(V a, V b) { return a < b ? a : b; }
    static Mask le(V a, V b) { return a <= b; }
    static V select(Mask m, V a, V b) { return m ? a : b; }
    static int bits(Mask m) { return m ? 1 : 0; }
};

#if defined(__SSE2__)
struct F32x4 {
    using V = __m128;
    using Mask = __m128;
    static constexpr int kLanes = 4;
    static V set1(float x) { return _mm_set1_ps(x); }
    static V load(const float* p) { return _mm_load_ps(p); }
    static void store(float* p, V x) { _mm_storeu_ps(p, x); }
    static V sub(V a, V b) { return _mm_sub_ps(a, b); }
    static V mul(V a, V b) { return _mm_mul_ps(a, b); }
    static V max(V a, V b) { return _mm_max_ps(a, b); }
    static V min(V a, V b) { return _mm_min_ps(a, b); }
    static Mask le(V a, V b) { return _mm_cmple_ps(a, b); }
    static int bits(Mask m) { return _mm_movemask_ps(m); }
};
#endif

#if defined(__AVX__)
struct F32x8 {
    using V = __m256;
    using Mask = __m256;
    static constexpr int kLanes = 8;
    static V set1(float x) { return _mm256_set1_ps(x); }
    static V load(const float* p) { return _mm256_loadu_ps(p); }
    static void store(float* p, V x) { _mm256_storeu_ps(p, x); }
    static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
    static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
    static V max(V a, V b) { return _mm256_max_ps(a, b); }
    static V min(V a, V b) { return _mm256_min_ps(a, b); }
    static Mask le(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LE_OQ); }
    static int bits(Mask m) { return _mm256_movemask_ps(m); }
    // Lanes where any of a, b, c is < 0 (kLess) or > 0.
    template <bool kLess>
    static int any_sign(V a, V b, V c) {
        constexpr int kCmp = kLess ? _CMP_LT_OQ : _CMP_GT_OQ;
        const V z = _mm256_setzero_ps();
        return _mm256_movemask_ps(_mm256_or_ps(_mm256_or_ps(_mm256_cmp_ps(a, z, kCmp), _mm256_cmp_ps(b, z, kCmp)),
                                               _mm256_cmp_ps(c, z, kCmp)));
    }
};

struct F64x4 {
    using V = __m256d;
    using Mask = __m256d;
    static constexpr int kLanes = 4;
    static V set1(double x) { return _mm256_set1_pd(x); }
    static V load(const double* p) { return _mm256_loadu_pd(p); }
    static V load(const float* p) { return _mm256_cvtps_pd(_mm_loadu_ps(p)); }
    static void store(double* p, V x) { _mm256_storeu_pd(p, x); }
    static V sub(V a, V b) { return _mm256_sub_pd(a, b); }
    static V mul(V a, V b) { return _mm256_mul_pd(a, b); }
    static V max(V a, V b) { return _mm256_max_pd(a, b); }
    static V min(V a, V b) { return _mm256_min_pd(a, b); }
    static Mask le(V a, V b) { return _mm256_cmp_pd(a, b, _CMP_LE_OQ); }
    static V select(Mask m, V a, V b) { return _mm256_blendv_pd(b, a, m); }
    static int bits(Mask m) { return _mm256_movemask_pd(m); }
    template <bool kLess>
    static int any_sign(V a, V b, V c) {
        constexpr int kCmp = kLess ? _CMP_LT_OQ : _CMP_GT_OQ;
        const V z = _mm256_setzero_pd();
        return _mm256_movemask_pd(_mm256_or_pd(_mm256_or_pd(_mm256_cmp_pd(a, z, kCmp), _mm256_cmp_pd(b, z, kCmp)),
                                               _mm256_cmp_pd(c, z, kCmp)));
    }
};
#endif

#if defined(__AVX512F__)
struct F64x8 {
    using V = __m512d;
    using Mask = __mmask8;
    static constexpr int kLanes = 8;
    static V set1(double x) { return _mm512_set1_pd(x); }
    static V load(const float* p) { return _mm512_cvtps_pd(_mm256_loadu_ps(p)); }
    static void store(double* p, V x) { _mm512_storeu_pd(p, x); }
    static V sub(V a, V b) { return _mm512_sub_pd(a, b); }
    static V mul(V a, V b) { return _mm512_mul_pd(a, b); }
    static V max(V a, V b) { return _mm512_max_pd(a, b); }
    static V min(V a, V b) { return _mm512_min_pd(a, b); }
    static Mask le(V a, V b) { return _mm512_cmp_pd_mask(a, b, _CMP_LE_OQ); }
    static V select(Mask m, V a, V b) { return _mm512_mask_blend_pd(m, b, a); }
    static int bits(Mask m) { return m; }
    static V load(const double* p) { return _mm512_loadu_pd(p); }
    template <bool kLess>
    static int any_sign(V a, V b, V c) {
        constexpr int kCmp = kLess ? _CMP_LT_OQ : _CMP_GT_OQ;
        const V z = _mm512_setzero_pd();
        return _mm512_cmp_pd_mask(a, z, kCmp) | _mm512_cmp_pd_mask(b, z, kCmp) | _mm512_cmp_pd_mask(c, z, kCmp);
    }
};
#endif

#if defined(__wasm_simd128__)
// WebAssembly SIMD (the browser build, docs/web.md). pmax and pmin with their operands
// swapped are x86's max and min: pmax(b, a) = b < a ? a : b, the second operand on NaN.
// tests/test_lanes.cpp runs natively only; make check-web checks these through the images.
struct W64x2 {
    using V = v128_t;
    using Mask = v128_t;
    static constexpr int kLanes = 2;
    static V set1(double x) { return wasm_f64x2_splat(x); }
    static V load(const float* p) { return wasm_f64x2_promote_low_f32x4(wasm_v128_load64_zero(p)); }
    static V load(const double* p) { return wasm_v128_load(p); }
    static void store(double* p, V x) { wasm_v128_store(p, x); }
    static V sub(V a, V b) { return wasm_f64x2_sub(a, b); }
    static V mul(V a, V b) { return wasm_f64x2_mul(a, b); }
    static V max(V a, V b) { return wasm_f64x2_pmax(b, a); }
    static V min(V a, V b) { return wasm_f64x2_pmin(b, a); }
    static Mask le(V a, V b) { return wasm_f64x2_le(a, b); }
    static V select(Mask m, V a, V b) { return wasm_v128_bitselect(a, b, m); }
    static int bits(Mask m) { return wasm_i64x2_bitmask(m); }
};

struct W32x4 {
    using V = v128_t;
    using Mask = v128_t;
    static constexpr int kLanes = 4;
    static V set1(float x) { return wasm_f32x4_splat(x); }
    static V load(const float* p) { return wasm_v128_load(p); }
    static void store(float* p, V x) { wasm_v128_store(p, x); }
    static V sub(V a, V b) { return wasm_f32x4_sub(a, b); }
    static V mul(V a, V b) { return wasm_f32x4_mul(a, b); }
    static V max(V a, V b) { return wasm_f32x4_pmax(b, a); }
    static V min(V a, V b) { return wasm_f32x4_pmin(b, a); }
    static Mask le(V a, V b) { return wasm_f32x4_le(a, b); }
    static int bits(Mask m) { return wasm_i32x4_bitmask(m); }
};
#endif

}  // namespace rt::traversal
