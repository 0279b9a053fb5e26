// gen_mesh's deterministic gradient noise: Perlin-style noise on a hashed lattice and its
// fractal sum, a function of the seed and the point alone (same seed, same surface).
#include <cstdint>

#include "gen_mesh.h"

namespace gen_mesh {

uint64_t mix64(uint64_t x) {  // splitmix64 finaliser
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

namespace {

// Gradient at a lattice point: one of the 12 cube-edge directions.
double grad(uint64_t seed, int64_t ix, int64_t iy, int64_t iz, double fx, double fy, double fz) {
    uint64_t h =
        mix64(seed ^ mix64(static_cast<uint64_t>(ix) * 0x8da6b343ull ^ static_cast<uint64_t>(iy) * 0xd8163841ull ^
                           static_cast<uint64_t>(iz) * 0xcb1ab31full));
    switch (h % 12) {
        case 0:
            return fx + fy;
        case 1:
            return -fx + fy;
        case 2:
            return fx - fy;
        case 3:
            return -fx - fy;
        case 4:
            return fx + fz;
        case 5:
            return -fx + fz;
        case 6:
            return fx - fz;
        case 7:
            return -fx - fz;
        case 8:
            return fy + fz;
        case 9:
            return -fy + fz;
        case 10:
            return fy - fz;
        default:
            return -fy - fz;
    }
}
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
double lerp(double a, double b, double t) { return a + t * (b - a); }

}  // namespace

double Noise::operator()(V3 p) const {
    const double flx = std::floor(p.x), fly = std::floor(p.y), flz = std::floor(p.z);
    const auto ix = static_cast<int64_t>(flx), iy = static_cast<int64_t>(fly), iz = static_cast<int64_t>(flz);
    const double fx = p.x - flx, fy = p.y - fly, fz = p.z - flz;
    const double u = fade(fx), v = fade(fy), w = fade(fz);
    const double x00 = lerp(grad(seed, ix, iy, iz, fx, fy, fz), grad(seed, ix + 1, iy, iz, fx - 1, fy, fz), u);
    const double x10 =
        lerp(grad(seed, ix, iy + 1, iz, fx, fy - 1, fz), grad(seed, ix + 1, iy + 1, iz, fx - 1, fy - 1, fz), u);
    const double x01 =
        lerp(grad(seed, ix, iy, iz + 1, fx, fy, fz - 1), grad(seed, ix + 1, iy, iz + 1, fx - 1, fy, fz - 1), u);
    const double x11 = lerp(grad(seed, ix, iy + 1, iz + 1, fx, fy - 1, fz - 1),
                            grad(seed, ix + 1, iy + 1, iz + 1, fx - 1, fy - 1, fz - 1), u);
    return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
}

double Noise::fbm(V3 p, int octaves) const {
    double sum = 0, amp = 1, norm = 0;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * (*this)(p);
        norm += amp;
        amp *= 0.5;
        p = 2.03 * p + V3{17.1, -3.7, 5.3};  // shift each octave off the previous lattice
    }
    return sum / norm;
}

}  // namespace gen_mesh
