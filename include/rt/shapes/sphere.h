// A sphere (spec 3, "Sphere"), built from its SphereDesc (rt/loader/shape_descs.h).
// Under Transformations it stays a sphere in its own space and is intersected there,
// so a non-uniform scaling makes an exact ellipsoid (docs/transformations.md).
#pragma once
#include <algorithm>
#include <cmath>
#include <utility>

#include "rt/bvh/bvh.h"
#include "rt/core/affine.h"
#include "rt/shapes/shape.h"

namespace rt {

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
    if (t0 > tmin && t0 < tmax) {
        t = t0;
        return true;
    }
    if (t1 > tmin && t1 < tmax) {
        t = t1;
        return true;
    }
    return false;
}

struct Sphere {
    using Desc = SphereDesc;
    static constexpr bool kBounded = true;

    Vec3 center;
    Real radius;
    uint32_t material;
    // Transformed: world -> the space where it is the unit sphere about the origin.
    bool transformed = false;
    Affine to_unit;
    // MotionBlur: at time t of a ray it is moved by motion * t (world space).
    bool moving = false;
    Vec3 motion;

    static Sphere build(const Desc& d, const BuildInputs&) {
        Sphere s{d.center, d.radius, d.material, false, Affine{}, !is_still(d.motion), d.motion};
        if (!d.transform.is_identity()) {
            s.transformed = true;
            s.to_unit = Affine::scaling(1 / double(d.radius), 1 / double(d.radius), 1 / double(d.radius)) *
                        Affine::translation(-double(d.center.x), -double(d.center.y), -double(d.center.z)) *
                        d.transform.inverse();
        }
        return s;
    }

    // Around every place it takes over the shutter.
    Box bounds() const { return moving ? swept(still_bounds(), motion) : still_bounds(); }
    Box still_bounds() const {
        if (transformed) {  // the unit cube about the unit sphere, moved to the world
            const Affine to_world = to_unit.inverse();
            Vec3 lo{Real(HUGE_VAL), Real(HUGE_VAL), Real(HUGE_VAL)}, hi = -lo;
            for (int c = 0; c < 8; ++c) {
                const Vec3 p = to_world.point(
                    {c & 1 ? Real(1) : Real(-1), c & 2 ? Real(1) : Real(-1), c & 4 ? Real(1) : Real(-1)});
                lo = vmin(lo, p);
                hi = vmax(hi, p);
            }
            return Box::around(lo, hi);
        }
        const Vec3 r{radius, radius, radius};
        return Box::around(center - r, center + r);
    }
    // A moving sphere is tested where it is at the ray's time, and keeps how far it
    // moved in w for surface().
    template <bool kCull, bool kShadow>
    bool intersect(const Ray& ray, Real tmin, Real tmax, Real& t, Real* w, uint32_t&) const {
        if (moving) {
            const Vec3 shift = motion * ray.time;
            w[0] = shift.x;
            w[1] = shift.y;
            w[2] = shift.z;
            return intersect_still({ray.org - shift, ray.dir, ray.time}, tmin, tmax, t);
        }
        return intersect_still(ray, tmin, tmax, t);
    }
    bool intersect_still(const Ray& ray, Real tmin, Real tmax, Real& t) const {
        if (!transformed) return intersect_sphere(ray, center, radius, tmin, tmax, t);
        // In the unit sphere's space the direction has length `len`, so the unit-speed
        // distance s there is t * len.
        const Vec3 d = to_unit.vector(ray.dir);
        const Real len = length(d);
        Real s;
        if (!intersect_sphere({to_unit.point(ray.org), d / len}, Vec3{0, 0, 0}, 1, tmin * len, tmax * len, s))
            return false;
        t = s / len;
        return t > tmin && t < tmax;
    }
    Surface surface(Vec3 p, const Real* w, uint32_t) const {
        if (moving) p = p - Vec3{w[0], w[1], w[2]};
        if (transformed) {
            const Vec3 n = normalize(to_unit.transposed_vector(to_unit.point(p)));
            return {n, n, material};
        }
        const Vec3 n = (p - center) / radius;
        return {n, n, material};
    }

    template <class Add>
    static void extent(const Desc& d, const std::vector<MeshDesc>&, Add&& add) {
        for (int c = 0; c < 8; ++c)
            add(d.transform.point(d.center + Vec3{c & 1 ? d.radius : -d.radius, c & 2 ? d.radius : -d.radius,
                                                  c & 4 ? d.radius : -d.radius}));
    }
    // A UV sphere: rings of constant polar angle from +y; quads (a b c d) run along the
    // ring, then down: counter-clockwise seen from outside.
    static Polygons polygons(const Desc& d, const ExportFrame& f) {
        const int segments = std::max(f.segments, 3);
        const int rings = std::max(segments / 2, 2);
        Polygons out;
        out.smooth = true;
        out.vertices.push_back(d.center + Vec3{0, d.radius, 0});
        for (int r = 1; r < rings; ++r) {
            const Real theta = kPi * Real(r) / Real(rings);
            for (int k = 0; k < segments; ++k) {
                const Real phi = 2 * kPi * Real(k) / Real(segments);
                out.vertices.push_back(
                    d.center +
                    Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)} * d.radius);
            }
        }
        const uint32_t south = static_cast<uint32_t>(out.vertices.size());
        out.vertices.push_back(d.center - Vec3{0, d.radius, 0});
        auto at = [&](int r, int k) { return uint32_t(1 + (r - 1) * segments + k % segments); };
        for (int k = 0; k < segments; ++k) out.faces.push_back({0, at(1, k + 1), at(1, k)});
        for (int r = 1; r + 1 < rings; ++r)
            for (int k = 0; k < segments; ++k)
                out.faces.push_back({at(r, k), at(r, k + 1), at(r + 1, k + 1), at(r + 1, k)});
        for (int k = 0; k < segments; ++k) out.faces.push_back({at(rings - 1, k), at(rings - 1, k + 1), south});
        out.move(d.transform);
        return out;
    }
};

}  // namespace rt
