// The Whitted integrator (spec 2): what a primary ray brings back, and what it needs.
// The reflectance formulas it applies are in rt/materials/optics.h.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "rt/core/math.h"
#include "rt/core/random.h"
#include "rt/materials/optics.h"

namespace rt {

struct Scene;
struct RayTrace;

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
// `stream`: the path's random numbers (rt/core/random.h: area lights and rough surfaces
// draw from it), or null for the stream of sample 0 of pixel 0 under seed 0.
Vec3 trace_primary(const Scene& scene, const Ray& ray, const TraceOptions& options, TraceCache* cache = nullptr,
                   RayTrace* record = nullptr, SampleStream* stream = nullptr);
// trace_primary for n primary rays at once (1 <= n <= kPacket): the same radiance
// in radiance[0 .. n), their closest hits found by one packet traversal (closest_hits),
// and their points' shadow rays towards each light by another (any_hits).
// streams[i]: ray i's path's random numbers.
void trace_primaries(const Scene& scene, const Ray* rays, int n, const TraceOptions& options, TraceCache* cache,
                     SampleStream* streams, Vec3* radiance);

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
