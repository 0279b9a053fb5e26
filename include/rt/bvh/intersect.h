// The watertight ray/triangle test. The other kinds' tests are in their own files
// (rt/shapes/); the scene queries built on them are in rt/geometry/traverse.h.
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "rt/core/math.h"

namespace rt {

// Per-ray constants of the watertight triangle test (Woop, Benthin, Wald 2013):
// the ray is sheared so that it runs along +z, then edge functions are evaluated
// in 2D. Rays through a shared edge or vertex hit at least one of its triangles.
struct RayPre {
    Ray ray;
    int kx, ky, kz;
    Real sx, sy, sz;
    Real org_k[3];  // ray.org[kx], ray.org[ky], ray.org[kz]
};

// The value of x, which the compiler may not merge with neighbouring loads (an empty
// asm that could have changed it, on x86; elsewhere, the browser build, x itself).
inline Real opaque(Real x) {
#if defined(__x86_64__) || defined(__i386__)
    asm("" : "+x"(x));
#endif
    return x;
}

inline RayPre prepare(const Ray& r) {
    RayPre p;
    // One coordinate at a time: callers have just stored the ray, coordinate by
    // coordinate, and a load spanning several of those stores cannot take their values
    // from the store buffer; it waits for them to reach the cache (a copy as one
    // 32-byte load stalled every traversal call for some 15 cycles).
    p.ray = {{opaque(r.org.x), opaque(r.org.y), opaque(r.org.z)},
             {opaque(r.dir.x), opaque(r.dir.y), opaque(r.dir.z)},
             r.time};
    Real ax = std::fabs(r.dir.x), ay = std::fabs(r.dir.y), az = std::fabs(r.dir.z);
    p.kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    p.kx = (p.kz + 1) % 3;
    p.ky = (p.kx + 1) % 3;
    if (r.dir[p.kz] < 0) std::swap(p.kx, p.ky);  // keep the winding of the projected triangle
    p.sx = r.dir[p.kx] / r.dir[p.kz];
    p.sy = r.dir[p.ky] / r.dir[p.kz];
    p.sz = Real(1) / r.dir[p.kz];
    p.org_k[0] = r.org[p.kx];
    p.org_k[1] = r.org[p.ky];
    p.org_k[2] = r.org[p.kz];
    return p;
}

// gamma(n) = n u / (1 - n u), u the unit roundoff of T: bounds the relative
// error of n chained floating-point operations (Higham; pbrt-v3 3.9.1).
template <class T = Real>
constexpr T gamma_bound(int n) {
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    return n * u / (1 - n * u);
}

// The first stage of the watertight triangle test: the vertices relative to the
// ray origin, sheared (x, y) and unsheared (z), and the three edge functions,
// u, v, w the unnormalised weights of a, b and c. The traversal computes these
// for a register of triangles at once with the same operations (rt/geometry/leaf_test.h), so both
// paths give the same bits.
struct TriEdges {
    Real ax, ay, az, bx, by, bz, cx, cy, cz;
    Real u, v, w;
};

inline TriEdges triangle_edges(const RayPre& p, Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 A = a - p.ray.org, B = b - p.ray.org, C = c - p.ray.org;
    TriEdges e;
    e.az = A[p.kz];
    e.bz = B[p.kz];
    e.cz = C[p.kz];
    e.ax = A[p.kx] - p.sx * e.az;
    e.ay = A[p.ky] - p.sy * e.az;
    e.bx = B[p.kx] - p.sx * e.bz;
    e.by = B[p.ky] - p.sy * e.bz;
    e.cx = C[p.kx] - p.sx * e.cz;
    e.cy = C[p.ky] - p.sy * e.cz;
    e.u = e.cx * e.by - e.cy * e.bx;
    e.v = e.ax * e.cy - e.ay * e.cx;
    e.w = e.bx * e.ay - e.by * e.ax;
    return e;
}

// The ray passes inside the triangle's edges (or on them). With kCull, triangles
// whose counter-clockwise front faces away from the ray are ignored (spec 2.9):
// the edge functions are then all >= 0 exactly when dot(dir, (b - a) x (c - a)) < 0,
// so culling costs nothing extra.
template <bool kCull>
inline bool inside_edges(Real u, Real v, Real w) {
    return kCull ? !(u < 0 || v < 0 || w < 0) : !((u < 0 || v < 0 || w < 0) && (u > 0 || v > 0 || w > 0));
}

// The second stage, for a triangle inside whose edges the ray passes: the
// distance, its range check and the weights. With kShadow, a t within rounding
// error of 0 is no hit (see below).
template <bool kShadow = false>
inline bool triangle_hit(const RayPre& p, const TriEdges& e, Real tmin, Real tmax, Real& t, Real w[3]) {
    const Real det = e.u + e.v + e.w;
    if (det == 0) return false;
    const Real tz = p.sz * (e.u * e.az + e.v * e.bz + e.w * e.cz);
    // Reject hits behind the origin before dividing (t has the sign of tz * det).
    if (det > 0 ? tz <= 0 : tz >= 0) return false;
    const Real inv = Real(1) / det;
    // The range is checked on the t we return, so a caller that asks again with
    // tmax = nextafter(t) gets the same hit (the closest-hit tie-break relies on it).
    const Real tt = tz * inv;
    if (!(tt > tmin && tt < tmax)) return false;
    // For shadow rays, a t within rounding error of 0 is a ray starting on the
    // triangle's plane (offset from a concave edge onto the adjacent face): not an
    // occluder, whatever sign the rounding gave it. The error counted is that of t
    // itself (the bound of pbrt-v3, section 3.9.6) plus that of the origin, a
    // computed hit point moved by ShadowRayEpsilon (a few ulps of its largest
    // coordinate, bounded by gamma(8); the direction has unit length). Only shadow
    // rays pay for it (one bound per occluded ray): on every candidate hit of
    // closest-hit rays it cost 5-10% of render time.
    if (kShadow) {
        const Real max_zt = std::fabs(p.sz) * max_num(std::fabs(e.az), max_num(std::fabs(e.bz), std::fabs(e.cz)));
        const Real max_xt = max_num(std::fabs(e.ax), max_num(std::fabs(e.bx), std::fabs(e.cx)));
        const Real max_yt = max_num(std::fabs(e.ay), max_num(std::fabs(e.by), std::fabs(e.cy)));
        const Real max_e = max_num(std::fabs(e.u), max_num(std::fabs(e.v), std::fabs(e.w)));
        const Real dz = gamma_bound(3) * max_zt;
        const Real dx = gamma_bound(5) * (max_xt + max_zt), dy = gamma_bound(5) * (max_yt + max_zt);
        const Real de = 2 * (gamma_bound(2) * max_xt * max_yt + dy * max_xt + dx * max_yt);
        const Real max_o = max_num(std::fabs(p.ray.org.x), max_num(std::fabs(p.ray.org.y), std::fabs(p.ray.org.z)));
        const Real dt =
            3 * (gamma_bound(3) * max_e * max_zt + de * max_zt + dz * max_e) * std::fabs(inv) + gamma_bound(8) * max_o;
        if (tt <= dt) return false;
    }
    t = tt;
    w[0] = e.u * inv;
    w[1] = e.v * inv;
    w[2] = e.w * inv;
    return true;
}

// Watertight ray/triangle test. On a hit in (tmin, tmax) returns true with the
// distance t and the barycentric weights (w0, w1, w2) of a, b, c. kCull: see
// inside_edges; kShadow: see triangle_hit.
template <bool kCull = false, bool kShadow = false>
inline bool intersect_triangle(const RayPre& p, Vec3 a, Vec3 b, Vec3 c, Real tmin, Real tmax, Real& t, Real w[3]) {
    const TriEdges e = triangle_edges(p, a, b, c);
    return inside_edges<kCull>(e.u, e.v, e.w) && triangle_hit<kShadow>(p, e, tmin, tmax, t, w);
}

}  // namespace rt
