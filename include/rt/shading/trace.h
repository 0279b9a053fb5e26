// The ray tree of one pixel (raytracer --trace X,Y): every ray the integrator traced for
// it, with what it hit, the lights, Fresnel, Beer's law and the radiance each ray
// returned. The integrator itself records it (trace_primary's `record`), so the tree is
// the render's own computation, never a second one. Format: docs/trace.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/core/math.h"
#include "rt/geometry/scene.h"
#include "rt/image/image.h"
#include "rt/shading/pixel_samples.h"
#include "rt/shading/shading.h"

namespace rt {

const char* ray_kind_name(RayKind kind);  // "camera", "reflection", ...

// One point light at a shaded point (Integrator::local).
struct LightTrace {
    size_t light = 0;     // 0-based, in the scene's order
    Vec3 from;            // the point light, or the point drawn on the area light
    Vec3 scale;           // irradiance times d^2 (rt/geometry/light.h, LightSample)
    Real ndotl = 0;       // n.l with the outward shading normal
    bool facing = false;  // n.l above its rounding noise: the light counts at all
    // The shadow ray (never culled); not traced when the light is within 2 eps of the point.
    bool shadow_traced = false;
    Ray shadow;
    Real shadow_tmax = 0;
    bool shadowed = false;
    bool occluder_found = false;  // the nearest occluder, found by a second (closest-hit) query
    ShapeRef occluder{ShapeKind::Triangle, 0};
    Real occluder_t = 0;
    // When lit: irradiance scale / d^2 (spec 2.8), the Blinn-Phong terms and their sum as added.
    Vec3 irradiance, diffuse, specular, added;
    Real ndoth = 0;
};

// One ray and what it returned.
struct RayTrace {
    RayKind kind = RayKind::Camera;
    int depth = 0;
    Ray ray;
    Real tmin = 0, tmax = 0;  // the interval searched
    bool cull = false;
    int medium = -1;         // the dielectric material it travels inside, or -1
    Real weight = 1;         // what its radiance is multiplied by in the pixel
    Vec3 factor{1, 1, 1};    // what the parent multiplies its radiance by
    bool perturbed = false;  // a rough surface's ray: `ray` turned from `ideal` (Roughness)
    Vec3 ideal;
    bool pruned = false;  // weight below the integrator's threshold: not traced

    bool hit = false;
    ShapeRef shape{ShapeKind::Triangle, 0};
    uint32_t part = 0;  // an instance's hit: the triangle of its mesh (Hit::part)
    Real t = 0;
    Vec3 point, ng, ns;  // ng, ns: outward geometric and shading normals (the side the vertices wind
                         // counter-clockwise around), whichever side the ray came from
    Vec3 nf;             // the shading normal turned towards the incoming ray: secondary rays' offsets
    bool front = true;
    uint32_t material = 0;
    // With culling: the nearest back face the culled query passed over (a second query).
    bool culled = false;
    ShapeRef culled_shape{ShapeKind::Triangle, 0};
    Real culled_t = 0;

    bool shaded = false;  // Blinn-Phong computed (not for dielectrics hit from inside)
    Vec3 ambient, local;  // ambient term, and ambient + every light
    std::vector<LightTrace> lights;

    bool has_fresnel = false;  // conductors and dielectrics
    FresnelTerms fresnel;      // reflectance F (transmittance 1 - F for dielectrics) and its terms
    bool refracts = false;     // dielectric with a refracted ray
    bool tir = false;          // dielectric from the denser side with no refracted ray
    Vec3 refracted;            // refracted direction
    bool depth_limit = false;  // depth reached MaxRecursionDepth: no secondary rays
    bool beer = false;         // inside a dielectric: Beer's law over t
    Vec3 attenuation{1, 1, 1};

    Vec3 radiance;  // returned
    std::vector<RayTrace> children;
};

// A pixel's trace: the tree and the pixel's value.
struct PixelTrace {
    std::string scene;  // the scene file
    size_t camera = 0;  // 0-based
    int x = 0, y = 0;   // column from the left, row from the top
    Rounding rounding = Rounding::Truncate;
    double min_weight = kDefaultMinWeight;  // the options' TraceOptions::min_weight
    RayTrace root;
    Vec3 clamped;        // clamp_channel of root.radiance
    uint8_t pixel[3]{};  // the image's byte: quantize of root.radiance, or of `mean` with samples
    // A camera with samples (rt/shading/pixel_samples.h): the one traced (root), where it
    // fell, and the pixel's mean over all of them, which the image holds.
    int samples = 0;  // 0: the centre ray, no samples
    int sample = 0;
    int taken = 1;  // the samples the pixel's mean is of (adaptive sampling: its own count)
    uint64_t seed = 0;
    SamplerKind sampler = SamplerKind::Random;
    Real dx = Real(0.5), dy = Real(0.5), lx = Real(0.5), ly = Real(0.5);
    bool lens = false;
    Vec3 mean;
};

// Traces pixel (x, y) of camera `camera` (0-based; both in range) as render() does: its
// sample `sample` (0 <= sample < max(1, samples)) under `sampling`.
PixelTrace trace_pixel(const Scene& scene, size_t camera, int x, int y, const TraceOptions& options, Rounding rounding,
                       const SamplingOptions& sampling = {}, int sample = 0);

// The tree as indented text, and as JSON (numbers as %.17g; the 8-bit value at the top
// as "pixel": [r, g, b]).
std::string trace_text(const Scene& scene, const PixelTrace& trace);
std::string trace_json(const Scene& scene, const PixelTrace& trace);

}  // namespace rt
