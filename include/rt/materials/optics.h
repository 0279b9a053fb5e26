// What light does at a surface (spec 2.6): the Fresnel equations, Beer's law, and the
// one place secondary rays are born. The material kinds' scatter() and the integrator
// use them.
#pragma once
#include <cmath>

#include "rt/core/math.h"

namespace rt {

// Which Fresnel equations gave a FresnelTerms.
enum class FresnelFormula { Dielectric, Conductor };

// The Fresnel equations at one interface, with the intermediate terms a student checks
// against their own (raytracer --trace prints them).
struct FresnelTerms {
    FresnelFormula formula = FresnelFormula::Dielectric;
    Real eta_i = 1, eta_t = 1;   // index of the incoming side and of the far side (a conductor: n of n + i k)
    Real k = 0;                  // a conductor's absorption index (the imaginary part); 0 for a dielectric
    Real cos_i = 0;              // cosine of the angle of incidence, clamped to [0, 1]
    Real sin_t2 = 0;             // a dielectric's (eta_i / eta_t)^2 (1 - cos_i^2): total internal reflection when >= 1
    Real cos_t = 0;              // a dielectric's cosine of the refraction angle (0 under total internal reflection)
    Real r_par = 0, r_perp = 0;  // reflectances of parallel (p) and perpendicular (s) polarised light
    Real reflectance = 0;        // unpolarised: (r_par + r_perp) / 2
};

// Unpolarised Fresnel reflectance of a dielectric interface, light arriving from
// the side with index eta_i at cos_i = cos(angle to the normal) in [0, 1].
// Reflectance 1 under total internal reflection (r_par = r_perp = 1, cos_t = 0).
FresnelTerms fresnel_dielectric_terms(Real cos_i, Real eta_i, Real eta_t);

// Its reflectance alone; sets cos_t when a refracted ray exists.
inline Real fresnel_dielectric(Real cos_i, Real eta_i, Real eta_t, Real* cos_t = nullptr) {
    const FresnelTerms f = fresnel_dielectric_terms(cos_i, eta_i, eta_t);
    if (cos_t && f.sin_t2 < 1) *cos_t = f.cos_t;
    return f.reflectance;
}

// Exact unpolarised Fresnel reflectance of a conductor with complex index
// n + i k, seen from air (index 1), at cos_i in [0, 1].
FresnelTerms fresnel_conductor_terms(Real cos_i, Real n, Real k);
inline Real fresnel_conductor(Real cos_i, Real n, Real k) { return fresnel_conductor_terms(cos_i, n, k).reflectance; }

// Beer's law (spec 2.6): L(x) = L(0) exp(-c x), per channel.
inline Vec3 beer_attenuation(Vec3 c, Real distance) {
    return {std::exp(-c.x * distance), std::exp(-c.y * distance), std::exp(-c.z * distance)};
}

enum class RayKind { Camera, Reflection, Refraction, Shadow };

// The one place secondary rays are born: the origin is pushed `epsilon` along
// `offset_normal` (which the caller points to the side the ray leaves from).
inline Ray spawn_ray(Vec3 p, Vec3 offset_normal, Real epsilon, Vec3 dir) { return {p + offset_normal * epsilon, dir}; }

}  // namespace rt
