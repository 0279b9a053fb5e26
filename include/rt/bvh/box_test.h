// The traversal's box test: a node's eight child boxes against one ray at once, the
// bounds float, rounded outwards (rt/bvh/bvh.h). Double rays test them in double
// (AVX-512 when the compiler targets it, else two AVX halves, scalar otherwise); float
// rays in float, conservatively widened (AVX, else two SSE halves, or scalar). Both
// tests are defined in both precisions' builds, so that tests/test_lanes.cpp checks
// every lane type; the traversal (closest.cpp, any_hit.cpp) uses its Real's, through
// BoxRay, box_ray and test_boxes below.
// Header-only: the test runs in the traversal's inner loops and must inline there.
#pragma once
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstddef>
#include <limits>

#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"
#include "rt/bvh/lanes.h"

namespace rt::traversal {

constexpr int kWidth = BvhNode::kWidth;

// Per-ray data of the box test in precision B (double or float, below).
template <class B>
struct BoxRayOf;

// The box ray of `p` for the test in precision B into `b`; tmin is the least t the ray
// asks for. Written in place, field by field: the traversals keep it in their search
// state, and a copy of a returned one (one wide load over the narrower stores that
// built it) cannot take its bytes from the store buffer and stalls every traversal.
template <class B>
void box_ray_into(const RayPre& p, const Bvh& bvh, Real tmin, BoxRayOf<B>& b);
template <class B>
BoxRayOf<B> box_ray_of(const RayPre& p, const Bvh& bvh, Real tmin) {
    BoxRayOf<B> b;
    box_ray_into<B>(p, bvh, tmin, b);
    return b;
}

// ---- The double test: exact float bounds, slab distances in double -----------------

// Widening of the exit distance that makes the slab test conservative despite
// rounding in (bound - org) * inv_dir (pbrt-v3 section 3.9.2: 1 + 2 gamma(3)).
// Flat boxes (axis-aligned walls) make the slabs meet at one t, so without the
// widening a ray along a wall's edge could miss both walls. tmax is widened alike:
// an entry at exactly tmax may be computed up to gamma(3) above it.
constexpr double kSlabWiden = 1 + 2 * gamma_bound<double>(3);

// For each axis the near plane is lo when the direction is positive, so the entry is
// (near - org) * inv and the exit (far - org) * inv; a 0 * inf = NaN (ray in a slab's
// boundary plane, parallel to it) then falls out of the max/min of test_lanes and
// leaves the interval open.
template <>
struct BoxRayOf<double> {
    double org[3], inv[3];
    int near_is_hi[3];
};

// Double rays are not padded (box_pad, below); tmin is unused.
template <>
inline void box_ray_into<double>(const RayPre& p, const Bvh&, Real, BoxRayOf<double>& b) {
    for (int a = 0; a < 3; ++a) {
        b.org[a] = p.ray.org[a];
        b.inv[a] = 1.0 / double(p.ray.dir[a]);
        b.near_is_hi[a] = std::signbit(b.inv[a]) ? 1 : 0;
    }
}

// Entry distances of the node's children into `t` (HUGE_VAL for a miss), and a hit
// mask, O::kLanes children at a time.
template <class O>
inline int test_lanes(const BvhNode& n, const BoxRayOf<double>& r, double tmin, double tmax, double t[kWidth]) {
    int mask = 0;
    for (int h = 0; h < kWidth; h += O::kLanes) {
        typename O::V tnear = O::set1(tmin), tfar = O::set1(tmax * kSlabWiden);
        for (int a = 0; a < 3; ++a) {
            const float* nearp = (r.near_is_hi[a] ? n.hi[a] : n.lo[a]) + h;
            const float* farp = (r.near_is_hi[a] ? n.lo[a] : n.hi[a]) + h;
            const typename O::V o = O::set1(r.org[a]), inv = O::set1(r.inv[a]);
            const typename O::V t0 = O::mul(O::sub(O::load(nearp), o), inv);
            const typename O::V t1 = O::mul(O::sub(O::load(farp), o), inv);
            tnear = O::max(t0, tnear);
            tfar = O::min(O::mul(t1, O::set1(kSlabWiden)), tfar);
        }
        const typename O::Mask hit = O::le(tnear, tfar);
        O::store(t + h, O::select(hit, tnear, O::set1(HUGE_VAL)));
        mask |= O::bits(hit) << h;
    }
    return mask;
}

// ---- The float test: conservatively widened, for float rays -------------------------

// Float rays test boxes in float, conservatively: the float slab interval
// contains the exact one of the padded box, so no box the exact ray enters once
// padded by box_pad is rejected (docs/precision.md, "Float box tests"; the proof is
// that of docs/precision.md, with the padded origins as the ray's origins).

// How far every box is padded for a float ray, so that the box test is conservative
// for the triangle and sphere tests as computed, not only for exact geometry: a
// primitive test in Real may report a hit where the exact ray passes just outside
// the primitive, and so outside its box. In double that error, some 1e-16 R, is
// below the float rounding of the boxes around double vertices; around float ones
// (PLY meshes) the boxes are tight, and no test has found a miss there: double rays
// are not padded. In float the error is 1e-7 R and boxes fit the (float) vertices
// exactly: rays missed hits. The watertight test's
// computed answer is the exact one for vertices moved by the rounding of
// a - org, of the shear and of the edge functions, each a few u (float's unit
// roundoff) times the largest coordinate of a - org, at most R = max|org| + the
// largest coordinate of the scene's bounded geometry; its t is off by up to about
// gamma(16) R (pbrt-v3 3.9.6), the sphere test's by as much. A hit so computed lies
// within gamma(16) R of the ray point at its t and of the primitive, so padding by
// twice gamma(32) R (twice: so that its computed t, not only some t, is inside the
// padded slabs; 32 not 16: margin for needles, whose edge lines the rounding
// turns the most) covers it.
inline double box_pad(const Bvh& bvh, const Ray& r) {
    const double org = std::max(std::fabs(r.org.x), std::max(std::fabs(r.org.y), std::fabs(r.org.z)));
    return 2 * double(gamma_bound<float>(32)) * (double(bvh.extent) + org);
}

// Relative widening of 1/dir, towards zero for the near planes and away from it for
// the far planes: it covers the rounding of 1/dir, of the widening product itself, and
// of the slab's subtraction and product (1 + 2^-24 each; docs/precision.md).
constexpr float kInvWiden = 0x1p-21f;
// Above this magnitude a bound or origin could make a float subtraction overflow:
// such rays enter every box (see box_ray_into<float>).
constexpr float kBoxDomain = 0x1p125f;
// Above this magnitude a direction component's float inverse could be subnormal (below
// FLT_MIN), where rounding is no longer within a factor 1 + u: such rays enter every box
// too (no ray the renderer spawns: theirs are unit length).
constexpr float kDirDomain = 0x1p100f;

// For each axis the entry into the slab is (near - org_near) * inv_near and the exit
// (far - org_far) * inv_far, the near plane being lo when the direction's sign bit is
// clear. org_near is the origin moved by box_pad against the direction, org_far moved
// with it.
template <>
struct BoxRayOf<float> {
    float org_near[3], org_far[3], inv_near[3], inv_far[3];
    int near_is_hi[3];
};

// The box ray for rays with tmin >= 0, direction components within kDirDomain and
// padded origin and scene bounds within kBoxDomain; any other ray gets NaN inverses,
// which the max and min of test_lanes skip: it enters every box (and empty slots,
// leaves of no primitives).
template <>
inline void box_ray_into<float>(const RayPre& p, const Bvh& bvh, Real tmin, BoxRayOf<float>& b) {
    // Grown by 1/32 so that the origin's rounding to nearest below (at most u of
    // |org| + pad, under 1/64 of pad) still leaves a pad of at least box_pad.
    const float pad = float(box_pad(bvh, p.ray) * (1 + 1.0 / 32));
    bool in_domain = tmin >= 0 && bvh.extent < kBoxDomain;
    for (int a = 0; a < 3; ++a) {
        const float d = p.ray.dir[a], o = p.ray.org[a];
        b.near_is_hi[a] = std::signbit(d) ? 1 : 0;
        // 1/d within a factor 1 + u; a d whose inverse overflows gets FLT_MAX as its
        // lower bound.
        const float inv = 1 / d, shrunk = std::fabs(inv) * (1 - kInvWiden);
        b.inv_near[a] = d == 0 ? inv : std::copysign(shrunk < FLT_MAX ? shrunk : FLT_MAX, d);
        b.inv_far[a] = inv * (1 + kInvWiden);
        // No padding keeps the origin's bits, -0 included.
        const float out = b.near_is_hi[a] ? -pad : pad;
        b.org_near[a] = pad == 0 ? o : o + out;
        b.org_far[a] = pad == 0 ? o : o - out;
        in_domain = in_domain && std::fabs(d) <= kDirDomain && std::fabs(b.org_near[a]) < kBoxDomain &&
                    std::fabs(b.org_far[a]) < kBoxDomain;
    }
    if (!in_domain)
        for (int a = 0; a < 3; ++a) b.inv_near[a] = b.inv_far[a] = std::numeric_limits<float>::quiet_NaN();
}

// Entry distances of the node's children into `t` (meaningful for hits only), and a
// hit mask, O::kLanes children at a time.
template <class O>
inline int test_lanes(const BvhNode& n, const BoxRayOf<float>& r, float tmin, float tmax, float t[kWidth]) {
    int mask = 0;
    for (int h = 0; h < kWidth; h += O::kLanes) {
        typename O::V tnear = O::set1(tmin), tfar = O::set1(tmax);
        for (int a = 0; a < 3; ++a) {
            const float* nearp = (r.near_is_hi[a] ? n.hi[a] : n.lo[a]) + h;
            const float* farp = (r.near_is_hi[a] ? n.lo[a] : n.hi[a]) + h;
            const typename O::V t0 = O::mul(O::sub(O::load(nearp), O::set1(r.org_near[a])), O::set1(r.inv_near[a]));
            const typename O::V t1 = O::mul(O::sub(O::load(farp), O::set1(r.org_far[a])), O::set1(r.inv_far[a]));
            tnear = O::max(t0, tnear);
            tfar = O::min(t1, tfar);
        }
        O::store(t + h, tnear);
        mask |= O::bits(O::le(tnear, tfar)) << h;
    }
    return mask;
}

// ---- The traversal's test: its Real's -----------------------------------------------

#if !defined(RT_REAL_FLOAT)
// Double rays test boxes in double: the float bounds convert exactly.
using BoxReal = double;
// Eight lanes in one AVX-512 register, else two AVX halves (four WebAssembly quarters).
#if defined(__AVX512F__)
using BoxLanes = F64x8;
#elif defined(__AVX__)
using BoxLanes = F64x4;
#elif defined(__wasm_simd128__)
using BoxLanes = W64x2;
#else
using BoxLanes = OneLane<double>;
#endif
#else
using BoxReal = float;
// Eight lanes in one AVX register, else two SSE (or WebAssembly) halves.
#if defined(__AVX__)
using BoxLanes = F32x8;
#elif defined(__SSE2__)
using BoxLanes = F32x4;
#elif defined(__wasm_simd128__)
using BoxLanes = W32x4;
#else
using BoxLanes = OneLane<float>;
#endif
#endif

using BoxRay = BoxRayOf<BoxReal>;
inline BoxRay box_ray(const RayPre& p, const Bvh& bvh, Real tmin) { return box_ray_of<BoxReal>(p, bvh, tmin); }
inline void box_ray_into(const RayPre& p, const Bvh& bvh, Real tmin, BoxRay& b) {
    box_ray_into<BoxReal>(p, bvh, tmin, b);
}

// Alignment of the arrays test_boxes writes. GCC may align such a local array to its
// size (64 bytes for eight doubles) and then store to it with aligned instructions,
// while AddressSanitizer's stack-use-after-return frames give it only 32 (check-asan
// fails without it): declared, the alignment is honoured by both.
constexpr size_t kBoxesAlign = 64;

// The box test of the traversal, and its lane-by-lane reference (same bits).
inline int test_boxes(const BvhNode& n, const BoxRay& r, BoxReal tmin, BoxReal tmax, BoxReal t[kWidth]) {
    return test_lanes<BoxLanes>(n, r, tmin, tmax, t);
}
inline int test_scalar(const BvhNode& n, const BoxRay& r, BoxReal tmin, BoxReal tmax, BoxReal t[kWidth]) {
    return test_lanes<OneLane<BoxReal>>(n, r, tmin, tmax, t);
}

}  // namespace rt::traversal
