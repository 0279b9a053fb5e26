// One pixel's ray tree, recorded by the integrator itself (rt/shading/trace.h).
#include "rt/shading/trace.h"

namespace rt {

const char* ray_kind_name(RayKind kind) {
    switch (kind) {
        case RayKind::Camera:
            return "camera";
        case RayKind::Reflection:
            return "reflection";
        case RayKind::Refraction:
            return "refraction";
        case RayKind::Shadow:
            return "shadow";
    }
    return "?";
}

PixelTrace trace_pixel(const Scene& scene, size_t camera, int x, int y, const TraceOptions& options,
                       Rounding rounding) {
    PixelTrace t;
    t.camera = camera;
    t.x = x;
    t.y = y;
    t.rounding = rounding;
    t.min_weight = options.min_weight;
    // The render's own computation (render.cpp): the camera's primary ray, its radiance
    // (trace_primary, which the render's packets, trace_primaries, equal) and quantize;
    // a fresh cache, whose hints never change a result.
    TraceCache cache;
    const Vec3 c = trace_primary(scene, scene.setup.cameras.at(camera).primary_ray(x, y), options, &cache, &t.root);
    t.clamped = {clamp_channel(c.x), clamp_channel(c.y), clamp_channel(c.z)};
    t.pixel[0] = quantize(c.x, rounding);
    t.pixel[1] = quantize(c.y, rounding);
    t.pixel[2] = quantize(c.z, rounding);
    return t;
}

}  // namespace rt
