#include "rt/shading/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

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
        s.first = adaptive_first(s.samples);
    }
    const int n = static_cast<int>(std::lround(std::sqrt(double(s.samples))));
    s.grid = s.samples > 1 && n * n == s.samples && s.noise_target <= 0 ? n : 0;
    return s;
}

CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k) {
    CameraSample c;
    const uint64_t pixel = uint64_t(y) * uint64_t(cam.width) + uint64_t(x);
    c.stream = SampleStream(sampling.sampler, sampling.seed, pixel, uint32_t(k), uint32_t(sampling.pattern()));
    // The camera's numbers, in order: its point in the pixel, on the lens, its time. Under
    // Sobol without the grid, one point of Sobol's first dimensions, so that a moving or
    // defocused edge is stratified across the pixel and the shutter or the lens at once
    // (the grid's cells do that otherwise); else a pair, a pair and one number.
    const bool in_pixel = sampling.pattern() > 1, lens = cam.aperture > 0;
    Real u[5];
    const int dims = (in_pixel ? 2 : 0) + (lens ? 2 : 0) + (sampling.timed ? 1 : 0);
    if (sampling.sampler == SamplerKind::Sobol && !sampling.grid) {
        if (dims > 0) c.stream.sobol_point(u, dims);
    } else {
        Real* q = u;
        for (int pairs = (in_pixel ? 1 : 0) + (lens ? 1 : 0); pairs > 0; --pairs, q += 2) c.stream.next2(q[0], q[1]);
        if (sampling.timed) *q = c.stream.next();
    }
    const Real* next = u;
    if (in_pixel) {
        const int n = sampling.grid;
        c.dx = n ? (Real(k % n) + next[0]) / Real(n) : next[0];
        c.dy = n ? (Real(k / n) + next[1]) / Real(n) : next[1];
        next += 2;
    }
    if (lens) {
        c.lx = next[0];
        c.ly = next[1];
        next += 2;
    }
    const Real time = sampling.timed ? next[0] : Real(0);
    c.ray = cam.sample_ray(x, y, c.dx, c.dy, c.lx, c.ly, time);
    return c;
}

void PixelSum::add(const Vec3& radiance, bool noise) {
    sum += radiance;
    ++n;
    if (!noise) return;
    const double v[3] = {clamp_channel(radiance.x), clamp_channel(radiance.y), clamp_channel(radiance.z)};
    for (int c = 0; c < 3; ++c) {
        clamped[c] += v[c];
        squares[c] += v[c] * v[c];
        block_partial[0][c] += v[c];
    }
    // A block of 2 << b ends here when n is a multiple of it: its sum joins the squares of
    // its level and the partial sum of the next level's block.
    for (int b = 0; b < kBlocks && (n & ((2 << b) - 1)) == 0; ++b)
        for (int c = 0; c < 3; ++c) {
            const double s = block_partial[b][c];
            block_squares[b][c] += s * s;
            if (b + 1 < kBlocks) block_partial[b + 1][c] += s;
            block_partial[b][c] = 0;
        }
}

double PixelSum::standard_error(bool sobol) const {
    if (n < 2) return std::numeric_limits<double>::infinity();
    // The largest block size b with n a multiple of b and n / b >= 4 (sobol), else 1.
    int level = -1;
    if (sobol)
        for (int b = kBlocks - 1; b >= 0 && level < 0; --b)
            if (n % (2 << b) == 0 && n / (2 << b) >= 4) level = b;
    const double size = level < 0 ? 1 : double(2 << level);
    const double m = n / size;  // blocks
    double worst = 0;
    for (int c = 0; c < 3; ++c) {
        // The blocks' sums S_j: the variance of their means S_j / size, over m.
        const double sq = level < 0 ? squares[c] : block_squares[level][c];
        const double variance = std::max(0.0, (sq - clamped[c] * clamped[c] / m) / (size * size) / (m - 1));
        worst = std::max(worst, variance / m);
    }
    return std::sqrt(worst);
}

void add_samples(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y, int k0, int k1,
                 const TraceOptions& options, TraceCache* cache, PixelSum& acc) {
    const bool noise = sampling.noise_target > 0;
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
        for (int i = 0; i < n; ++i) acc.add(radiance[i], noise);
    }
}

PixelValue sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                        const TraceOptions& options, TraceCache* cache) {
    PixelSum acc;
    add_samples(scene, cam, sampling, x, y, 0, std::max(1, sampling.samples), options, cache, acc);
    return {acc.sum / Real(acc.n), acc.n};
}

double judged_noise(const double* noise, int w, int h, int x, int y) {
    double around = 0;
    int count = 0;
    for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
            const int qx = x + dx, qy = y + dy;
            if ((dx || dy) && qx >= 0 && qx < w && qy >= 0 && qy < h) {
                around += noise[qy * w + qx];
                ++count;
            }
        }
    const double own = noise[y * w + x];
    return count ? std::max(own, kNeighbourShare * around / count) : own;
}

void sample_region(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x0, int y0, int x1, int y1,
                   const TraceOptions& options, TraceCache* cache, PixelValue* out) {
    const int w = x1 - x0, h = y1 - y0;
    const int cap = sampling.max_samples;
    const bool sobol = sampling.sampler == SamplerKind::Sobol;
    std::vector<PixelSum> acc(static_cast<size_t>(w * h));
    std::vector<double> noise(static_cast<size_t>(w * h));  // per sample: the estimate squared x n
    for (int i = 0; i < w * h; ++i)
        add_samples(scene, cam, sampling, x0 + i % w, y0 + i / w, 0, std::min(cap, sampling.first), options, cache,
                    acc[i]);
    const double target = sampling.noise_target * sampling.noise_target;
    for (bool more = true; more;) {
        for (int i = 0; i < w * h; ++i) {
            const double e = acc[i].standard_error(sobol);
            noise[i] = e * e * acc[i].n;
        }
        more = false;
        for (int i = 0; i < w * h; ++i) {
            if (acc[i].n >= cap) continue;
            const int px = i % w, py = i / w;
            const double v = judged_noise(noise.data(), w, h, px, py);
            if (!(v <= target * acc[i].n)) {
                add_samples(scene, cam, sampling, x0 + px, y0 + py, acc[i].n, std::min(cap, acc[i].n + kPacket),
                            options, cache, acc[i]);
                more = true;
            }
        }
    }
    for (int i = 0; i < w * h; ++i) out[i] = {acc[i].sum / Real(acc[i].n), acc[i].n};
}

PixelValue sample_pixel_adaptive(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                                 const TraceOptions& options, TraceCache* cache) {
    const int x0 = x / kAdaptiveRegion * kAdaptiveRegion, y0 = y / kAdaptiveRegion * kAdaptiveRegion;
    const int x1 = std::min(x0 + kAdaptiveRegion, cam.width), y1 = std::min(y0 + kAdaptiveRegion, cam.height);
    PixelValue out[kAdaptiveRegion * kAdaptiveRegion];
    sample_region(scene, cam, sampling, x0, y0, x1, y1, options, cache, out);
    return out[(y - y0) * (x1 - x0) + (x - x0)];
}

}  // namespace rt
