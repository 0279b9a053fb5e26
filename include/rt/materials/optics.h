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

// A rough surface's secondary ray direction (Roughness; docs/conventions.md,
// "Assignment 3"): the ideal direction r (unit length) moved by roughness * (xi - 1/2) along
// each of two unit vectors orthogonal to it and to each other, and renormalised; xi1 and
// xi2 uniform in [0, 1).
inline Vec3 perturb_direction(Vec3 r, Real roughness, Real xi1, Real xi2) {
    // The axis of r's smallest component is the farthest from r: a stable cross product.
    const Real ax = std::fabs(r.x), ay = std::fabs(r.y), az = std::fabs(r.z);
    const Vec3 axis = ax <= ay && ax <= az ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
    const Vec3 u = normalize(cross(r, axis));
    const Vec3 v = cross(r, u);
    return normalize(r + (u * (xi1 - Real(0.5)) + v * (xi2 - Real(0.5))) * roughness);
}

}  // namespace rt
