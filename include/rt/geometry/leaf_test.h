// The leaf kernels of the BVH traversal: the primitives of one leaf against one ray,
// for closest.cpp and any_hit.cpp. With AVX2, leaves of triangles run the edge stage
// of the watertight test one register of triangles at a time (rt/bvh/lanes.h).
// Header-only and forced inline: the kernels run in the traversal's inner loops.
#pragma once
#include <algorithm>
#include <cstdint>
#include <type_traits>

#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"
#include "rt/bvh/lanes.h"
#include "rt/geometry/scene.h"

namespace rt::traversal {

// Tests one BVH primitive; returns true with t (and weights, and an instance's part) on
// a hit in (tmin, tmax).
template <bool kCull, bool kShadow = false>
[[gnu::always_inline]] inline bool hit_prim(const Scene& s, const RayPre& p, uint32_t id, Real tmin, Real tmax, Real& t,
                                            Real w[3], uint32_t& part) {
    return s.geometry.intersect<kCull, kShadow>(p, s.geometry.shape_of<true>(id), tmin, tmax, t, w, part);
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
using LeafLanes = std::conditional_t<std::is_same_v<Real, float>, F32x8, F64x8>;
#else
using LeafLanes = std::conditional_t<std::is_same_v<Real, float>, F32x8, F64x4>;
#endif
constexpr int kLeafLanes = LeafLanes::kLanes;
static_assert(kLeafLanes == int(kLeafBlock), "a leaf block is one register");

struct EdgesN {
    alignas(32) Real ax[kLeafLanes], ay[kLeafLanes], az[kLeafLanes], bx[kLeafLanes], by[kLeafLanes], bz[kLeafLanes],
        cx[kLeafLanes], cy[kLeafLanes], cz[kLeafLanes], u[kLeafLanes], v[kLeafLanes], w[kLeafLanes];
    TriEdges lane(int j) const {
        return {ax[j], ay[j], az[j], bx[j], by[j], bz[j], cx[j], cy[j], cz[j], u[j], v[j], w[j]};
    }
};

// The vertices of a block of triangles, relative to the ray origin, for the edge
// stage: v[k][0..2] = components kx, ky, kz of vertex k of each lane.
struct VerticesN {
    LeafLanes::V v[3][3];
};

// Vertices of triangles ids[0 .. n) (1 <= n <= kLeafLanes; lanes past n repeat lane
// n - 1) through their indices into Geometry::positions.
inline VerticesN indexed_vertices(const Scene& s, const RayPre& p, const uint32_t ids[kLeafLanes], int n) {
    const int axis[3] = {p.kx, p.ky, p.kz};
    VerticesN r;
#if !defined(RT_REAL_FLOAT) && defined(__AVX512F__)
    // The eight triangles' vertex indices by vertex: v0 of each, v1 of each, v2 of each.
    alignas(32) uint32_t vi[3][kLeafLanes];
    for (int j = 0; j < kLeafLanes; ++j) {
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
    alignas(32) Real c[3][3][kLeafLanes];
    for (int j = 0; j < kLeafLanes; ++j) {
        const Triangle& t = s.geometry.triangles[ids[j < n ? j : n - 1]];
        for (int k = 0; k < 3; ++k)
            for (int a = 0; a < 3; ++a) c[k][a][j] = s.geometry.positions[t.v[k]][axis[a]];
    }
    for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) r.v[k][a] = LeafLanes::sub(LeafLanes::load(c[k][a]), LeafLanes::set1(p.org_k[a]));
#endif
    return r;
}

// Vertices of the triangles at leaf positions first + j0 .. first + j0 + kLeafLanes of
// the leaf at prims[first, first + n) from Acceleration::leaf_vertices (coordinates
// that equal the positions exactly); lanes past the leaf's end hold other numbers.
template <class T>
inline VerticesN leaf_vertices_n(const T* leaf_vertices, const RayPre& p, uint32_t first, uint32_t n, uint32_t j0) {
    const int axis[3] = {p.kx, p.ky, p.kz};
    VerticesN r;
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 3; ++c)
            r.v[k][c] = LeafLanes::sub(LeafLanes::load(leaf_vertices + LeafVertices::at(first, n, j0, k, axis[c])),
                                       LeafLanes::set1(p.org_k[c]));
    return r;
}

// Edge stage of a block of triangles whose first n lanes count; returns the mask
// of those inside whose edges the ray passes (inside_edges), with their values in `e`.
template <bool kCull>
inline int edges_n(const RayPre& p, const VerticesN& vx, int n, EdgesN& e) {
    const LeafLanes::V sx = LeafLanes::set1(p.sx), sy = LeafLanes::set1(p.sy);
    LeafLanes::V x[3], y[3], z[3];
    for (int k = 0; k < 3; ++k) {
        z[k] = vx.v[k][2];
        x[k] = LeafLanes::sub(vx.v[k][0], LeafLanes::mul(sx, z[k]));
        y[k] = LeafLanes::sub(vx.v[k][1], LeafLanes::mul(sy, z[k]));
    }
    const LeafLanes::V u = LeafLanes::sub(LeafLanes::mul(x[2], y[1]), LeafLanes::mul(y[2], x[1]));
    const LeafLanes::V v = LeafLanes::sub(LeafLanes::mul(x[0], y[2]), LeafLanes::mul(y[0], x[2]));
    const LeafLanes::V w = LeafLanes::sub(LeafLanes::mul(x[1], y[0]), LeafLanes::mul(y[1], x[0]));
    const int neg = LeafLanes::any_sign<true>(u, v, w);
    int out;
    if (kCull) {
        out = ~neg;
    } else {
        out = ~(neg & LeafLanes::any_sign<false>(u, v, w));
    }
    out &= (1 << n) - 1;
    if (out) {
        LeafLanes::store(e.ax, x[0]);
        LeafLanes::store(e.ay, y[0]);
        LeafLanes::store(e.az, z[0]);
        LeafLanes::store(e.bx, x[1]);
        LeafLanes::store(e.by, y[1]);
        LeafLanes::store(e.bz, z[1]);
        LeafLanes::store(e.cx, x[2]);
        LeafLanes::store(e.cy, y[2]);
        LeafLanes::store(e.cz, z[2]);
        LeafLanes::store(e.u, u);
        LeafLanes::store(e.v, v);
        LeafLanes::store(e.w, w);
    }
    return out;
}

// The leaf at prims[first, first + size) from the leaf-order vertices `lv`, as
// test_leaf (below) does.
template <bool kCull, bool kShadow, class T, class Limit, class OnHit>
[[gnu::always_inline]] inline bool test_copied_leaf(const Scene& s, const RayPre& p, const T* lv, uint32_t first,
                                                    uint32_t size, Real tmin, const Limit& limit, Real w[3],
                                                    const OnHit& hit) {
    // A leaf's vertices are one block; primitive ids are read only for hits.
    for (uint32_t j0 = 0; j0 < size; j0 += kLeafLanes) {
        const int n = static_cast<int>(std::min<uint32_t>(kLeafLanes, size - j0));
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

// Calls hit(id, t, corners) (weights in w, an instance's triangle in part) for every primitive of the leaf at
// prims[first] with BvhNode count `count` that the ray hits in (tmin, limit()), in
// leaf order; corners is the triangle's first float in the float leaf-order
// vertices (Hit::corners, with the leaf's size as stride), or null. limit() is read
// again for each test, and hit() returns true to stop early (test_leaf then
// returns true).
template <bool kCull, bool kShadow, class Limit, class OnHit>
[[gnu::always_inline]] inline bool test_leaf(const Scene& s, const RayPre& p, uint32_t first, uint16_t count, Real tmin,
                                             const Limit& limit, Real w[3], uint32_t& part, const OnHit& hit) {
    const uint32_t size = BvhNode::leaf_size_of(count);
    const uint32_t end = first + size;
    // Separate loops per source of vertices: one loop choosing the source per block
    // measured slower.
    if (!(count & BvhNode::kIndexedLeaf)) {
        if constexpr (std::is_same_v<Real, double>)
            if (const double* lv = s.accel.leaf_vertices.doubles())
                return test_copied_leaf<kCull, kShadow>(s, p, lv, first, size, tmin, limit, w, hit);
        if (const float* lv = s.accel.leaf_vertices.floats())
            return test_copied_leaf<kCull, kShadow>(s, p, lv, first, size, tmin, limit, w, hit);
    }
    for (uint32_t i = first; i < end; i += kLeafLanes) {
        const int n = static_cast<int>(std::min<uint32_t>(kLeafLanes, end - i));
        uint32_t ids[kLeafLanes];
        bool triangles = true;
        for (int j = 0; j < n; ++j) {
            ids[j] = s.accel.bvh.prims[i + j];
            triangles &= s.geometry.shape_of<true>(ids[j]).kind == ShapeKind::Triangle;
        }
        if (!triangles) {  // other shapes among them: one at a time
            for (int j = 0; j < n; ++j) {
                Real t;
                if (hit_prim<kCull, kShadow>(s, p, ids[j], tmin, limit(), t, w, part) && hit(ids[j], t, nullptr))
                    return true;
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
[[gnu::always_inline]] inline bool test_leaf(const Scene& s, const RayPre& p, uint32_t first, uint16_t count, Real tmin,
                                             const Limit& limit, Real w[3], uint32_t& part, const OnHit& hit) {
    const uint32_t end = first + BvhNode::leaf_size_of(count);
    for (uint32_t i = first; i < end; ++i) {
        const uint32_t id = s.accel.bvh.prims[i];
        Real t;
        if (hit_prim<kCull, kShadow>(s, p, id, tmin, limit(), t, w, part) && hit(id, t, nullptr)) return true;
    }
    return false;
}
#endif

}  // namespace rt::traversal
