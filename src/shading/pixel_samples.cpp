#include "rt/shading/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rt/geometry/scene.h"
#include "rt/geometry/traverse.h"
#include "rt/image/image.h"

namespace rt {

PixelSampling pixel_sampling(const Scene& scene, size_t camera, const SamplingOptions& options) {
    const Camera& cam = scene.setup.cameras.at(camera);
    PixelSampling s;
    s.samples = cam.samples;
    s.seed = options.seed;
    s.sampler = options.sampler;
    s.timed = scene.geometry.moves;
    s.random =
        s.samples > 1 || cam.aperture > 0 || s.timed ||
        std::any_of(scene.setup.lights.begin(), scene.setup.lights.end(), [](const Light& l) { return l.sampled(); }) ||
        std::any_of(scene.setup.materials.begin(), scene.setup.materials.end(),
                    [](const Material& m) { return m.roughness > 0; });
    if (options.noise_target > 0 && s.random) {
        s.noise_target = options.noise_target;
        s.max_samples = options.max_samples > 0 ? options.max_samples : kAdaptiveCapFactor * std::max(1, s.samples);
    }
    const int n = static_cast<int>(std::lround(std::sqrt(double(s.samples))));
    s.grid = s.samples > 1 && n * n == s.samples && s.noise_target <= 0 ? n : 0;
    return s;
}

CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k) {
    CameraSample c;
    const uint64_t pixel = uint64_t(y) * uint64_t(cam.width) + uint64_t(x);
    c.stream = SampleStream(sampling.sampler, sampling.seed, pixel, uint32_t(k), uint32_t(sampling.pattern()));
    if (sampling.pattern() > 1) {
        Real u1, u2;
        c.stream.next2(u1, u2);
        if (const int n = sampling.grid) {
            c.dx = (Real(k % n) + u1) / Real(n);
            c.dy = (Real(k / n) + u2) / Real(n);
        } else {
            c.dx = u1;
            c.dy = u2;
        }
    }
    if (cam.aperture > 0) c.stream.next2(c.lx, c.ly);
    const Real time = sampling.timed ? c.stream.next() : Real(0);
    c.ray = cam.sample_ray(x, y, c.dx, c.dy, c.lx, c.ly, time);
    return c;
}

double PixelSum::standard_error() const {
    if (n < 2) return std::numeric_limits<double>::infinity();
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        const double variance = std::max(0.0, (squares[c] - clamped[c] * clamped[c] / n) / (n - 1));
        worst = std::max(worst, variance / n);
    }
    return std::sqrt(worst);
}

void add_samples(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y, int k0, int k1,
                 const TraceOptions& options, TraceCache* cache, PixelSum& acc) {
    for (int k = k0; k < k1; k += kPacket) {
        const int n = std::min(kPacket, k1 - k);
        Ray rays[kPacket];
        SampleStream streams[kPacket];
        for (int i = 0; i < n; ++i) {
            CameraSample c = camera_sample(cam, sampling, x, y, k + i);
            rays[i] = c.ray;
            streams[i] = c.stream;
        }
        Vec3 radiance[kPacket];
        trace_primaries(scene, rays, n, options, cache, streams, radiance);
        for (int i = 0; i < n; ++i) {
            acc.sum += radiance[i];
            const Real rgb[3] = {radiance[i].x, radiance[i].y, radiance[i].z};
            for (int c = 0; c < 3; ++c) {
                const double v = clamp_channel(rgb[c]);
                acc.clamped[c] += v;
                acc.squares[c] += v * v;
            }
        }
        acc.n += n;
    }
}

PixelValue sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                        const TraceOptions& options, TraceCache* cache) {
    PixelSum acc;
    if (sampling.noise_target > 0) {
        // Adaptive: a first few samples, then a packet at a time until the estimate meets
        // the target.
        while (acc.n < sampling.max_samples && !(acc.standard_error() <= sampling.noise_target)) {
            const int batch = acc.n == 0 ? kAdaptiveFirst : kPacket;
            add_samples(scene, cam, sampling, x, y, acc.n, std::min(sampling.max_samples, acc.n + batch), options,
                        cache, acc);
        }
    } else {
        add_samples(scene, cam, sampling, x, y, 0, std::max(1, sampling.samples), options, cache, acc);
    }
    return {acc.sum / Real(acc.n), acc.n};
}

}  // namespace rt
