// One pixel's ray tree, recorded by the integrator itself (rt/shading/trace.h).
#include "rt/shading/trace.h"

#include "rt/shading/pixel_samples.h"

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

PixelTrace trace_pixel(const Scene& scene, size_t camera, int x, int y, const TraceOptions& options, Rounding rounding,
                       const SamplingOptions& sampling_options, int sample) {
    PixelTrace t;
    t.camera = camera;
    t.x = x;
    t.y = y;
    t.rounding = rounding;
    t.min_weight = options.min_weight;
    // The render's own computation (render.cpp): the sample's camera ray, its radiance
    // (trace_primary, which the render's packets, trace_primaries, equal) and quantize;
    // with samples, the pixel's mean (sample_pixel; adaptive sampling: its region's,
    // sample_region). A fresh cache, whose hints never change a result.
    TraceCache cache;
    const Camera& cam = scene.setup.cameras.at(camera);
    const PixelSampling sampling = pixel_sampling(scene, camera, sampling_options);
    CameraSample cs = camera_sample(cam, sampling, x, y, sample);
    t.samples = sampling.samples;
    t.sample = sample;
    t.seed = sampling.seed;
    t.sampler = sampling.sampler;
    t.dx = cs.dx;
    t.dy = cs.dy;
    t.lx = cs.lx;
    t.ly = cs.ly;
    t.lens = cam.aperture > 0;
    const Vec3 c = trace_primary(scene, cs.ray, options, &cache, &t.root, &cs.stream);
    t.clamped = {clamp_channel(c.x), clamp_channel(c.y), clamp_channel(c.z)};
    if (sampling.samples > 1 || sampling.noise_target > 0) {
        const PixelValue v = sampling.noise_target > 0
                                 ? sample_pixel_adaptive(scene, cam, sampling, x, y, options, &cache)
                                 : sample_pixel(scene, cam, sampling, x, y, options, &cache);
        t.mean = v.radiance;
        t.taken = v.samples;
    } else {
        t.mean = c;
        t.taken = 1;
    }
    t.pixel[0] = quantize(t.mean.x, rounding);
    t.pixel[1] = quantize(t.mean.y, rounding);
    t.pixel[2] = quantize(t.mean.z, rounding);
    return t;
}

}  // namespace rt
