// BVH traversal: closest hit (near child first, fixed stack), for one ray or a
// packet of neighbouring rays, and any hit.
// A node's eight child boxes are tested at once against float bounds rounded
// outwards: in double for double rays (AVX-512 when the compiler targets it, else
// two AVX halves, scalar otherwise), in float, conservatively widened, for float
// rays (AVX, else two SSE halves, or scalar).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#if defined(__SSE2__)
// GCC 12's AVX-512 intrinsics start from _mm512_undefined_pd(), which
// -Wmaybe-uninitialized reports wherever they are inlined (GCC bug 105593, fixed
// in GCC 13 by the same pragmas inside the header).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#pragma GCC diagnostic pop
#endif

#include "rt/bvh/traverse.h"
#include "rt/geometry/intersect.h"

namespace rt {
namespace {

constexpr int kWidth = BvhNode::kWidth;
// kWidth - 1 entries per level at most; the builder bounds the depth to 48 levels of
// SAH splits followed by halvings (bvh_build.cpp, kSahDepthLimit): 81 levels for 2^32
// primitives.
constexpr int kStackSize = (kWidth - 1) * 81;
constexpr Real kTieSlack = 1 + 64 * std::numeric_limits<Real>::epsilon();

// Lane operations. The box test and the leaf test are each written once, over a
// type O whose O::V holds O::kLanes values of one precision; every width below
// does the same IEEE operation in each lane, so every width gives the same bits.
// OneLane is plain C++ (the reference and the fallback); the others are one
// register each. max and min return the second operand when either is NaN, as
// the SIMD instructions do. Loads read float bounds or Real coordinates; load and
// store take unaligned addresses except F32x4's load (node bounds, 16-byte aligned).
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

#if !defined(RT_REAL_FLOAT)
// Double rays test boxes in double: the float bounds convert exactly.
using BoxReal = double;

// Widening of the exit distance that makes the slab test conservative despite
// rounding in (bound - org) * inv_dir (pbrt-v3 section 3.9.2: 1 + 2 gamma(3)).
// Flat boxes (axis-aligned walls) make the slabs meet at one t, so without the
// widening a ray along a wall's edge could miss both walls. tmax is widened alike:
// an entry at exactly tmax may be computed up to gamma(3) above it.
constexpr double kSlabWiden = 1 + 2 * gamma_bound<double>(3);

// Per-ray data of the box test. For each axis the near plane is lo when the
// direction is positive, so the entry is (near - org) * inv and the exit
// (far - org) * inv; a 0 * inf = NaN (ray in a slab's boundary plane, parallel
// to it) then falls out of the max/min below and leaves the interval open.
struct BoxRay {
    double org[3], inv[3];
    int near_is_hi[3];
};

// Double rays are not padded (box_pad, in the float branch below); tmin is unused.
inline BoxRay box_ray(const RayPre& p, const Bvh&, Real) {
    BoxRay b;
    for (int a = 0; a < 3; ++a) {
        b.org[a] = p.ray.org[a];
        b.inv[a] = 1.0 / double(p.ray.dir[a]);
        b.near_is_hi[a] = std::signbit(b.inv[a]) ? 1 : 0;
    }
    return b;
}

// Entry distances of the node's children into `t` (HUGE_VAL for a miss), and a hit
// mask, O::kLanes children at a time.
template <class O>
inline int test_lanes(const BvhNode& n, const BoxRay& r, double tmin, double tmax, double t[kWidth]) {
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

// Eight lanes in one AVX-512 register, else two AVX halves.
#if defined(__AVX512F__)
using BoxLanes = F64x8;
#elif defined(__AVX__)
using BoxLanes = F64x4;
#else
using BoxLanes = OneLane<double>;
#endif

#else
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

// Float rays test boxes in float, conservatively: the float slab interval
// contains the exact one of the padded box, so no box the exact ray enters once
// padded by box_pad is rejected (docs/precision.md, "Float box tests"; the proof is
// that of docs/precision.md, with the padded origins as the ray's origins).
using BoxReal = float;

// Relative widening of 1/dir, towards zero for the near planes and away from it for
// the far planes: it covers the rounding of 1/dir, of the widening product itself, and
// of the slab's subtraction and product (1 + 2^-24 each; docs/precision.md).
constexpr float kInvWiden = 0x1p-21f;
// Above this magnitude a bound or origin could make a float subtraction overflow:
// such rays enter every box (see box_ray).
constexpr float kBoxDomain = 0x1p125f;
// Above this magnitude a direction component's float inverse could be subnormal (below
// FLT_MIN), where rounding is no longer within a factor 1 + u: such rays enter every box
// too (no ray the renderer spawns: theirs are unit length).
constexpr float kDirDomain = 0x1p100f;

// Per-ray data of the float box test: for each axis the entry into the slab is
// (near - org_near) * inv_near and the exit (far - org_far) * inv_far, the near
// plane being lo when the direction's sign bit is clear. org_near is the origin
// moved by box_pad against the direction, org_far moved with it.
struct BoxRay {
    float org_near[3], org_far[3], inv_near[3], inv_far[3];
    int near_is_hi[3];
};

// The box ray for rays with tmin >= 0, direction components within kDirDomain and
// padded origin and scene bounds within kBoxDomain; any other ray gets NaN inverses,
// which the max and min of test_boxes skip: it enters every box (and empty slots,
// leaves of no primitives).
inline BoxRay box_ray(const RayPre& p, const Bvh& bvh, Real tmin) {
    BoxRay b;
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
    return b;
}

// Entry distances of the node's children into `t` (meaningful for hits only), and a
// hit mask, O::kLanes children at a time.
template <class O>
inline int test_lanes(const BvhNode& n, const BoxRay& r, float tmin, float tmax, float t[kWidth]) {
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

// Eight lanes in one AVX register, else two SSE halves.
#if defined(__AVX__)
using BoxLanes = F32x8;
#elif defined(__SSE2__)
using BoxLanes = F32x4;
#else
using BoxLanes = OneLane<float>;
#endif
#endif

// Alignment of the arrays test_boxes writes. GCC may align such a local array to its
// size (64 bytes for eight doubles) and then store to it with aligned instructions,
// while AddressSanitizer's stack-use-after-return frames give it only 32 (check-asan
// failed on it): declared, the alignment is honoured by both.
constexpr size_t kBoxesAlign = 64;

// The box test of the traversal, and its lane-by-lane reference (same bits).
inline int test_boxes(const BvhNode& n, const BoxRay& r, BoxReal tmin, BoxReal tmax, BoxReal t[kWidth]) {
    return test_lanes<BoxLanes>(n, r, tmin, tmax, t);
}
inline int test_scalar(const BvhNode& n, const BoxRay& r, BoxReal tmin, BoxReal tmax, BoxReal t[kWidth]) {
    return test_lanes<OneLane<BoxReal>>(n, r, tmin, tmax, t);
}

// Tests one BVH primitive; returns true with t (and weights) on a hit in (tmin, tmax).
template <bool kCull, bool kShadow = false>
inline bool hit_prim(const Scene& s, const RayPre& p, uint32_t id, Real tmin, Real tmax, Real& t, Real w[3]) {
    return s.geometry.intersect<kCull, kShadow>(p, s.geometry.shape_of<true>(id), tmin, tmax, t, w);
}

#if defined(__AVX2__)
// Leaves test their triangles kLeafBlock at a time, one register of Real lanes
// (four doubles with AVX2, eight with AVX-512, eight floats): the edge stage of the watertight test
// (triangle_edges) with the same operations lane by lane, so the same bits as one
// at a time. The loads of all the block's triangles and vertices are issued
// together instead of each waiting behind the previous triangle's branches; the
// rest of the test (triangle_hit) runs only for the lanes whose edges the ray
// passes, in leaf order.

// The edge stage's lanes: one AVX register of Real, or eight doubles in one
// AVX-512 register.
#if defined(__AVX512F__)
using L = std::conditional_t<std::is_same_v<Real, float>, F32x8, F64x8>;
#else
using L = std::conditional_t<std::is_same_v<Real, float>, F32x8, F64x4>;
#endif
constexpr int kLanes = L::kLanes;
static_assert(kLanes == int(kLeafBlock), "a leaf block is one register");

struct EdgesN {
    alignas(32) Real ax[kLanes], ay[kLanes], az[kLanes], bx[kLanes], by[kLanes], bz[kLanes], cx[kLanes], cy[kLanes],
        cz[kLanes], u[kLanes], v[kLanes], w[kLanes];
    TriEdges lane(int j) const {
        return {ax[j], ay[j], az[j], bx[j], by[j], bz[j], cx[j], cy[j], cz[j], u[j], v[j], w[j]};
    }
};

// The vertices of a block of triangles, relative to the ray origin, for the edge
// stage: v[k][0..2] = components kx, ky, kz of vertex k of each lane.
struct VerticesN {
    L::V v[3][3];
};

// Vertices of triangles ids[0 .. n) (1 <= n <= kLanes; lanes past n repeat lane
// n - 1) through their indices into Geometry::positions.
inline VerticesN indexed_vertices(const Scene& s, const RayPre& p, const uint32_t ids[kLanes], int n) {
    const int axis[3] = {p.kx, p.ky, p.kz};
    VerticesN r;
#if !defined(RT_REAL_FLOAT) && defined(__AVX512F__)
    // The eight triangles' vertex indices by vertex: v0 of each, v1 of each, v2 of each.
    alignas(32) uint32_t vi[3][kLanes];
    for (int j = 0; j < kLanes; ++j) {
        const uint32_t* v = s.geometry.triangles[ids[j < n ? j : n - 1]].v;
        for (int k = 0; k < 3; ++k) vi[k][j] = v[k];
    }
    const double* base = &s.geometry.positions.data()->x;
    for (int k = 0; k < 3; ++k) {
        const __m512i i64 = _mm512_cvtepu32_epi64(_mm256_load_si256(reinterpret_cast<const __m256i*>(vi[k])));
        const __m512i i3 = _mm512_add_epi64(i64, _mm512_slli_epi64(i64, 1));  // Vec3 = 3 doubles
        for (int c = 0; c < 3; ++c)
            r.v[k][c] = _mm512_sub_pd(_mm512_i64gather_pd(i3, base + axis[c], 8), _mm512_set1_pd(p.org_k[c]));
    }
#elif !defined(RT_REAL_FLOAT)
    // The four triangles' vertex indices, transposed: v0 of each, v1 of each, v2 of each.
    // (Two loads each: a 16-byte load could read past the last 12-byte triangle.)
    __m128i t[4];
    for (int j = 0; j < 4; ++j) {
        const uint32_t* v = s.geometry.triangles[ids[j < n ? j : n - 1]].v;
        t[j] = _mm_insert_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(v)), static_cast<int>(v[2]), 2);
    }
    const __m128i lo01 = _mm_unpacklo_epi32(t[0], t[1]), lo23 = _mm_unpacklo_epi32(t[2], t[3]);
    const __m128i hi01 = _mm_unpackhi_epi32(t[0], t[1]), hi23 = _mm_unpackhi_epi32(t[2], t[3]);
    const __m128i vi[3] = {_mm_unpacklo_epi64(lo01, lo23), _mm_unpackhi_epi64(lo01, lo23),
                           _mm_unpacklo_epi64(hi01, hi23)};
    const double* base = &s.geometry.positions.data()->x;
    for (int k = 0; k < 3; ++k) {
        const __m256i i64 = _mm256_cvtepu32_epi64(vi[k]);
        const __m256i i3 = _mm256_add_epi64(i64, _mm256_slli_epi64(i64, 1));  // Vec3 = 3 doubles
        for (int c = 0; c < 3; ++c)
            r.v[k][c] = _mm256_sub_pd(_mm256_i64gather_pd(base + axis[c], i3, 8), _mm256_set1_pd(p.org_k[c]));
    }
#else
    // Seldom taken: with Real = float the leaf-order copy serves every leaf of
    // triangles only.
    alignas(32) Real c[3][3][kLanes];
    for (int j = 0; j < kLanes; ++j) {
        const Triangle& t = s.geometry.triangles[ids[j < n ? j : n - 1]];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) c[k][a][j] = s.geometry.positions[t.v[k]][axis[a]];
    }
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) r.v[k][a] = L::sub(L::load(c[k][a]), L::set1(p.org_k[a]));
#endif
    return r;
}

// Vertices of the triangles at leaf positions first + j0 .. first + j0 + kLanes of
// the leaf at prims[first, first + n) from Acceleration::leaf_vertices (coordinates
// that equal the positions exactly); lanes past the leaf's end hold other numbers.
template <class T>
inline VerticesN leaf_vertices_n(const T* leaf_vertices, const RayPre& p, uint32_t first, uint32_t n, uint32_t j0) {
    const int axis[3] = {p.kx, p.ky, p.kz};
    VerticesN r;
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            r.v[k][c] =
                L::sub(L::load(leaf_vertices + LeafVertices::at(first, n, j0, k, axis[c])), L::set1(p.org_k[c]));
    return r;
}

// Edge stage of a block of triangles whose first n lanes count; returns the mask
// of those inside whose edges the ray passes (inside_edges), with their values in `e`.
template <bool kCull>
inline int edges_n(const RayPre& p, const VerticesN& vx, int n, EdgesN& e) {
    const L::V sx = L::set1(p.sx), sy = L::set1(p.sy);
    L::V x[3], y[3], z[3];
    for (int k = 0; k < 3; ++k) {
        z[k] = vx.v[k][2];
        x[k] = L::sub(vx.v[k][0], L::mul(sx, z[k]));
        y[k] = L::sub(vx.v[k][1], L::mul(sy, z[k]));
    }
    const L::V u = L::sub(L::mul(x[2], y[1]), L::mul(y[2], x[1]));
    const L::V v = L::sub(L::mul(x[0], y[2]), L::mul(y[0], x[2]));
    const L::V w = L::sub(L::mul(x[1], y[0]), L::mul(y[1], x[0]));
    const int neg = L::any_sign<true>(u, v, w);
    int out;
    if (kCull) {
        out = ~neg;
    } else {
        out = ~(neg & L::any_sign<false>(u, v, w));
    }
    out &= (1 << n) - 1;
    if (out) {
        L::store(e.ax, x[0]);
        L::store(e.ay, y[0]);
        L::store(e.az, z[0]);
        L::store(e.bx, x[1]);
        L::store(e.by, y[1]);
        L::store(e.bz, z[1]);
        L::store(e.cx, x[2]);
        L::store(e.cy, y[2]);
        L::store(e.cz, z[2]);
        L::store(e.u, u);
        L::store(e.v, v);
        L::store(e.w, w);
    }
    return out;
}

// The leaf at prims[first, first + size) from the leaf-order vertices `lv`, as
// test_leaf (below) does.
template <bool kCull, bool kShadow, class T, class Limit, class OnHit>
inline bool test_copied_leaf(const Scene& s, const RayPre& p, const T* lv, uint32_t first, uint32_t size, Real tmin,
                             const Limit& limit, Real w[3], const OnHit& hit) {
    // A leaf's vertices are one block; primitive ids are read only for hits.
    for (uint32_t j0 = 0; j0 < size; j0 += kLanes) {
        const int n = static_cast<int>(std::min<uint32_t>(kLanes, size - j0));
        EdgesN e;
        for (int mask = edges_n<kCull>(p, leaf_vertices_n(lv, p, first, size, j0), n, e); mask; mask &= mask - 1) {
            const int j = __builtin_ctz(mask);
            Real t;
            if (!triangle_hit<kShadow>(p, e.lane(j), tmin, limit(), t, w)) continue;
            const float* corners = nullptr;
            if constexpr (std::is_same_v<T, float>) corners = lv + LeafVertices::at(first, size, j0 + j, 0, 0);
            if (hit(s.accel.bvh.prims[first + j0 + j], t, corners)) return true;
        }
    }
    return false;
}

// Calls hit(id, t, corners) (weights in w) for every primitive of the leaf at
// prims[first] with BvhNode count `count` that the ray hits in (tmin, limit()), in
// leaf order; corners is the triangle's first float in the float leaf-order
// vertices (Hit::corners, with the leaf's size as stride), or null. limit() is read
// again for each test, and hit() returns true to stop early (test_leaf then
// returns true).
template <bool kCull, bool kShadow, class Limit, class OnHit>
inline bool test_leaf(const Scene& s, const RayPre& p, uint32_t first, uint16_t count, Real tmin, const Limit& limit,
                      Real w[3], const OnHit& hit) {
    const uint32_t size = BvhNode::leaf_size_of(count);
    const uint32_t end = first + size;
    // Separate loops per source of vertices: one loop choosing the source per
    // block of four was 3-10% slower (knot_4m_glass render, medians of 5 and 7).
    if (!(count & BvhNode::kIndexedLeaf)) {
        if constexpr (std::is_same_v<Real, double>)
            if (const double* lv = s.accel.leaf_vertices.doubles())
                return test_copied_leaf<kCull, kShadow>(s, p, lv, first, size, tmin, limit, w, hit);
        if (const float* lv = s.accel.leaf_vertices.floats())
            return test_copied_leaf<kCull, kShadow>(s, p, lv, first, size, tmin, limit, w, hit);
    }
    for (uint32_t i = first; i < end; i += kLanes) {
        const int n = static_cast<int>(std::min<uint32_t>(kLanes, end - i));
        uint32_t ids[kLanes];
        bool triangles = true;
        for (int j = 0; j < n; ++j) {
            ids[j] = s.accel.bvh.prims[i + j];
            triangles &= s.geometry.shape_of<true>(ids[j]).kind == ShapeKind::Triangle;
        }
        if (!triangles) {  // other shapes among them: one at a time
            for (int j = 0; j < n; ++j) {
                Real t;
                if (hit_prim<kCull, kShadow>(s, p, ids[j], tmin, limit(), t, w) && hit(ids[j], t, nullptr)) return true;
            }
            continue;
        }
        EdgesN e;
        for (int mask = edges_n<kCull>(p, indexed_vertices(s, p, ids, n), n, e); mask; mask &= mask - 1) {
            const int j = __builtin_ctz(mask);
            Real t;
            if (triangle_hit<kShadow>(p, e.lane(j), tmin, limit(), t, w) && hit(ids[j], t, nullptr)) return true;
        }
    }
    return false;
}
#else
template <bool kCull, bool kShadow, class Limit, class OnHit>
inline bool test_leaf(const Scene& s, const RayPre& p, uint32_t first, uint16_t count, Real tmin, const Limit& limit,
                      Real w[3], const OnHit& hit) {
    const uint32_t end = first + BvhNode::leaf_size_of(count);
    for (uint32_t i = first; i < end; ++i) {
        const uint32_t id = s.accel.bvh.prims[i];
        Real t;
        if (hit_prim<kCull, kShadow>(s, p, id, tmin, limit(), t, w) && hit(id, t, nullptr)) return true;
    }
    return false;
}
#endif

// Starts loading the node a stack entry names while the traversal goes on: the ray
// reaches it after the nearer subtrees, and the traversal mostly waits for node
// loads. Leaves are not prefetched: that measured slower (docs/performance.md).
inline void prefetch_node(const Bvh& bvh, int32_t child) {
    if (child < 0) return;
    const char* p = reinterpret_cast<const char*>(&bvh.nodes[child]);
    for (int line = 0; line < int(sizeof(BvhNode)); line += 64) __builtin_prefetch(p + line);
}

// A node's child links, copied before its box test: the copy's load is issued with
// the boxes' loads instead of waiting for the test's answer to pick a child.
struct NodeLinks {
    alignas(32) int32_t child[kWidth];
    alignas(16) uint16_t count[kWidth];
    explicit NodeLinks(const BvhNode& n) {
        std::memcpy(child, n.child, sizeof child);
        std::memcpy(count, n.count, sizeof count);
    }
};

// A child to visit: on the closest-hit traversals' stacks, and the one they visit next.
struct StackEntry {
    int32_t child;   // node index, or ~first for a leaf
    uint16_t count;  // leaf size
    uint16_t rays;   // packet traversal only: the rays that entered it (bit r: ray r)
    BoxReal t;       // entry distance (a packet's: the least of its rays'), to skip entries beyond the best hit
};

// The closest-hit search of one ray: its best hit so far and the limits that
// follow from it. The single-ray traversal and the packet traversal drive it; the
// answer is the hit of least t, ties to the lower id, whichever leaves are tested
// in whichever order, so both give the same hit.
template <bool kCull>
struct ClosestSearch {
    const Scene* s = nullptr;
    RayPre p;
    BoxRay br;
    Real tmin = 0;
    bool found = false;
    Real best_t = 0;
    uint32_t best_id = ~0u;  // primitive id (Geometry::shape_of)
    Real w[3] = {0, 0, 0};   // the last primitive test's weights; spheres leave them untouched
    Real best_w[3] = {0, 0, 0};
    // Primitive tests accept t <= best_t, so ties reach consider() and are settled by
    // id: their range ends at next_up(best_t), kept here as best_t changes rather than
    // computed for every primitive test.
    Real prim_limit = 0;
    BoxReal box_lim = 0;  // box_limit(), kept here as best_t changes
    const float* best_corners = nullptr;
    uint32_t best_stride = 0;

    void start(const Scene& scene, const Ray& ray, Real t0, Real t1) {
        s = &scene;
        p = prepare(ray);
        tmin = t0;
        best_t = prim_limit = t1;
        box_lim = BoxReal(t1);
        if (!scene.accel.bvh.nodes.empty()) br = box_ray(p, scene.accel.bvh, t0);
    }
    void consider(uint32_t gid, Real t, const float* corners, uint32_t stride) {
        // Ties in t go to the lower id, so the answer does not depend on the BVH.
        if (t < best_t || (t == best_t && gid < best_id)) {
            if (t != best_t) prim_limit = next_up(t);
            best_t = t;
            box_lim = BoxReal(t * kTieSlack);
            best_id = gid;
            best_corners = corners;
            best_stride = stride;
            // Shading reads the triangle's record: start loading it while the
            // traversal goes on.
            if (corners) __builtin_prefetch(&s->geometry.triangles[gid]);
            best_w[0] = w[0];
            best_w[1] = w[1];
            best_w[2] = w[2];
            found = true;
        }
    }
    // Boxes get more slack: the entry distance of a flat box around a primitive hit at
    // exactly best_t can round a few ulps above it (kTieSlack covers the error of both
    // the slab distances and the triangle's t).
    BoxReal box_limit() const { return box_lim; }
    int test_node(const BvhNode& n, BoxReal t[kWidth]) const {
        return test_boxes(n, br, BoxReal(tmin), box_limit(), t);
    }
    void test_leaf_at(uint32_t first, uint16_t count) {
        test_leaf<kCull, false>(
            *s, p, first, count, tmin, [this] { return prim_limit; }, w,
            [this, count](uint32_t id, Real t, const float* corners) {
                consider(id, t, corners, BvhNode::leaf_size_of(count));
                return false;
            });
    }
    // The unbounded shapes, outside the BVH; then the answer into `hit`.
    bool finish(Hit& hit) {
        for_each_shape([&](auto k) {
            using S = decltype(k);
            if constexpr (!S::kBounded) {
                const std::vector<S>& shapes = s->geometry.all<S>();
                const uint32_t base = s->geometry.first_id(kind_of<S>);
                for (size_t i = 0; i < shapes.size(); ++i) {
                    Real t;
                    if (shapes[i].intersect(p.ray, tmin, prim_limit, t))
                        consider(base + static_cast<uint32_t>(i), t, nullptr, 0);
                }
            }
        });
        if (!found) return false;
        hit.t = best_t;
        const ShapeRef shape = s->geometry.shape_of(best_id);
        hit.kind = shape.kind;
        hit.index = shape.index;
        hit.w[0] = best_w[0];
        hit.w[1] = best_w[1];
        hit.w[2] = best_w[2];
        hit.corners = best_corners;
        hit.stride = best_stride;
        return true;
    }
};

// The hit children of a node, farthest first, by entry distance t: their count.
inline int order_far_to_near(int mask, const BoxReal t[kWidth], int order[kWidth]) {
    int k = 0;
    while (mask) {
        const int i = __builtin_ctz(mask);
        mask &= mask - 1;
        int j = k++;
        while (j > 0 && t[order[j - 1]] < t[i]) {
            order[j] = order[j - 1];
            --j;
        }
        order[j] = i;
    }
    return k;
}

template <bool kCull>
bool closest(const Scene& s, const Ray& ray, Real tmin, Real tmax, Hit& hit) {
    ClosestSearch<kCull> q;
    q.start(s, ray, tmin, tmax);
    if (!s.accel.bvh.nodes.empty()) {
        StackEntry stack[kStackSize];
        int sp = 0;
        // The nearest hit child is visited next without a trip through the stack;
        // the others are pushed far to near.
        StackEntry e{0, 0, 0, BoxReal(tmin)};
        for (;;) {
            if (e.child < 0) {
                q.test_leaf_at(~static_cast<uint32_t>(e.child), e.count);
            } else {
                const BvhNode& n = s.accel.bvh.nodes[e.child];
                const NodeLinks links(n);
                alignas(kBoxesAlign) BoxReal t[kWidth];
                int order[kWidth];
                const int k = order_far_to_near(q.test_node(n, t), t, order);
                if (k > 0) {
                    for (int j = 0; j + 1 < k; ++j) {
                        const int i = order[j];
                        stack[sp++] = {links.child[i], links.count[i], 0, t[i]};
                        prefetch_node(s.accel.bvh, links.child[i]);
                    }
                    const int i = order[k - 1];
                    e = {links.child[i], links.count[i], 0, t[i]};
                    continue;
                }
            }
            // Next from the stack, skipping entries beyond the best hit so far.
            while (sp > 0 && stack[sp - 1].t > q.box_limit()) --sp;
            if (sp == 0) break;
            e = stack[--sp];
        }
    }
    return q.finish(hit);
}

// The packet traversal: up to kPacket rays walk the tree together, each node and
// leaf loaded once for all of them. Each ray tests a node's boxes itself, enters
// only the children its own test enters and tests only those leaves, so its hit is
// the one closest() finds; the packet visits a child when any of its rays enters it,
// nearest first by the least entry distance among them.
template <bool kCull>
void closest_packet(const Scene& s, const Ray* rays, int n_rays, Real tmin, Real tmax, Hit* hits, bool* found) {
    ClosestSearch<kCull> q[kPacket];
    for (int r = 0; r < n_rays; ++r) q[r].start(s, rays[r], tmin, tmax);
    if (!s.accel.bvh.nodes.empty()) {
        StackEntry stack[kStackSize];
        int sp = 0;
        StackEntry e{0, 0, static_cast<uint16_t>((1u << n_rays) - 1), BoxReal(tmin)};
        for (;;) {
            if (e.child < 0) {
                for (unsigned m = e.rays; m; m &= m - 1)
                    q[__builtin_ctz(m)].test_leaf_at(~static_cast<uint32_t>(e.child), e.count);
            } else {
                const BvhNode& n = s.accel.bvh.nodes[e.child];
                const NodeLinks links(n);
                unsigned child_rays[kWidth] = {};
                BoxReal tc[kWidth];
                int any = 0;
                for (unsigned m = e.rays; m; m &= m - 1) {
                    const int r = __builtin_ctz(m);
                    alignas(kBoxesAlign) BoxReal t[kWidth];
                    const int hit = q[r].test_node(n, t);
                    for (int h = hit; h; h &= h - 1) {
                        const int i = __builtin_ctz(h);
                        tc[i] = (any >> i & 1) ? std::min(tc[i], t[i]) : t[i];
                        child_rays[i] |= 1u << r;
                    }
                    any |= hit;
                }
                int order[kWidth];
                const int k = order_far_to_near(any, tc, order);
                if (k > 0) {
                    for (int j = 0; j + 1 < k; ++j) {
                        const int i = order[j];
                        stack[sp++] = {links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i]), tc[i]};
                        prefetch_node(s.accel.bvh, links.child[i]);
                    }
                    const int i = order[k - 1];
                    e = {links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i]), tc[i]};
                    continue;
                }
            }
            // Next from the stack, with the rays whose best hit so far is not nearer.
            e.rays = 0;
            while (!e.rays && sp > 0) {
                e = stack[--sp];
                unsigned live = 0;
                for (unsigned m = e.rays; m; m &= m - 1) {
                    const int r = __builtin_ctz(m);
                    if (!(e.t > q[r].box_limit())) live |= 1u << r;
                }
                e.rays = static_cast<uint16_t>(live);
            }
            if (!e.rays) break;
        }
    }
    for (int r = 0; r < n_rays; ++r) found[r] = q[r].finish(hits[r]);
}

}  // namespace

double box_padding(const Bvh& bvh, const Ray& ray) {
#if defined(RT_REAL_FLOAT)
    return box_pad(bvh, ray);
#else
    (void)bvh, (void)ray;
    return 0;
#endif
}

int test_node_boxes(const Bvh& bvh, const BvhNode& node, const Ray& ray, Real tmin, Real tmax, Real t[kWidth],
                    bool scalar) {
    const BoxRay br = box_ray(prepare(ray), bvh, tmin);
    alignas(kBoxesAlign) BoxReal bt[kWidth];
    const int mask = scalar ? test_scalar(node, br, BoxReal(tmin), BoxReal(tmax), bt)
                            : test_boxes(node, br, BoxReal(tmin), BoxReal(tmax), bt);
    for (int i = 0; i < kWidth; ++i) t[i] = Real(bt[i]);
    return mask;
}

bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit) {
    return cull ? closest<true>(scene, ray, tmin, tmax, hit) : closest<false>(scene, ray, tmin, tmax, hit);
}

void closest_hits(const Scene& scene, const Ray* rays, int n, Real tmin, Real tmax, bool cull, Hit* hits, bool* found) {
    if (cull)
        closest_packet<true>(scene, rays, n, tmin, tmax, hits, found);
    else
        closest_packet<false>(scene, rays, n, tmin, tmax, hits, found);
}

namespace {

// What any_hit and any_hits know of a shadow ray before the traversal.
enum class BeforeTree {
    Blocked,   // by an unbounded shape (outside the BVH) or by the hint
    Clear,     // and the tree is empty
    Traverse,  // the tree decides: p and br are set
};

inline BeforeTree any_hit_before_tree(const Scene& s, const Ray& ray, Real tmin, Real tmax, const uint32_t* occluder,
                                      RayPre& p, BoxRay& br) {
    bool blocked = false;
    for_each_shape([&](auto k) {
        using S = decltype(k);
        if constexpr (!S::kBounded) {
            for (const S& shape : s.geometry.all<S>()) {
                Real t;
                if (!blocked && shape.intersect(ray, tmin, tmax, t)) blocked = true;
            }
        }
    });
    if (blocked) return BeforeTree::Blocked;
    if (s.accel.bvh.nodes.empty()) return BeforeTree::Clear;
    p = prepare(ray);
    if (occluder && *occluder != kNoOccluder) {
        Real t, w[3];
        if (hit_prim<false, true>(s, p, *occluder, tmin, tmax, t, w)) return BeforeTree::Blocked;
    }
    br = box_ray(p, s.accel.bvh, tmin);
    return BeforeTree::Traverse;
}

}  // namespace

bool any_hit(const Scene& s, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder) {
    RayPre p;
    BoxRay br;
    const BeforeTree before = any_hit_before_tree(s, ray, tmin, tmax, occluder, p, br);
    if (before != BeforeTree::Traverse) return before == BeforeTree::Blocked;
    Real w[3];
    int32_t stack[kStackSize];
    uint16_t counts[kStackSize];
    int sp = 0;
    // One hit child is visited next without a trip through the stack.
    int32_t child = 0;
    uint16_t count = 0;
    for (;;) {
        if (child < 0) {
            const uint32_t first = ~static_cast<uint32_t>(child);
            if (test_leaf<false, true>(
                    s, p, first, count, tmin, [&] { return tmax; }, w,
                    [&](uint32_t id, Real, const float*) {
                        if (occluder) *occluder = id;
                        return true;
                    }))
                return true;
        } else {
            const BvhNode& n = s.accel.bvh.nodes[child];
            const NodeLinks links(n);
            alignas(kBoxesAlign) BoxReal t[kWidth];
            int mask = test_boxes(n, br, BoxReal(tmin), BoxReal(tmax), t);
            if (mask) {
                for (;;) {
                    const int i = __builtin_ctz(mask);
                    mask &= mask - 1;
                    if (!mask) {
                        child = links.child[i];
                        count = links.count[i];
                        break;
                    }
                    stack[sp] = links.child[i];
                    counts[sp++] = links.count[i];
                    prefetch_node(s.accel.bvh, links.child[i]);
                }
                continue;
            }
        }
        if (sp == 0) return false;
        --sp;
        child = stack[sp];
        count = counts[sp];
    }
}

// The packet traversal of any_hit: the queries' rays walk the tree together, each
// node and leaf loaded once for all of them. Each ray tests a node's boxes itself and
// enters only the children its own test enters, and a ray leaves the packet once it
// is blocked, so each answer is any_hit's. Children are visited in any_hit's order.
void any_hits(const Scene& s, const ShadowQuery* queries, int n, bool* hit) {
    if (n == 1) {
        hit[0] = any_hit(s, queries[0].ray, queries[0].tmin, queries[0].tmax, queries[0].occluder);
        return;
    }
    RayPre p[kPacket];
    BoxRay br[kPacket];
    unsigned live = 0;  // bit r: query r is still open
    for (int r = 0; r < n; ++r) {
        const ShadowQuery& q = queries[r];
        const BeforeTree before = any_hit_before_tree(s, q.ray, q.tmin, q.tmax, q.occluder, p[r], br[r]);
        hit[r] = before == BeforeTree::Blocked;
        if (before == BeforeTree::Traverse) live |= 1u << r;
    }
    if (!live) return;
    struct Entry {
        int32_t child;
        uint16_t count;
        uint16_t rays;  // the rays that entered it (bit r: query r)
    };
    Entry stack[kStackSize];
    int sp = 0;
    Entry e{0, 0, static_cast<uint16_t>(live)};
    for (;;) {
        if (e.child < 0) {
            const uint32_t first = ~static_cast<uint32_t>(e.child);
            for (unsigned m = e.rays; m; m &= m - 1) {
                const int r = __builtin_ctz(m);
                const ShadowQuery& q = queries[r];
                Real w[3];
                if (test_leaf<false, true>(
                        s, p[r], first, e.count, q.tmin, [&q] { return q.tmax; }, w,
                        [&q](uint32_t id, Real, const float*) {
                            if (q.occluder) *q.occluder = id;
                            return true;
                        })) {
                    hit[r] = true;
                    live &= ~(1u << r);
                }
            }
            if (!live) return;
        } else {
            const BvhNode& node = s.accel.bvh.nodes[e.child];
            const NodeLinks links(node);
            unsigned child_rays[kWidth] = {};
            int any = 0;
            for (unsigned m = e.rays; m; m &= m - 1) {
                const int r = __builtin_ctz(m);
                alignas(kBoxesAlign) BoxReal t[kWidth];
                const int mask = test_boxes(node, br[r], BoxReal(queries[r].tmin), BoxReal(queries[r].tmax), t);
                for (int h = mask; h; h &= h - 1) child_rays[__builtin_ctz(h)] |= 1u << r;
                any |= mask;
            }
            if (any) {
                for (;;) {
                    const int i = __builtin_ctz(any);
                    any &= any - 1;
                    const Entry c{links.child[i], links.count[i], static_cast<uint16_t>(child_rays[i])};
                    if (!any) {
                        e = c;
                        break;
                    }
                    stack[sp++] = c;
                    prefetch_node(s.accel.bvh, c.child);
                }
                continue;
            }
        }
        // Next from the stack, with the rays not blocked since it was pushed.
        e.rays = 0;
        while (!e.rays && sp > 0) {
            e = stack[--sp];
            e.rays &= live;
        }
        if (!e.rays) return;
    }
}

}  // namespace rt
