#include "rt/shading/pixel_samples.h"

#include <algorithm>
#include <cmath>

#include "rt/geometry/scene.h"
#include "rt/geometry/traverse.h"

namespace rt {

PixelSampling pixel_sampling(const Scene& scene, size_t camera, uint64_t seed) {
    const Camera& cam = scene.setup.cameras.at(camera);
    PixelSampling s;
    s.samples = cam.samples;
    s.seed = seed;
    s.timed = scene.geometry.moves;
    const int n = static_cast<int>(std::lround(std::sqrt(double(s.samples))));
    s.grid = s.samples > 1 && n * n == s.samples ? n : 0;
    s.random =
        s.samples > 1 || cam.aperture > 0 || s.timed ||
        std::any_of(scene.setup.lights.begin(), scene.setup.lights.end(), [](const Light& l) { return l.sampled(); }) ||
        std::any_of(scene.setup.materials.begin(), scene.setup.materials.end(),
                    [](const Material& m) { return m.roughness > 0; });
    return s;
}

CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k) {
    CameraSample c;
    c.stream = SampleStream(sampling.seed, uint64_t(y) * uint64_t(cam.width) + uint64_t(x), uint32_t(k));
    if (sampling.samples > 1) {
        const Real u1 = c.stream.next(), u2 = c.stream.next();
        if (const int n = sampling.grid) {
            c.dx = (Real(k % n) + u1) / Real(n);
            c.dy = (Real(k / n) + u2) / Real(n);
        } else {
            c.dx = u1;
            c.dy = u2;
        }
    }
    if (cam.aperture > 0) {
        c.lx = c.stream.next();
        c.ly = c.stream.next();
    }
    const Real time = sampling.timed ? c.stream.next() : Real(0);
    c.ray = cam.sample_ray(x, y, c.dx, c.dy, c.lx, c.ly, time);
    return c;
}

Vec3 sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                  const TraceOptions& options, TraceCache* cache) {
    const int total = std::max(1, sampling.samples);
    Vec3 sum;
    for (int k0 = 0; k0 < total; k0 += kPacket) {
        const int n = std::min(kPacket, total - k0);
        Ray rays[kPacket];
        SampleStream streams[kPacket];
        for (int i = 0; i < n; ++i) {
            CameraSample c = camera_sample(cam, sampling, x, y, k0 + i);
            rays[i] = c.ray;
            streams[i] = c.stream;
        }
        Vec3 radiance[kPacket];
        trace_primaries(scene, rays, n, options, cache, streams, radiance);
        for (int i = 0; i < n; ++i) sum += radiance[i];
    }
    return sum / Real(total);
}

}  // namespace rt
