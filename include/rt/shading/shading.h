// Reflectance formulas (spec 2.6) and the Whitted integrator.
#pragma once
#include <cstdint>
#include <vector>

#include "rt/core/math.h"

namespace rt {

struct Scene;
struct RayTrace;

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

// A reflected or refracted ray is not traced when its weight (what its radiance is
// multiplied by in the pixel: the product of MirrorReflectance x Fresnel, 1 - Fresnel and
// Beer's law along its path) is below the minimum weight; 0 traces every ray to
// MaxRecursionDepth, as the assignment describes. The default moves a few pixels of the
// official images by one level and keeps the ray tree of glass at a deep
// MaxRecursionDepth from growing geometrically (docs/conventions.md, "Weak rays").
constexpr double kDefaultMinWeight = 1e-4;

struct TraceOptions {
    bool cull = true;
    double min_weight = kDefaultMinWeight;
};

// Rays traced, by kind: one camera ray per pixel; one shadow ray per light that
// faces a shaded point from farther than 2 ShadowRayEpsilon; reflection and refraction
// rays as they are spawned.
struct RayCounts {
    uint64_t camera = 0, shadow = 0, reflection = 0, refraction = 0;
    uint64_t total() const { return camera + shadow + reflection + refraction; }
    RayCounts& operator+=(const RayCounts& o) {
        camera += o.camera;
        shadow += o.shadow;
        reflection += o.reflection;
        refraction += o.refraction;
        return *this;
    }
};

// Per-thread state: the last occluder found for each point light (see any_hit),
// which speeds up tracing without changing any result, and the rays traced so far.
// Written for every ray, so it owns its cache lines (no other thread's data shares them).
struct alignas(64) TraceCache {
    std::vector<uint32_t> last_occluder;
    RayCounts rays;
};

// Radiance (in 0..255 units, unclamped) arriving at the camera along a primary ray.
// `record`, when given, receives the ray tree (rt/shading/trace.h); renders pass none.
Vec3 trace_primary(const Scene& scene, const Ray& ray, const TraceOptions& options, TraceCache* cache = nullptr,
                   RayTrace* record = nullptr);
// trace_primary for n primary rays at once (1 <= n <= kPacket): the same radiance
// in radiance[0 .. n), their closest hits found by one packet traversal (closest_hits),
// and their points' shadow rays towards each light by another (any_hits).
void trace_primaries(const Scene& scene, const Ray* rays, int n, const TraceOptions& options, TraceCache* cache,
                     Vec3* radiance);

// x^e for the Blinn-Phong lobe: whole exponents up to 1024 by repeated squaring
// (exact to a few ulps, several times faster than std::pow), others by std::pow.
inline Real phong_pow(Real x, Real e) {
    if (e >= 0 && e <= 1024 && e == std::floor(e)) {
        unsigned n = static_cast<unsigned>(e);
        Real result = 1, base = x;
        while (n) {
            if (n & 1u) result *= base;
            base *= base;
            n >>= 1;
        }
        return result;
    }
    return std::pow(x, e);
}

}  // namespace rt
