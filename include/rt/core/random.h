// Counter-based random numbers (docs/conventions.md, "Assignment 3"): each sample of
// each pixel has a stream of its own, a pure function of (seed, pixel, sample) and of
// how many numbers it has drawn, with no state shared between threads. An image is then
// the same whatever the thread count, the tile order, the CPU or the build.
#pragma once
#include <cstdint>

#include "rt/core/real.h"

namespace rt {

// A 64-bit mixing function (the finaliser of SplitMix64): every input bit changes
// about half of the output bits.
inline uint64_t mix64(uint64_t z) {
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

struct SampleStream {
    uint64_t key;
    uint32_t drawn;

    // Uninitialised: a packet's array of streams costs nothing where no number is drawn.
    SampleStream() = default;
    SampleStream(uint64_t seed, uint64_t pixel, uint32_t sample)
        : key(mix64(mix64(mix64(seed + 0x9e3779b97f4a7c15ULL) ^ pixel) + sample)), drawn(0) {}

    // The next number, uniform in [0, 1): the top 53 bits (double) or 24 bits (float)
    // of the hash, so that each is exact in Real.
    Real next() {
        const uint64_t h = mix64(key + 0x9e3779b97f4a7c15ULL * ++drawn);
        if constexpr (sizeof(Real) == 8)
            return static_cast<Real>(static_cast<double>(h >> 11) * 0x1.0p-53);
        else
            return static_cast<Real>(static_cast<float>(h >> 40) * 0x1.0p-24f);
    }
};

}  // namespace rt
