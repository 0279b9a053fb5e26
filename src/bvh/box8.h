// Box8, the SAH builder's box in one register (bvh_build.cpp): all inline, the
// binning and partitioning loops use it for every primitive.
#pragma once
#include <algorithm>
#include <cmath>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "rt/bvh/bvh.h"

namespace rt::bvh_builder {

// A box as eight floats (lo0, lo1, lo2, 0, -hi0, -hi1, -hi2, 0): one min
// extends both ends, so binning and partitioning need one instruction per box
// with AVX. The empty box is all +inf. A type of its own because it lives in a
// register: binning and partitioning (most of the build) load every BuildBox
// into one and extend one per bin and side; a Box (lo, hi) would take a min and
// a max and twice the loads for each. Range bounds and node slots are Boxes
// (to_box).
#if defined(__AVX__)
using Box8 = __m256;
inline Box8 empty8() { return _mm256_set1_ps(HUGE_VALF); }
inline Box8 min8(Box8 a, Box8 b) { return _mm256_min_ps(a, b); }
// Lanes 3 and 7 of a BuildBox (id, padding) are zeroed so that no arithmetic
// ever sees their bits (small ids are denormal floats).
inline Box8 load8(const BuildBox& b) {
    const __m256 sign = _mm256_setr_ps(0, 0, 0, 0, -0.0f, -0.0f, -0.0f, -0.0f);
    return _mm256_blend_ps(_mm256_xor_ps(_mm256_loadu_ps(b.lo), sign), _mm256_setzero_ps(), 0x88);
}
// lo + hi (the doubled centroid, binning's measure) in lanes 0..2.
inline __m128 centre4(Box8 v) { return _mm_sub_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1)); }
// The box of the point lo + hi.
inline Box8 centroid8(Box8 v) {
    const __m128 c = centre4(v);
    return _mm256_insertf128_ps(_mm256_castps128_ps256(c), _mm_xor_ps(c, _mm_set1_ps(-0.0f)), 1);
}
// Box::area of the box, bit for bit: lo - hi = -(hi - lo) exactly, and the
// products and their order of summation are Box::area's.
inline float area8(Box8 v) {
    const __m128 e = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));  // -(extent)
    if (_mm_cvtss_f32(e) > 0) return 0;                                                   // empty
    const __m128 p = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1)));        // xy, yz, zx
    const __m128 s = _mm_add_ss(_mm_add_ss(p, _mm_shuffle_ps(p, p, 1)), _mm_shuffle_ps(p, p, 2));
    return 2 * _mm_cvtss_f32(s);
}
inline void store8(Box8 v, float f[8]) { _mm256_storeu_ps(f, v); }
#else
struct Box8 {
    float f[8];
};
inline Box8 empty8() {
    Box8 b;
    for (float& x : b.f) x = HUGE_VALF;
    return b;
}
inline Box8 min8(Box8 a, const Box8& b) {
    for (int i = 0; i < 8; ++i) a.f[i] = std::min(a.f[i], b.f[i]);
    return a;
}
inline Box8 load8(const BuildBox& b) { return {{b.lo[0], b.lo[1], b.lo[2], 0, -b.hi[0], -b.hi[1], -b.hi[2], 0}}; }
inline Box8 centroid8(const Box8& v) {
    const float c[3] = {v.f[0] - v.f[4], v.f[1] - v.f[5], v.f[2] - v.f[6]};
    return {{c[0], c[1], c[2], 0, -c[0], -c[1], -c[2], 0}};
}
inline float area8(const Box8& v) {
    const float x = -(v.f[0] + v.f[4]), y = -(v.f[1] + v.f[5]), z = -(v.f[2] + v.f[6]);
    return x < 0 ? 0 : 2 * (x * y + y * z + z * x);
}
inline void store8(const Box8& v, float f[8]) { std::copy(v.f, v.f + 8, f); }
#endif
inline Box to_box(Box8 v) {
    float f[8];
    store8(v, f);
    Box b;
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = f[a];
        b.hi[a] = -f[4 + a];
    }
    return b;
}

}  // namespace rt::bvh_builder
