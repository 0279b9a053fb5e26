// Reflectance formulas (spec 2.6) and the Whitted integrator.
#pragma once
#include "rt/math.h"

namespace rt {

struct Scene;

// Unpolarised Fresnel reflectance of a dielectric interface, light arriving from
// the side with index eta_i at cos_i = cos(angle to the normal) in [0, 1].
// Returns 1 under total internal reflection; sets cos_t when a refracted ray exists.
Real fresnel_dielectric(Real cos_i, Real eta_i, Real eta_t, Real* cos_t = nullptr);

// Exact unpolarised Fresnel reflectance of a conductor with complex index
// n + i k, seen from air (index 1), at cos_i in [0, 1].
Real fresnel_conductor(Real cos_i, Real n, Real k);

// Beer's law (spec 2.6): L(x) = L(0) exp(-c x), per channel.
inline Vec3 beer_attenuation(Vec3 c, Real distance) {
    return {std::exp(-c.x * distance), std::exp(-c.y * distance), std::exp(-c.z * distance)};
}

// The one place secondary rays are born: the origin is pushed `epsilon` along
// `offset_normal` (which the caller points to the side the ray leaves from).
inline Ray spawn_ray(Vec3 p, Vec3 offset_normal, Real epsilon, Vec3 dir) {
    return {p + offset_normal * epsilon, dir};
}

struct TraceOptions {
    bool cull = true;
};

// Radiance (in 0..255 units, unclamped) arriving at the camera along a primary ray.
Vec3 trace_primary(const Scene& scene, const Ray& ray, const TraceOptions& options);

}  // namespace rt
