// Tests for the small vector library (include/rt/core/math.h) and for quantize()
// (include/rt/image/image.h), which turns radiance into 8-bit channel values.
// Every expected value is worked out by hand in the comment next to it; the
// inputs are chosen so that the arithmetic is exact in binary floating point.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "rt/core/math.h"
#include "rt/image/image.h"
#include "rt/render/render.h"

namespace {

using rt::Real;
using rt::Rounding;
using rt::Vec3;

// A few units in the last place of Real (double by default, float with PRECISION=float).
const Real kTol = 4 * std::numeric_limits<Real>::epsilon();

void expect_vec_eq(Vec3 got, Real x, Real y, Real z) {
    EXPECT_EQ(got.x, x);
    EXPECT_EQ(got.y, y);
    EXPECT_EQ(got.z, z);
}

void expect_vec_near(Vec3 got, Real x, Real y, Real z, Real tol) {
    EXPECT_NEAR(got.x, x, tol);
    EXPECT_NEAR(got.y, y, tol);
    EXPECT_NEAR(got.z, z, tol);
}

TEST(MathVec3, DefaultIsZero) {
    const Vec3 v;
    expect_vec_eq(v, 0, 0, 0);
}

TEST(MathVec3, Indexing) {
    Vec3 v{1, 2, 3};
    EXPECT_EQ(v[0], 1);
    EXPECT_EQ(v[1], 2);
    EXPECT_EQ(v[2], 3);
    v[0] = 7;
    v[1] = 8;
    v[2] = 9;
    expect_vec_eq(v, 7, 8, 9);
    const Vec3 c = v;
    EXPECT_EQ(c[2], 9);
}

TEST(MathVec3, AddSubNegate) {
    const Vec3 a{1, 2, 3}, b{4, -5, 6.5};
    expect_vec_eq(a + b, 5, -3, 9.5);   // (1+4, 2-5, 3+6.5)
    expect_vec_eq(a - b, -3, 7, -3.5);  // (1-4, 2+5, 3-6.5)
    expect_vec_eq(-a, -1, -2, -3);
    Vec3 c = a;
    c += b;
    expect_vec_eq(c, 5, -3, 9.5);
}

TEST(MathVec3, ScalarProductAndDivision) {
    const Vec3 a{1, -2, 3};
    expect_vec_eq(a * Real(2), 2, -4, 6);
    expect_vec_eq(Real(-0.5) * a, -0.5, 1, -1.5);
    expect_vec_eq(a / Real(4), 0.25, -0.5, 0.75);
    Vec3 c = a;
    c *= Real(3);
    expect_vec_eq(c, 3, -6, 9);
}

TEST(MathVec3, ComponentwiseProduct) {
    // Colours times reflectances: (2*0.5, 4*0.25, 8*2).
    expect_vec_eq(Vec3{2, 4, 8} * Vec3{0.5, 0.25, 2}, 1, 1, 16);
}

TEST(MathVec3, Dot) {
    // 1*4 + 2*(-5) + 3*6 = 4 - 10 + 18 = 12
    EXPECT_EQ(rt::dot(Vec3{1, 2, 3}, Vec3{4, -5, 6}), 12);
    // Orthogonal vectors: 1*0 + 0*1 + 0*0 = 0
    EXPECT_EQ(rt::dot(Vec3{1, 0, 0}, Vec3{0, 1, 0}), 0);
    // |v|^2: 3^2 + 4^2 + 12^2 = 169
    EXPECT_EQ(rt::dot(Vec3{3, 4, 12}, Vec3{3, 4, 12}), 169);
}

TEST(MathVec3, CrossOfBasisIsRightHanded) {
    expect_vec_eq(rt::cross(Vec3{1, 0, 0}, Vec3{0, 1, 0}), 0, 0, 1);   // x * y = z
    expect_vec_eq(rt::cross(Vec3{0, 1, 0}, Vec3{0, 0, 1}), 1, 0, 0);   // y * z = x
    expect_vec_eq(rt::cross(Vec3{0, 0, 1}, Vec3{1, 0, 0}), 0, 1, 0);   // z * x = y
    expect_vec_eq(rt::cross(Vec3{0, 1, 0}, Vec3{1, 0, 0}), 0, 0, -1);  // y * x = -z
}

TEST(MathVec3, CrossGeneral) {
    // (1,2,3) x (4,5,6) = (2*6-3*5, 3*4-1*6, 1*5-2*4) = (-3, 6, -3)
    const Vec3 a{1, 2, 3}, b{4, 5, 6};
    const Vec3 c = rt::cross(a, b);
    expect_vec_eq(c, -3, 6, -3);
    // The cross product is orthogonal to both factors: -3 + 12 - 9 = 0, -12 + 30 - 18 = 0.
    EXPECT_EQ(rt::dot(c, a), 0);
    EXPECT_EQ(rt::dot(c, b), 0);
    // Anti-commutative.
    expect_vec_eq(rt::cross(b, a), 3, -6, 3);
    // Parallel vectors give zero: (1,2,3) x (2,4,6) = (12-12, 6-6, 4-4).
    expect_vec_eq(rt::cross(a, a * Real(2)), 0, 0, 0);
}

TEST(MathVec3, LengthAndNormalize) {
    // |(3,4,12)| = sqrt(9+16+144) = sqrt(169) = 13
    EXPECT_EQ(rt::length(Vec3{3, 4, 12}), 13);
    // normalize((3,4,12)) = (3/13, 4/13, 12/13)
    const Vec3 n = rt::normalize(Vec3{3, 4, 12});
    expect_vec_near(n, Real(3) / 13, Real(4) / 13, Real(12) / 13, kTol);
    EXPECT_NEAR(rt::length(n), 1, kTol);
    // (0,0,-5) -> (0,0,-1) exactly: -5 / 5
    expect_vec_eq(rt::normalize(Vec3{0, 0, -5}), 0, 0, -1);
    // (1,1,1)/sqrt(3): each component 0.5773502691896258
    expect_vec_near(rt::normalize(Vec3{2, 2, 2}), 0.5773502691896258, 0.5773502691896258, 0.5773502691896258, kTol);
}

// Zeros, +-1, 0.1, the least subnormal and normal, the largest finite, infinities, and n
// Reals of random bits; no NaN.
std::vector<Real> special_and_random_reals(int n, uint64_t seed) {
    const Real inf = std::numeric_limits<Real>::infinity(), big = std::numeric_limits<Real>::max();
    const Real tiny = std::numeric_limits<Real>::denorm_min();
    std::vector<Real> xs = {0,   -0.0f, 1,   -1,  Real(0.1), tiny, -tiny, std::numeric_limits<Real>::min(),
                            big, -big,  inf, -inf};
    std::mt19937_64 rng(seed);
    for (int i = 0; i < n; ++i) {
        Real x;
        do {
            const uint64_t b = rng();
            std::memcpy(&x, &b, sizeof x);
        } while (std::isnan(x));
        xs.push_back(x);
    }
    return xs;
}

// max_num and min_num stand in for std::fmax and std::fmin (without their libm
// calls): the same values on ordinary numbers, zeros, subnormals,
// the largest finite, infinities and NaN (fmax's rule: NaN loses), and on random bits.
TEST(MathScalar, MaxNumMinNumAgreeWithLibm) {
    const Real inf = std::numeric_limits<Real>::infinity(), nan = std::numeric_limits<Real>::quiet_NaN();
    const Real big = std::numeric_limits<Real>::max();
    std::vector<Real> xs = special_and_random_reals(2000, 795);
    xs.push_back(nan);
    auto same = [](Real a, Real b) {
        return (std::isnan(a) && std::isnan(b)) || (a == b && std::signbit(a) == std::signbit(b));
    };
    for (Real a : xs) {
        for (Real b : {Real(0), Real(1), -big, inf, nan, xs[xs.size() / 2]}) {
            // Equal zeros of opposite signs may give either zero (the contract).
            if (a == 0 && b == 0) continue;
            EXPECT_TRUE(same(rt::max_num(a, b), std::fmax(a, b))) << "max_num(" << a << ", " << b << ")";
            EXPECT_TRUE(same(rt::min_num(a, b), std::fmin(a, b))) << "min_num(" << a << ", " << b << ")";
        }
    }
}

// next_up stands in for std::nextafter(x, +inf) (without its libm call): the same bits
// on zeros, subnormals, the largest finite, infinities and random bits (NaN excluded).
TEST(MathScalar, NextUpAgreesWithLibm) {
    for (Real x : special_and_random_reals(20000, 13)) {
        const Real a = rt::next_up(x), b = std::nextafter(x, std::numeric_limits<Real>::infinity());
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "next_up(" << x << ") = " << a << ", nextafter: " << b;
    }
}

TEST(MathVec3, MinMax) {
    const Vec3 a{1, -2, 3}, b{0, 5, 3};
    expect_vec_eq(rt::vmin(a, b), 0, -2, 3);
    expect_vec_eq(rt::vmax(a, b), 1, 5, 3);
    // fmin/fmax ignore a NaN operand, so an empty box's sentinels never poison it.
    const Real nan = std::numeric_limits<Real>::quiet_NaN();
    expect_vec_eq(rt::vmin(Vec3{nan, 1, 2}, Vec3{4, 5, 6}), 4, 1, 2);
}

TEST(MathVec3, IsFinite) {
    EXPECT_TRUE(rt::isfinite(Vec3{1, 2, 3}));
    EXPECT_FALSE(rt::isfinite(Vec3{1, Real(HUGE_VAL), 3}));
    EXPECT_FALSE(rt::isfinite(Vec3{1, 2, std::numeric_limits<Real>::quiet_NaN()}));
    EXPECT_FALSE(rt::isfinite(Vec3{-Real(HUGE_VAL), 2, 3}));
}

// --- quantize ----------------------------------------------------------------

TEST(MathQuantize, DefaultRenderOptionIsTruncation) {
    // reference-conventions.md, "Output": the references truncate, so that is the default.
    EXPECT_EQ(rt::RenderOptions{}.rounding, Rounding::Truncate);
}

TEST(MathQuantize, TruncationDropsTheFraction) {
    EXPECT_EQ(rt::quantize(Real(254.99), Rounding::Truncate), 254);  // floor(254.99)
    EXPECT_EQ(rt::quantize(Real(0.99), Rounding::Truncate), 0);
    EXPECT_EQ(rt::quantize(Real(12.5), Rounding::Truncate), 12);
    EXPECT_EQ(rt::quantize(Real(1), Rounding::Truncate), 1);
    EXPECT_EQ(rt::quantize(Real(128), Rounding::Truncate), 128);
    EXPECT_EQ(rt::quantize(Real(0), Rounding::Truncate), 0);
    // The largest value below 255 still truncates to 254.
    EXPECT_EQ(rt::quantize(std::nextafter(Real(255), Real(0)), Rounding::Truncate), 254);
}

TEST(MathQuantize, NearestRoundsHalfUp) {
    EXPECT_EQ(rt::quantize(Real(254.5), Rounding::Nearest), 255);  // 254.5 + 0.5 = 255
    EXPECT_EQ(rt::quantize(Real(254.49), Rounding::Nearest), 254);
    EXPECT_EQ(rt::quantize(Real(0.49), Rounding::Nearest), 0);
    EXPECT_EQ(rt::quantize(Real(0.5), Rounding::Nearest), 1);
    EXPECT_EQ(rt::quantize(Real(12.5), Rounding::Nearest), 13);
    EXPECT_EQ(rt::quantize(Real(12.4999), Rounding::Nearest), 12);
    EXPECT_EQ(rt::quantize(Real(7), Rounding::Nearest), 7);
}

TEST(MathQuantize, ClampsToByteRange) {
    for (Rounding r : {Rounding::Truncate, Rounding::Nearest}) {
        EXPECT_EQ(rt::quantize(Real(255), r), 255);
        EXPECT_EQ(rt::quantize(Real(255.7), r), 255);
        EXPECT_EQ(rt::quantize(Real(256), r), 255);  // would wrap to 0 in uint8_t without clamping
        EXPECT_EQ(rt::quantize(Real(1e6), r), 255);
        EXPECT_EQ(rt::quantize(Real(1e300), r), 255);
        EXPECT_EQ(rt::quantize(Real(HUGE_VAL), r), 255);
    }
}

TEST(MathQuantize, NegativeBecomesZero) {
    for (Rounding r : {Rounding::Truncate, Rounding::Nearest}) {
        EXPECT_EQ(rt::quantize(Real(-0.4), r), 0);
        EXPECT_EQ(rt::quantize(Real(-0.6), r), 0);  // rounding -0.6 must not give 255 or 1
        EXPECT_EQ(rt::quantize(Real(-1), r), 0);
        EXPECT_EQ(rt::quantize(Real(-300), r), 0);
        EXPECT_EQ(rt::quantize(Real(-HUGE_VAL), r), 0);
        EXPECT_EQ(rt::quantize(Real(-0.0), r), 0);
    }
}

TEST(MathQuantize, NaNBecomesZero) {
    for (Rounding r : {Rounding::Truncate, Rounding::Nearest}) {
        EXPECT_EQ(rt::quantize(std::numeric_limits<Real>::quiet_NaN(), r), 0);
        EXPECT_EQ(rt::quantize(-std::numeric_limits<Real>::quiet_NaN(), r), 0);
    }
}

TEST(MathQuantize, EveryLevelRoundTrips) {
    // v + 0.25 truncates to v and rounds to v; v + 0.75 truncates to v and rounds to v + 1.
    for (int v = 0; v < 255; ++v) {
        EXPECT_EQ(rt::quantize(Real(v) + Real(0.25), Rounding::Truncate), v);
        EXPECT_EQ(rt::quantize(Real(v) + Real(0.25), Rounding::Nearest), v);
        EXPECT_EQ(rt::quantize(Real(v) + Real(0.75), Rounding::Truncate), v);
        EXPECT_EQ(rt::quantize(Real(v) + Real(0.75), Rounding::Nearest), v + 1);
    }
}

}  // namespace
