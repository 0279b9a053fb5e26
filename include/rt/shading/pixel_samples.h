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
    // > 0: adaptive sampling: a pixel takes adaptive_first samples, then kPacket at a time,
    // until the estimated standard error of its mean, in output levels after clamping, is
    // at most this in every channel, or until max_samples (sample_region).
    double noise_target = 0;
    int max_samples = 0;  // adaptive: the cap (0: kAdaptiveCapFactor x the camera's samples)
};
inline constexpr int kAdaptiveCapFactor = 2;
// Adaptive sampling's first samples of a pixel for a camera of `samples` per pixel: the
// largest power of two up to samples / 6, from 4 to 32. Every pixel spends them, so they are
// a small part of the uniform budget; enough that a pixel which a feature covers only in part
// (an edge, a moving shape) rarely stops on samples that all miss it; and a power of two: a
// Sobol net, its blocks of 2, 4 and 8 complete.
inline int adaptive_first(int samples) {
    int first = 4;
    while (first < 32 && 2 * first <= samples / 6) first *= 2;
    return first;
}

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
    int first = 0;  // adaptive: the samples every pixel takes first (adaptive_first)
    // The sample count each pixel's pattern is laid out for: samples, or max_samples
    // when adaptive.
    int pattern() const { return noise_target > 0 ? max_samples : samples; }
};

// The sampling of camera `camera` of `scene` (its NumSamples, or --samples, already in
// Camera::samples: apply_overrides). Adaptive sampling applies only where a number is
// drawn (random); the pixel grid only to a fixed count (a grid stopped part way would
// cover the top of the pixel only).
PixelSampling pixel_sampling(const Scene& scene, size_t camera, const SamplingOptions& options);

// Sample k (0 <= k < max(1, samples)) of pixel (x, y): its camera ray, and the stream its
// path draws from after the camera's numbers. Its point in the pixel: the centre for one
// sample or none (assignment 1's bunny.json writes NumSamples 1: its reference is of
// centre rays); stratified on an n x n grid when samples is a square n^2 > 1 and fixed
// (sample k in cell (k % n, k / n)), uniform otherwise, its lens point and time uniform,
// all drawn from the sampler; under Sobol without the grid the pixel point, lens point
// and time are one point of Sobol's first dimensions (SampleStream::sobol_point).
struct CameraSample {
    Ray ray;
    SampleStream stream;
    Real dx = Real(0.5), dy = Real(0.5);  // its point in the pixel, from the top-left corner
    Real lx = Real(0.5), ly = Real(0.5);  // its point on the lens (a corner at 0, 0)
};
CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k);

// Running sums of a pixel's samples: their radiance (0..255 units, unclamped), and, for
// adaptive sampling's estimate of the noise, the clamped radiance, its squares and the
// squares of its sums over aligned blocks of 2, 4 and 8 samples (in double whatever Real
// is: the squares' sums cancel).
struct PixelSum {
    static constexpr int kBlocks = 3;  // block sizes 2 << i
    Vec3 sum;
    double clamped[3] = {0, 0, 0}, squares[3] = {0, 0, 0};
    double block_squares[kBlocks][3] = {}, block_partial[kBlocks][3] = {};
    int n = 0;
    // The estimated standard error of the clamped mean, the largest of the channels'
    // (infinite below two samples). `sobol`: the samples are Sobol points, whose aligned
    // blocks are nets: the spread of the means of the largest aligned blocks of which there
    // are at least 4 (their error, not that of independent samples, which overstates a
    // net's), else of the samples.
    double standard_error(bool sobol) const;
    void add(const Vec3& radiance, bool noise);
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
// A pixel of a camera without adaptive sampling.
PixelValue sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                        const TraceOptions& options, TraceCache* cache);

// Adaptive sampling (sampling.noise_target > 0) decides a pixel's samples within its
// region: the kAdaptiveRegion x kAdaptiveRegion square of the image, aligned at 0 and cut at
// its edges, that holds it. Every pixel takes sampling.first samples, then, pass after pass,
// kPacket more while its noise estimate is above the target and it is under the cap. A
// pixel's estimate is its own (PixelSum::standard_error) or, if larger, what its
// neighbours' per-sample noise (in the region, 3 x 3) predicts for its own count: a pixel
// whose first samples happen to agree beside noisy ones is not taken as converged. A region
// depends on nothing outside it, so the image is the same for any thread count and tiling.
inline constexpr int kAdaptiveRegion = 16;
inline constexpr double kNeighbourShare = 0.5;
// The per-sample noise pixel (x, y) of a w x h region is judged by: the largest of its own
// (noise[y * w + x], its estimate squared times its count) and kNeighbourShare times the
// mean of its neighbours' in the region.
double judged_noise(const double* noise, int w, int h, int x, int y);
// The pixels of region [x0, x1) x [y0, y1) into out (row-major, (x1 - x0) * (y1 - y0)).
void sample_region(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x0, int y0, int x1, int y1,
                   const TraceOptions& options, TraceCache* cache, PixelValue* out);
// Pixel (x, y) under adaptive sampling: its region's computation, this pixel's value.
PixelValue sample_pixel_adaptive(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                                 const TraceOptions& options, TraceCache* cache);

}  // namespace rt
