// BVH traversal: closest hit (near child first, fixed stack) and any hit.
// Four child boxes are tested at once, in double precision (AVX when the
// compiler targets it, scalar otherwise), against float bounds rounded outwards.
#include <algorithm>
#include <limits>

#if defined(__AVX__)
#include <immintrin.h>
#endif

#include "rt/intersect.h"
#include "rt/scene.h"

namespace rt {
namespace {

constexpr int kStackSize = 256;  // 3 entries per level at most; the builder bounds depth to ~80
constexpr Real kTieSlack = 1 + 64 * std::numeric_limits<Real>::epsilon();

// Widening of the exit distance that makes the slab test conservative despite
// rounding in (bound - org) * inv_dir (pbrt-v3 section 3.9.2: 1 + 2 gamma(3)).
// Flat boxes (axis-aligned walls) make the slabs meet at one t, so without the
// widening a ray along a wall's edge could miss both walls.
constexpr double kSlabWiden = 1 + 2 * gamma_bound<double>(3);

// Per-ray data of the box test. For each axis the near plane is lo when the
// direction is positive, so the entry is (near - org) * inv and the exit
// (far - org) * inv; a 0 * inf = NaN (ray in a slab's boundary plane, parallel
// to it) then falls out of the max/min below and leaves the interval open.
struct BoxRay {
    double org[3], inv[3];
    int near_is_hi[3];
};

inline BoxRay box_ray(const RayPre& p) {
    BoxRay b;
    for (int a = 0; a < 3; ++a) {
        b.org[a] = p.ray.org[a];
        b.inv[a] = 1.0 / double(p.ray.dir[a]);
        b.near_is_hi[a] = std::signbit(b.inv[a]) ? 1 : 0;
    }
    return b;
}

// Entry distances of the four children into `t` (HUGE_VAL for a miss), and a hit mask.
inline int test4(const Bvh4Node& n, const BoxRay& r, double tmin, double tmax, double t[4]) {
#if defined(__AVX__)
    __m256d tnear = _mm256_set1_pd(tmin), tfar = _mm256_set1_pd(tmax);
    for (int a = 0; a < 3; ++a) {
        const float* nearp = r.near_is_hi[a] ? n.hi[a] : n.lo[a];
        const float* farp = r.near_is_hi[a] ? n.lo[a] : n.hi[a];
        const __m256d o = _mm256_set1_pd(r.org[a]), inv = _mm256_set1_pd(r.inv[a]);
        const __m256d t0 = _mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(_mm_load_ps(nearp)), o), inv);
        const __m256d t1 = _mm256_mul_pd(_mm256_sub_pd(_mm256_cvtps_pd(_mm_load_ps(farp)), o), inv);
        // max/min return their second operand when the first is NaN.
        tnear = _mm256_max_pd(t0, tnear);
        tfar = _mm256_min_pd(_mm256_mul_pd(t1, _mm256_set1_pd(kSlabWiden)), tfar);
    }
    const __m256d hit = _mm256_cmp_pd(tnear, tfar, _CMP_LE_OQ);
    _mm256_storeu_pd(t, _mm256_blendv_pd(_mm256_set1_pd(HUGE_VAL), tnear, hit));
    return _mm256_movemask_pd(hit);
#else
    int mask = 0;
    for (int i = 0; i < 4; ++i) {
        double tn = tmin, tf = tmax;
        for (int a = 0; a < 3; ++a) {
            const double nearv = r.near_is_hi[a] ? n.hi[a][i] : n.lo[a][i];
            const double farv = r.near_is_hi[a] ? n.lo[a][i] : n.hi[a][i];
            const double t0 = (nearv - r.org[a]) * r.inv[a];
            const double t1 = (farv - r.org[a]) * r.inv[a] * kSlabWiden;
            tn = t0 > tn ? t0 : tn;
            tf = t1 < tf ? t1 : tf;
        }
        const bool h = tn <= tf;
        t[i] = h ? tn : HUGE_VAL;
        mask |= h ? 1 << i : 0;
    }
    return mask;
#endif
}

// Tests one BVH primitive; returns true with t (and weights) on a hit in (tmin, tmax).
template <bool kCull, bool kShadow = false>
inline bool hit_prim(const Scene& s, const RayPre& p, uint32_t id, Real tmin, Real tmax, Real& t, Real w[3]) {
    const size_t ntri = s.triangles.size();
    if (id < ntri) {
        const Triangle& tri = s.triangles[id];
        return intersect_triangle<kCull, kShadow>(p, s.positions[tri.v[0]], s.positions[tri.v[1]], s.positions[tri.v[2]],
                                         tmin, tmax, t, w);
    }
    const Sphere& sp = s.spheres[id - ntri];
    return intersect_sphere(p.ray, sp.center, sp.radius, tmin, tmax, t);
}

struct StackEntry {
    int32_t child;   // node index, or ~first for a leaf
    uint16_t count;  // leaf size
    double t;        // entry distance, to skip entries beyond the best hit
};

template <bool kCull>
bool closest(const Scene& s, const Ray& ray, Real tmin, Real tmax, Hit& hit) {
    const RayPre p = prepare(ray);
    bool found = false;
    Real best_t = tmax;
    uint32_t best_id = ~0u;  // global id: BVH primitive id, then planes after them
    Real w[3] = {0, 0, 0};  // spheres leave them untouched
    // Primitive tests accept t <= best_t, so ties reach consider() and are settled by
    // id: their range ends at nextafter(best_t), kept here as best_t changes (a libm
    // call per primitive test cost 3% of render time).
    Real prim_limit = tmax;
    auto consider = [&](uint32_t gid, Real t) {
        // Ties in t go to the lower id, so the answer does not depend on the BVH.
        if (t < best_t || (t == best_t && gid < best_id)) {
            if (t != best_t) prim_limit = std::nextafter(t, Real(HUGE_VAL));
            best_t = t;
            best_id = gid;
            hit.w[0] = w[0];
            hit.w[1] = w[1];
            hit.w[2] = w[2];
            found = true;
        }
    };
    // Boxes get more slack: the entry distance of a flat box around a primitive hit at
    // exactly best_t can round a few ulps above it (kTieSlack covers the error of both
    // the slab distances and the triangle's t).
    auto box_limit = [&]() { return found ? double(best_t * kTieSlack) : double(tmax); };

    if (!s.bvh.nodes.empty()) {
        const BoxRay br = box_ray(p);
        StackEntry stack[kStackSize];
        int sp = 0;
        // The nearest hit child is visited next without a trip through the stack;
        // the others are pushed far to near.
        StackEntry e{0, 0, double(tmin)};
        for (;;) {
            if (e.child < 0) {
                for (uint32_t i = ~static_cast<uint32_t>(e.child), end = i + e.count; i < end; ++i) {
                    const uint32_t id = s.bvh.prims[i];
                    Real t;
                    if (hit_prim<kCull>(s, p, id, tmin, prim_limit, t, w)) consider(id, t);
                }
            } else {
                const Bvh4Node& n = s.bvh.nodes[e.child];
                double t[4];
                int mask = test4(n, br, double(tmin), box_limit(), t);
                int order[4], k = 0;  // hit children, farthest first
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
                if (k > 0) {
                    for (int j = 0; j + 1 < k; ++j) {
                        const int i = order[j];
                        stack[sp++] = {n.child[i], n.count[i], t[i]};
                    }
                    const int i = order[k - 1];
                    e = {n.child[i], n.count[i], t[i]};
                    continue;
                }
            }
            // Next from the stack, skipping entries beyond the best hit so far.
            while (sp > 0 && stack[sp - 1].t > box_limit()) --sp;
            if (sp == 0) break;
            e = stack[--sp];
        }
    }
    const uint32_t base = static_cast<uint32_t>(s.triangles.size() + s.spheres.size());
    for (size_t i = 0; i < s.planes.size(); ++i) {
        Real t;
        if (intersect_plane(ray, s.planes[i].point, s.planes[i].normal, tmin, prim_limit, t))
            consider(base + static_cast<uint32_t>(i), t);
    }
    if (!found) return false;
    hit.t = best_t;
    const size_t ntri = s.triangles.size();
    if (best_id < ntri) {
        hit.kind = HitKind::Triangle;
        hit.index = best_id;
    } else if (best_id < base) {
        hit.kind = HitKind::Sphere;
        hit.index = static_cast<uint32_t>(best_id - ntri);
    } else {
        hit.kind = HitKind::Plane;
        hit.index = best_id - base;
    }
    return true;
}

}  // namespace

bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit) {
    return cull ? closest<true>(scene, ray, tmin, tmax, hit) : closest<false>(scene, ray, tmin, tmax, hit);
}

bool any_hit(const Scene& s, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder) {
    for (const Plane& pl : s.planes) {
        Real t;
        if (intersect_plane(ray, pl.point, pl.normal, tmin, tmax, t)) return true;
    }
    if (s.bvh.nodes.empty()) return false;
    const RayPre p = prepare(ray);
    Real w[3];
    if (occluder && *occluder != kNoOccluder) {
        Real t;
        if (hit_prim<false, true>(s, p, *occluder, tmin, tmax, t, w)) return true;
    }
    const BoxRay br = box_ray(p);
    int32_t stack[kStackSize];
    uint16_t counts[kStackSize];
    int sp = 0;
    // One hit child is visited next without a trip through the stack.
    int32_t child = 0;
    uint16_t count = 0;
    for (;;) {
        if (child < 0) {
            for (uint32_t i = ~static_cast<uint32_t>(child), end = i + count; i < end; ++i) {
                Real t;
                if (hit_prim<false, true>(s, p, s.bvh.prims[i], tmin, tmax, t, w)) {
                    if (occluder) *occluder = s.bvh.prims[i];
                    return true;
                }
            }
        } else {
            const Bvh4Node& n = s.bvh.nodes[child];
            double t[4];
            int mask = test4(n, br, double(tmin), double(tmax), t);
            if (mask) {
                for (;;) {
                    const int i = __builtin_ctz(mask);
                    mask &= mask - 1;
                    if (!mask) {
                        child = n.child[i];
                        count = n.count[i];
                        break;
                    }
                    stack[sp] = n.child[i];
                    counts[sp++] = n.count[i];
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

}  // namespace rt
