// The per-pixel sample loop of distribution ray tracing (docs/conventions.md,
// "Assignment 3"), which the render, --trace and the page share: where sample k of a
// pixel falls, on the lens and in the shutter, its random numbers, and the pixel's mean.
#pragma once
#include <cstdint>

#include "rt/camera/camera.h"
#include "rt/core/random.h"
#include "rt/shading/shading.h"

namespace rt {

struct Scene;

// The seed of a run without --seed, and the largest seed --seed and the page take.
constexpr uint64_t kDefaultSeed = 0;
constexpr uint64_t kMaxSeed = uint64_t(1) << 62;

// The sampler's name on the command line, the page and the traces.
inline const char* sampler_name(SamplerKind kind) {
    switch (kind) {
        case SamplerKind::Random:
            return "random";
        case SamplerKind::Stratified:
            return "stratified";
        case SamplerKind::Sobol:
            return "sobol";
    }
    return "?";
}

// How a run samples its pixels (--seed, --sampler, --noise-target, --max-samples).
struct SamplingOptions {
    uint64_t seed = kDefaultSeed;
    SamplerKind sampler = SamplerKind::Sobol;
    // > 0: adaptive sampling: a pixel takes kAdaptiveFirst samples, then kPacket at a time,
    // until the estimated standard error of its mean, in output levels after clamping, is
    // at most this in every channel, or until max_samples.
    double noise_target = 0;
    int max_samples = 0;  // adaptive: the cap (0: kAdaptiveCapFactor x the camera's samples)
};
inline constexpr int kAdaptiveCapFactor = 4;
inline constexpr int kAdaptiveFirst = 8;  // enough for a first estimate of the variance

// How a camera's pixels are sampled.
struct PixelSampling {
    int samples = 0;  // per pixel; 0: one ray through the centre (no NumSamples)
    uint64_t seed = kDefaultSeed;
    SamplerKind sampler = SamplerKind::Sobol;
    bool timed = false;  // some shape moves: each sample draws a time
    int grid = 0;        // n when samples is a square n^2 > 1 and not adaptive (pixel cells), else 0
    // Whether any path draws a random number: samples, a lens, motion, an area light or a
    // rough material. Without, a pixel is its centre ray and its streams are never read.
    bool random = false;
    double noise_target = 0;  // > 0: adaptive, up to max_samples (SamplingOptions)
    int max_samples = 0;
    // The sample count each pixel's pattern is laid out for: samples, or max_samples
    // when adaptive.
    int pattern() const { return noise_target > 0 ? max_samples : samples; }
};

// The sampling of camera `camera` of `scene` (its NumSamples, or --samples, already in
// Camera::samples: apply_overrides). Adaptive sampling applies only where a number is
// drawn (random); Random's grid only to a fixed count (a grid stopped part way would
// cover the top of the pixel only).
PixelSampling pixel_sampling(const Scene& scene, size_t camera, const SamplingOptions& options);

// Sample k (0 <= k < max(1, samples)) of pixel (x, y): its camera ray, and the stream its
// path draws from after the camera's numbers. Its point in the pixel: the centre for one
// sample or none (assignment 1's bunny.json writes NumSamples 1: its reference is of
// centre rays); under the Random sampler stratified on an n x n grid when samples is a
// square n^2 > 1 (sample k in cell (k % n, k / n)), uniform otherwise, its lens point and
// time uniform; under the others from the sampler's pattern.
struct CameraSample {
    Ray ray;
    SampleStream stream;
    Real dx = Real(0.5), dy = Real(0.5);  // its point in the pixel, from the top-left corner
    Real lx = Real(0.5), ly = Real(0.5);  // its point on the lens (a corner at 0, 0)
};
CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k);

// Running sums of a pixel's samples: their radiance (0..255 units, unclamped), and
// the clamped radiance and its squares for the estimate of the noise (in double whatever
// Real is: the squares' sum cancels).
struct PixelSum {
    Vec3 sum;
    double clamped[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
    int n = 0;
    // The estimated standard error of the clamped mean, the largest of the channels'
    // (infinite below two samples).
    double standard_error() const;
};

// Adds samples [k0, k1) of pixel (x, y) to `acc`, in order, traced kPacket at a time
// from k0: the same sums whether a pixel's samples are added at once or in parts that
// start at multiples of kPacket (the page refines an image pass after pass so).
void add_samples(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y, int k0, int k1,
                 const TraceOptions& options, TraceCache* cache, PixelSum& acc);

// A pixel as the render computes it: the mean of its samples' radiance (0..255 units,
// unclamped), which the image then clamps (docs/conventions.md, "Assignment 3"), and how
// many it took (adaptive sampling stops each pixel on its own).
struct PixelValue {
    Vec3 radiance;
    int samples = 0;
};
PixelValue sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                        const TraceOptions& options, TraceCache* cache);

}  // namespace rt
