// The point sets of the patterned samplers (rt/core/random.h, docs/sampling.md): a pixel's
// N samples placed together in each pair of dimensions, so that they cover the square more
// evenly than N independent points do. Pure integer functions of (index, seed): the same
// points on every CPU and build.
#pragma once
#include <cstdint>

namespace rt {

inline uint32_t reverse_bits(uint32_t v) {
    v = ((v >> 1) & 0x55555555u) | ((v & 0x55555555u) << 1);
    v = ((v >> 2) & 0x33333333u) | ((v & 0x33333333u) << 2);
    v = ((v >> 4) & 0x0f0f0f0fu) | ((v & 0x0f0f0f0fu) << 4);
    v = ((v >> 8) & 0x00ff00ffu) | ((v & 0x00ff00ffu) << 8);
    return (v >> 16) | (v << 16);
}

// A nested uniform (Owen) scramble keyed by `seed`, on a 32-bit fraction whose bits are
// reversed (bit 0 its most significant): each bit is flipped or not depending only on the
// seed and the bits below it here (above it in the fraction), so points that share their
// top k bits still do after it and an elementary interval's points stay in one elementary
// interval. Adding, multiplying by an odd number and xoring with a multiple by an even
// number all change a bit only through the bits below it.
inline uint32_t owen_reversed(uint32_t v, uint32_t seed) {
    v += seed;
    v ^= v * 0x6a09e666u;
    v *= (seed >> 7) | 1u;
    v ^= v * 0xbb67ae84u;
    v += seed ^ 0x3c6ef372u;
    v ^= v * 0xa54ff53au;
    return v;
}

// The same on a fraction in its usual bit order.
inline uint32_t nested_scramble(uint32_t v, uint32_t seed) {
    return reverse_bits(owen_reversed(reverse_bits(v), seed));
}

// The second dimension of Sobol's sequence (direction numbers: Pascal's triangle mod 2,
// v_0 = 2^31, v_j+1 = v_j ^ v_j >> 1) as the XOR of the direction numbers of i's set bits,
// by byte, bit-reversed: t[b][x] is the XOR over the set bits of x at byte b.
struct Sobol1ReversedTable {
    uint32_t t[4][256];
    constexpr Sobol1ReversedTable() : t{} {
        uint32_t v[32] = {};
        v[0] = 1u;  // 2^31 reversed
        for (int j = 1; j < 32; ++j) v[j] = v[j - 1] ^ (v[j - 1] << 1);
        for (int b = 0; b < 4; ++b)
            for (int x = 0; x < 256; ++x) {
                uint32_t r = 0;
                for (int j = 0; j < 8; ++j)
                    if (x >> j & 1) r ^= v[8 * b + j];
                t[b][x] = r;
            }
    }
};
inline constexpr Sobol1ReversedTable kSobol1Reversed{};

inline uint32_t sobol1_reversed(uint32_t i) {
    const auto& t = kSobol1Reversed.t;
    return t[0][i & 0xff] ^ t[1][i >> 8 & 0xff] ^ t[2][i >> 16 & 0xff] ^ t[3][i >> 24];
}

// Point `i` of the first two dimensions of Sobol's sequence, as 32-bit fractions: the
// van der Corput radical inverse, and the dimension above. Its first 2^k points are a
// (0, k, 2)-net: one point in every elementary interval of area 2^-k.
inline void sobol2(uint32_t i, uint32_t& a, uint32_t& b) {
    a = reverse_bits(i);
    b = reverse_bits(sobol1_reversed(i));
}

// Point `i` of a pixel's shuffled, scrambled pair: Sobol's point of the index shuffled by
// `shuffle` (a nested scramble of the index, which keeps a block of 2^k indices one
// aligned block), its coordinates scrambled by `sa` and `sb`. The same as
// sobol2(nested_scramble(i, shuffle)) with nested_scramble(., sa) and (., sb) applied to
// its two coordinates, with the bit reversals that cancel left out.
inline void scrambled_sobol2(uint32_t i, uint32_t shuffle, uint32_t sa, uint32_t sb, uint32_t& a, uint32_t& b) {
    const uint32_t reversed = owen_reversed(reverse_bits(i), shuffle);  // the shuffled index, reversed
    const uint32_t shuffled = reverse_bits(reversed);
    a = reverse_bits(owen_reversed(shuffled, sa));
    b = reverse_bits(owen_reversed(sobol1_reversed(shuffled), sb));
}

// Dimensions 2, 3 and 4 of Sobol's sequence (Joe and Kuo's dimensions 3, 4 and 5: the
// primitive polynomials x^2 + x + 1, x^3 + x + 1 and x^3 + x^2 + 1, initial direction
// numbers 1 3, 1 3 1 and 1 1 1), their direction numbers as 32-bit fractions from the
// recurrence v_k = v_k-s ^ v_k-s >> s ^ the v_k-j the polynomial's inner terms select.
struct SobolHigherDirections {
    uint32_t v[3][32];
    constexpr SobolHigherDirections() : v{} {
        const int degree[3] = {2, 3, 3}, inner[3] = {1, 1, 2};
        const uint32_t initial[3][3] = {{1, 3, 0}, {1, 3, 1}, {1, 1, 1}};
        for (int d = 0; d < 3; ++d) {
            const int s = degree[d];
            for (int k = 0; k < s; ++k) v[d][k] = initial[d][k] << (31 - k);
            for (int k = s; k < 32; ++k) {
                uint32_t r = v[d][k - s] ^ (v[d][k - s] >> s);
                for (int j = 1; j < s; ++j)
                    if (inner[d] >> (s - 1 - j) & 1) r ^= v[d][k - j];
                v[d][k] = r;
            }
        }
    }
};
inline constexpr SobolHigherDirections kSobolHigher{};

// Point `i` of Sobol's dimension `d` (2..4) as a 32-bit fraction: the XOR of the direction
// numbers of i's set bits. The first 2^k points of dimensions 0, 1 and 2 together are a
// (1, k, 3)-net: every elementary box of volume 2^(1-k) holds two.
inline uint32_t sobol_higher(int d, uint32_t i) {
    uint32_t r = 0;
    for (; i; i &= i - 1) r ^= kSobolHigher.v[d - 2][__builtin_ctz(i)];
    return r;
}

// A bijection of [0, n) keyed by `seed` (n <= 2^31): a bijection of the next power of two
// (invertible mixing steps masked to its bits), walked until it lands inside [0, n).
inline uint32_t permute_index(uint32_t i, uint32_t n, uint32_t seed) {
    if (n <= 1) return 0;
    uint32_t mask = n - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    const uint32_t shift = mask > 3 ? 2 : 1;
    do {
        i ^= seed & mask;
        i = (i * 0x9e3779b1u) & mask;
        i ^= i >> shift;
        i = (i + (seed >> 9)) & mask;
        i = (i * (((seed >> 3) & mask) | 1u)) & mask;
        i ^= i >> shift;
        i = (i * 0x85ebca6bu) & mask;
    } while (i >= n);
    return i;
}

}  // namespace rt
