// An infinite plane (spec 3, "Plane"), built from its PlaneDesc (rt/loader/shape_descs.h),
// its normal normalised. Both sides are hit; it is outside the BVH, so every ray tests
// every plane.
#pragma once
#include <cmath>

#include "rt/bvh/bvh.h"
#include "rt/shapes/shape.h"

namespace rt {

// Infinite plane through `point` with unit `normal`; both sides are hit.
inline bool intersect_plane(const Ray& r, Vec3 point, Vec3 normal, Real tmin, Real tmax, Real& t) {
    const Real denom = dot(r.dir, normal);
    if (denom == 0) return false;
    const Real tt = dot(point - r.org, normal) / denom;
    if (!(tt > tmin && tt < tmax)) return false;
    t = tt;
    return true;
}

struct Plane {
    using Desc = PlaneDesc;
    static constexpr bool kBounded = false;

    Vec3 point, normal;  // normal has unit length
    uint32_t material;

    static Plane build(const Desc& d, const BuildInputs&) { return {d.point, normalize(d.normal), d.material}; }

    Box bounds() const { return {{-HUGE_VALF, -HUGE_VALF, -HUGE_VALF}, {HUGE_VALF, HUGE_VALF, HUGE_VALF}}; }
    template <bool kCull, bool kShadow>
    bool intersect(const Ray& ray, Real tmin, Real tmax, Real& t, Real*, uint32_t&) const {
        return intersect_plane(ray, point, normal, tmin, tmax, t);
    }
    Surface surface(Vec3, const Real*, uint32_t) const { return {normal, normal, material}; }

    template <class Add>
    static void extent(const Desc& d, const std::vector<MeshDesc>&, Add&& add) {
        add(d.point);
    }
    // A square of side 10 x the scene's extent, centred on the scene's centre's
    // projection onto the plane; (-u-v, u-v, u+v, -u+v) is counter-clockwise about n.
    static Polygons polygons(const Desc& d, const ExportFrame& f) {
        const Vec3 n = normalize(d.normal);
        const Vec3 helper = std::fabs(n.x) < Real(0.9) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 u = normalize(cross(n, helper));
        const Vec3 v = cross(n, u);  // u x v = n
        const Vec3 c = f.center - n * dot(f.center - d.point, n);
        const Real h = 5 * f.extent;
        Polygons out;
        out.vertices = {c - u * h - v * h, c + u * h - v * h, c + u * h + v * h, c - u * h + v * h};
        out.faces = {{0, 1, 2, 3}};
        return out;
    }
};

}  // namespace rt
