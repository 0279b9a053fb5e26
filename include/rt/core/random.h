// Counter-based random numbers (docs/conventions.md, "Assignment 3"; docs/sampling.md):
// each sample of each pixel has a stream of its own, a pure function of (seed, pixel,
// sample) and of how many numbers it has drawn, with no state shared between threads. An
// image is then the same whatever the thread count, the tile order, the CPU or the build.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "rt/core/real.h"
#include "rt/core/sample_patterns.h"

namespace rt {

// A 64-bit mixing function (the finaliser of SplitMix64): every input bit changes
// about half of the output bits.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

// How a pixel's samples draw their numbers (--sampler).
//   Random:     every number independent (the samples of a pixel know nothing of each other).
//   Stratified: each pair of dimensions a correlated multi-jittered pattern of the
//               pixel's samples: jittered on a grid of about sqrt(N) x sqrt(N) cells and
//               one sample per row and column of the fine N x N grid, permuted anew per
//               pixel and per pair.
//   Sobol:      each pair of dimensions the first two dimensions of Sobol's sequence,
//               Owen-scrambled and shuffled anew per pixel and per pair; any prefix of a
//               pixel's samples is well spread, so adaptive sampling may stop anywhere.
//               Without the pixel grid the camera's numbers are one point of several
//               dimensions (sobol_point, camera_sample).
// Every sample is uniform on its own (the patterns are randomised by the seed), so each
// sampler's pixel mean has the same expectation.
enum class SamplerKind : uint8_t { Random, Stratified, Sobol };

// A number in [0, 1) from the top bits of a 64-bit hash: 53 bits (double), 24 (float),
// exact in Real.
inline Real unit_from_bits(uint64_t h) {
    if constexpr (sizeof(Real) == 8)
        return static_cast<Real>(static_cast<double>(h >> 11) * 0x1.0p-53);
    else
        return static_cast<Real>(static_cast<float>(h >> 40) * 0x1.0p-24f);
}

struct SampleStream {
    uint64_t key;    // Random: of (seed, pixel, sample); the patterns: of (seed, pixel)
    uint32_t drawn;  // Random: numbers drawn; the patterns: pairs of dimensions drawn
    uint32_t index;  // the patterns: the sample's index in its pixel
    uint32_t count;  // Stratified: the pixel's sample count
    SamplerKind kind;

    // Uninitialised: a packet's array of streams costs nothing where no number is drawn.
    SampleStream() = default;
    // The Random stream of sample `sample` of pixel `pixel`.
    SampleStream(uint64_t seed, uint64_t pixel, uint32_t sample)
        : key(mix64(mix64(mix64(seed + 0x9e3779b97f4a7c15ULL) ^ pixel) + sample)),
          drawn(0),
          index(sample),
          count(0),
          kind(SamplerKind::Random) {}
    // Sample `sample` of the `count` of pixel `pixel` under `kind`.
    SampleStream(SamplerKind k, uint64_t seed, uint64_t pixel, uint32_t sample, uint32_t samples)
        : SampleStream(seed, pixel, sample) {
        if (k == SamplerKind::Random) return;
        key = mix64(mix64(seed + 0x9e3779b97f4a7c15ULL) ^ pixel);
        count = samples;
        kind = k;
    }

    // The next number, uniform in [0, 1). The patterns give it a pair of dimensions of
    // its own (and drop the pair's second number).
    Real next() {
        if (kind == SamplerKind::Random) return unit_from_bits(mix64(key + 0x9e3779b97f4a7c15ULL * ++drawn));
        Real a, b;
        next2(a, b);
        return a;
    }

    // The next two numbers, a point of the unit square: the patterns place the pixel's
    // samples together in it.
    void next2(Real& a, Real& b) {
        if (kind == SamplerKind::Random) {
            a = next();
            b = next();
            return;
        }
        const uint64_t h = mix64(key ^ (0xd1b54a32d192ed03ULL * ++drawn));
        const uint32_t h0 = uint32_t(h), h1 = uint32_t(h >> 32);
        if (kind == SamplerKind::Sobol) {
            uint32_t x, y;
            scrambled_sobol2(index, h0, h1, h1 ^ h0 ^ 0x5bd1e995u, x, y);
            a = unit32(x);
            b = unit32(y);
            return;
        }
        stratified(h, a, b);
    }

    // Sobol: `dims` numbers (1..5) of one point of Sobol's first `dims` dimensions, the
    // pixel's sample index shuffled and each coordinate scrambled as a pair's are, so that
    // they are stratified together and not only pair by pair. The first two are the pair
    // next2 would draw.
    void sobol_point(Real* out, int dims) {
        const uint64_t h = mix64(key ^ (0xd1b54a32d192ed03ULL * ++drawn));
        const uint32_t h0 = uint32_t(h), h1 = uint32_t(h >> 32);
        uint32_t x, y;
        scrambled_sobol2(index, h0, h1, h1 ^ h0 ^ 0x5bd1e995u, x, y);
        out[0] = unit32(x);
        if (dims > 1) out[1] = unit32(y);
        const uint32_t shuffled = dims > 2 ? nested_scramble(index, h0) : 0;
        for (int d = 2; d < dims; ++d)
            out[d] = unit32(nested_scramble(sobol_higher(d, shuffled), uint32_t(mix64(h + uint64_t(d)))));
    }

private:
    static Real unit32(uint32_t v) { return unit_from_bits(uint64_t(v) << 32); }

    // Correlated multi-jittered sampling: the sample's cell of an m x n grid (m n >= count,
    // a random one of them when count < m n, so every sample stays uniform), offset in
    // the cell by the permuted column and row so that the m n points are also one per
    // row and per column of the fine grid, then jittered.
    void stratified(uint64_t h, Real& a, Real& b) const {
        const uint32_t c = count > 0 ? count : 1;
        uint32_t m = static_cast<uint32_t>(std::ceil(std::sqrt(double(c))));  // exact for squares
        const uint32_t n = (c + m - 1) / m;
        const uint32_t s = permute_index(index % (m * n), m * n, uint32_t(h));
        const uint32_t col = s % m, row = s / m;
        const uint32_t sx = permute_index(col, m, uint32_t(h >> 32));
        const uint32_t sy = permute_index(row, n, uint32_t(h >> 32) ^ 0x68e31da4u);
        const uint64_t j = mix64(h + s);
        const Real jx = unit_from_bits(j), jy = unit_from_bits(mix64(j));
        constexpr Real below_one = Real(1) - std::numeric_limits<Real>::epsilon() / 2;
        a = std::min(below_one, (Real(col) + (Real(sy) + jx) / Real(n)) / Real(m));
        b = std::min(below_one, (Real(row) + (Real(sx) + jy) / Real(m)) / Real(n));
    }
};

}  // namespace rt
