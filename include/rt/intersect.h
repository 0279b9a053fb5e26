// Ray/primitive intersection and the two scene queries every ray uses:
// closest hit (camera, reflection, refraction rays) and any hit (shadow rays).
#pragma once
#include <cmath>
#include <cstdint>
#include <limits>

#include "rt/math.h"

namespace rt {

struct Scene;

// Per-ray constants of the watertight triangle test (Woop, Benthin, Wald 2013):
// the ray is sheared so that it runs along +z, then edge functions are evaluated
// in 2D. Rays through a shared edge or vertex hit at least one of its triangles.
struct RayPre {
    Ray ray;
    int kx, ky, kz;
    Real sx, sy, sz;
};

inline RayPre prepare(const Ray& r) {
    RayPre p;
    p.ray = r;
    Real ax = std::fabs(r.dir.x), ay = std::fabs(r.dir.y), az = std::fabs(r.dir.z);
    p.kz = (ax > ay) ? (ax > az ? 0 : 2) : (ay > az ? 1 : 2);
    p.kx = (p.kz + 1) % 3;
    p.ky = (p.kx + 1) % 3;
    if (r.dir[p.kz] < 0) std::swap(p.kx, p.ky);  // keep the winding of the projected triangle
    p.sx = r.dir[p.kx] / r.dir[p.kz];
    p.sy = r.dir[p.ky] / r.dir[p.kz];
    p.sz = Real(1) / r.dir[p.kz];
    return p;
}

// gamma(n) = n u / (1 - n u), u the unit roundoff of T: bounds the relative
// error of n chained floating-point operations (Higham; pbrt-v3 3.9.1).
template <class T = Real>
constexpr T gamma_bound(int n) {
    constexpr T u = std::numeric_limits<T>::epsilon() / 2;
    return n * u / (1 - n * u);
}

// Watertight ray/triangle test. On a hit in (tmin, tmax) returns true with the
// distance t and the barycentric weights (w0, w1, w2) of a, b, c.
// With kCull, triangles whose counter-clockwise front faces away from the ray
// are ignored (spec 2.9): the edge functions are then all >= 0 exactly when
// dot(dir, (b - a) x (c - a)) < 0, so culling costs nothing extra.
// With kShadow, a t within rounding error of 0 is no hit (see below).
template <bool kCull = false, bool kShadow = false>
inline bool intersect_triangle(const RayPre& p, Vec3 a, Vec3 b, Vec3 c, Real tmin, Real tmax,
                               Real& t, Real w[3]) {
    const Vec3 A = a - p.ray.org, B = b - p.ray.org, C = c - p.ray.org;
    const Real ax = A[p.kx] - p.sx * A[p.kz], ay = A[p.ky] - p.sy * A[p.kz];
    const Real bx = B[p.kx] - p.sx * B[p.kz], by = B[p.ky] - p.sy * B[p.kz];
    const Real cx = C[p.kx] - p.sx * C[p.kz], cy = C[p.ky] - p.sy * C[p.kz];
    const Real u = cx * by - cy * bx;  // weight of a
    const Real v = ax * cy - ay * cx;  // weight of b
    const Real ww = bx * ay - by * ax;  // weight of c
    if (kCull ? (u < 0 || v < 0 || ww < 0) : ((u < 0 || v < 0 || ww < 0) && (u > 0 || v > 0 || ww > 0)))
        return false;
    const Real det = u + v + ww;
    if (det == 0) return false;
    const Real tz = p.sz * (u * A[p.kz] + v * B[p.kz] + ww * C[p.kz]);
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
        const Real max_zt = std::fabs(p.sz) * std::fmax(std::fabs(A[p.kz]), std::fmax(std::fabs(B[p.kz]), std::fabs(C[p.kz])));
        const Real max_xt = std::fmax(std::fabs(ax), std::fmax(std::fabs(bx), std::fabs(cx)));
        const Real max_yt = std::fmax(std::fabs(ay), std::fmax(std::fabs(by), std::fabs(cy)));
        const Real max_e = std::fmax(std::fabs(u), std::fmax(std::fabs(v), std::fabs(ww)));
        const Real dz = gamma_bound(3) * max_zt;
        const Real dx = gamma_bound(5) * (max_xt + max_zt), dy = gamma_bound(5) * (max_yt + max_zt);
        const Real de = 2 * (gamma_bound(2) * max_xt * max_yt + dy * max_xt + dx * max_yt);
        const Real max_o = std::fmax(std::fabs(p.ray.org.x), std::fmax(std::fabs(p.ray.org.y), std::fabs(p.ray.org.z)));
        const Real dt = 3 * (gamma_bound(3) * max_e * max_zt + de * max_zt + dz * max_e) * std::fabs(inv) +
                        gamma_bound(8) * max_o;
        if (tt <= dt) return false;
    }
    t = tt;
    w[0] = u * inv;
    w[1] = v * inv;
    w[2] = ww * inv;
    return true;
}

// Nearest intersection of a unit-direction ray with a sphere in (tmin, tmax).
// The discriminant is computed as r^2 - |oc - (oc.d) d|^2, which stays accurate
// for small spheres far away (Haines et al., Ray Tracing Gems ch. 7).
inline bool intersect_sphere(const Ray& r, Vec3 centre, Real radius, Real tmin, Real tmax, Real& t) {
    const Vec3 oc = r.org - centre;
    const Real b = dot(oc, r.dir);
    const Vec3 perp = oc - r.dir * b;
    const Real disc = radius * radius - dot(perp, perp);
    if (disc < 0) return false;
    const Real c = dot(oc, oc) - radius * radius;
    // Stable roots: q = -b - sign(b) sqrt(disc); t0 = c / q, t1 = q.
    const Real q = -b - std::copysign(std::sqrt(disc), b);
    Real t0 = q, t1 = (q != 0) ? c / q : q;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > tmin && t0 < tmax) { t = t0; return true; }
    if (t1 > tmin && t1 < tmax) { t = t1; return true; }
    return false;
}

// Infinite plane through `point` with unit `normal`; both sides are hit.
inline bool intersect_plane(const Ray& r, Vec3 point, Vec3 normal, Real tmin, Real tmax, Real& t) {
    const Real denom = dot(r.dir, normal);
    if (denom == 0) return false;
    const Real tt = dot(point - r.org, normal) / denom;
    if (!(tt > tmin && tt < tmax)) return false;
    t = tt;
    return true;
}

enum class HitKind : uint32_t { Triangle, Sphere, Plane };

struct Hit {
    Real t = HUGE_VAL;
    HitKind kind = HitKind::Triangle;
    uint32_t index = 0;  // into Scene::triangles, spheres or planes
    Real w[3] = {0, 0, 0};  // barycentric weights (triangles)
};

// Closest hit in (tmin, tmax). With `cull`, triangles whose geometric normal
// points along the ray are ignored (spec 2.9). Ties in t go to the lower
// primitive id, so the answer does not depend on the BVH layout.
bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit);

// True when anything lies in (tmin, tmax); never culls (spec 2.9: shadow rays).
// `occluder`, when given, is a hint: a BVH primitive id (or kNoOccluder) tested
// before the traversal, and on a BVH hit it receives the id that was found.
// Neighbouring shadow rays are mostly blocked by the same primitive; the answer
// never depends on the hint.
constexpr uint32_t kNoOccluder = ~0u;
bool any_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder = nullptr);

}  // namespace rt
