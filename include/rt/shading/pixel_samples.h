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

// How a camera's pixels are sampled.
struct PixelSampling {
    int samples = 0;  // per pixel; 0: one ray through the centre (no NumSamples)
    uint64_t seed = kDefaultSeed;
    bool timed = false;  // some shape moves: each sample draws a time
    int grid = 0;        // n when samples is a square n^2 > 1 (stratified), else 0
    // Whether any path draws a random number: samples, a lens, motion, an area light or a
    // rough material. Without, a pixel is its centre ray and its streams are never read.
    bool random = false;
};

// The sampling of camera `camera` of `scene` under `seed` (its NumSamples, or --samples,
// already in Camera::samples: apply_overrides).
PixelSampling pixel_sampling(const Scene& scene, size_t camera, uint64_t seed);

// Sample k (0 <= k < max(1, samples)) of pixel (x, y): its camera ray, and the stream its
// path draws from after the camera's numbers. Its point in the pixel: the centre for one
// sample or none (assignment 1's bunny.json writes NumSamples 1: its reference is of
// centre rays), stratified on an n x n grid when samples is a square n^2 > 1 (sample k
// in cell (k % n, k / n)), uniform otherwise; its lens point and time uniform.
struct CameraSample {
    Ray ray;
    SampleStream stream;
    Real dx = Real(0.5), dy = Real(0.5);  // its point in the pixel, from the top-left corner
    Real lx = Real(0.5), ly = Real(0.5);  // its point on the lens (a corner at 0, 0)
};
CameraSample camera_sample(const Camera& cam, const PixelSampling& sampling, int x, int y, int k);

// The pixel's radiance (0..255 units, unclamped): the mean of its samples' radiance,
// which the image then clamps (docs/conventions.md, "Assignment 3"); its paths traced
// kPacket samples at a time.
Vec3 sample_pixel(const Scene& scene, const Camera& cam, const PixelSampling& sampling, int x, int y,
                  const TraceOptions& options, TraceCache* cache);

}  // namespace rt
