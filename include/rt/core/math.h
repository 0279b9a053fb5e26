// Small vector math used everywhere. Vec3 is a plain aggregate of three Reals;
// all operations are inline so the hot loops see through them.
#pragma once
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "rt/core/real.h"

namespace rt {

// pi in the floating type T (std::numbers::pi_v before C++20); kPi in Real.
template <class T>
inline constexpr T pi_v = static_cast<T>(3.141592653589793238462643383279502884L);
inline constexpr Real kPi = pi_v<Real>;

struct Vec3 {
    Real x = 0, y = 0, z = 0;

    Real operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    Real& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator-(Vec3 a) { return {-a.x, -a.y, -a.z}; }
inline Vec3 operator*(Vec3 a, Real s) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator*(Real s, Vec3 a) { return {a.x * s, a.y * s, a.z * s}; }
inline Vec3 operator/(Vec3 a, Real s) { return {a.x / s, a.y / s, a.z / s}; }
// Component-wise product: colours times reflectances.
inline Vec3 operator*(Vec3 a, Vec3 b) { return {a.x * b.x, a.y * b.y, a.z * b.z}; }
inline Vec3& operator+=(Vec3& a, Vec3 b) {
    a = a + b;
    return a;
}
inline Vec3& operator*=(Vec3& a, Real s) {
    a = a * s;
    return a;
}

// std::fmax and std::fmin without the libm call GCC makes for them (fmax has no one
// instruction unless math is finite-only): the larger (smaller) of a and b, the
// other one when one is NaN. Equal zeros of opposite signs may give either zero.
inline Real max_num(Real a, Real b) { return b != b || a > b ? a : b; }
inline Real min_num(Real a, Real b) { return b != b || a < b ? a : b; }

// std::nextafter(x, +inf) without the libm call: the least Real above x (x not NaN;
// +inf stays +inf).
inline Real next_up(Real x) {
    using Bits = std::conditional_t<sizeof(Real) == sizeof(uint64_t), uint64_t, uint32_t>;
    if (x == 0) return std::numeric_limits<Real>::denorm_min();
    if (x == std::numeric_limits<Real>::infinity()) return x;
    Bits bits;
    std::memcpy(&bits, &x, sizeof bits);
    bits += x > 0 ? Bits(1) : ~Bits(0);  // away from zero for positives, towards it for negatives
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

inline Real dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline Real length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { return a / length(a); }
inline Vec3 vmin(Vec3 a, Vec3 b) { return {min_num(a.x, b.x), min_num(a.y, b.y), min_num(a.z, b.z)}; }
inline Vec3 vmax(Vec3 a, Vec3 b) { return {max_num(a.x, b.x), max_num(a.y, b.y), max_num(a.z, b.z)}; }
inline bool isfinite(Vec3 a) { return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z); }

struct Ray {
    Vec3 org;
    Vec3 dir;       // unit length for every ray the renderer spawns
    Real time = 0;  // in the shutter interval [0, 1): where moving shapes are (MotionBlur)
};

}  // namespace rt
