// Affine transformations of 3D space (the scene format's Transformations: Translation,
// Scaling, Rotation, Composite), as the upper three rows of a 4x4 matrix acting on
// column vectors. Kept in double whatever the build's Real: they are composed once at
// load and their rounding should not depend on the precision the renderer runs in.
#pragma once
#include <cmath>

#include "rt/core/math.h"

namespace rt {

struct Affine {
    // Row r, column c; column 3 is the translation. The identity by default.
    double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

    static Affine translation(double x, double y, double z) {
        const double v[12] = {1, 0, 0, x, 0, 1, 0, y, 0, 0, 1, z};
        return rows(v);
    }
    static Affine scaling(double x, double y, double z) {
        const double v[12] = {x, 0, 0, 0, 0, y, 0, 0, 0, 0, z, 0};
        return rows(v);
    }
    // `degrees` counter-clockwise about the axis (x, y, z) seen from its tip (the
    // right-hand rule); the axis need not be unit length but must not be zero.
    static Affine rotation(double degrees, double x, double y, double z) {
        const double len = std::sqrt(x * x + y * y + z * z);
        x /= len;
        y /= len;
        z /= len;
        const double rad = degrees * 3.141592653589793238462643383279502884 / 180;
        const double c = std::cos(rad), s = std::sin(rad), k = 1 - c;
        Affine a;
        a.m[0][0] = c + x * x * k;
        a.m[0][1] = x * y * k - z * s;
        a.m[0][2] = x * z * k + y * s;
        a.m[1][0] = y * x * k + z * s;
        a.m[1][1] = c + y * y * k;
        a.m[1][2] = y * z * k - x * s;
        a.m[2][0] = z * x * k - y * s;
        a.m[2][1] = z * y * k + x * s;
        a.m[2][2] = c + z * z * k;
        return a;
    }
    // The first twelve numbers of a row-major 4x4 matrix (its last row must be 0 0 0 1).
    static Affine rows(const double* v) {
        Affine a;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c) a.m[r][c] = v[4 * r + c];
        return a;
    }

    bool is_identity() const {
        const Affine id;
        for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 4; ++c)
                if (m[r][c] != id.m[r][c]) return false;
        return true;
    }
    // The determinant of the linear part: negative when the transformation mirrors.
    double det() const {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }
    // The inverse; the caller makes sure det() is not zero.
    Affine inverse() const {
        const double d = det();
        Affine a;
        a.m[0][0] = (m[1][1] * m[2][2] - m[1][2] * m[2][1]) / d;
        a.m[0][1] = (m[0][2] * m[2][1] - m[0][1] * m[2][2]) / d;
        a.m[0][2] = (m[0][1] * m[1][2] - m[0][2] * m[1][1]) / d;
        a.m[1][0] = (m[1][2] * m[2][0] - m[1][0] * m[2][2]) / d;
        a.m[1][1] = (m[0][0] * m[2][2] - m[0][2] * m[2][0]) / d;
        a.m[1][2] = (m[0][2] * m[1][0] - m[0][0] * m[1][2]) / d;
        a.m[2][0] = (m[1][0] * m[2][1] - m[1][1] * m[2][0]) / d;
        a.m[2][1] = (m[0][1] * m[2][0] - m[0][0] * m[2][1]) / d;
        a.m[2][2] = (m[0][0] * m[1][1] - m[0][1] * m[1][0]) / d;
        for (int r = 0; r < 3; ++r) a.m[r][3] = -(a.m[r][0] * m[0][3] + a.m[r][1] * m[1][3] + a.m[r][2] * m[2][3]);
        return a;
    }

    // The point p moved: M p.
    Vec3 point(Vec3 p) const {
        return {Real(m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3]),
                Real(m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3]),
                Real(m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3])};
    }
    // The direction v moved (no translation).
    Vec3 vector(Vec3 v) const {
        return {Real(m[0][0] * v.x + m[0][1] * v.y + m[0][2] * v.z),
                Real(m[1][0] * v.x + m[1][1] * v.y + m[1][2] * v.z),
                Real(m[2][0] * v.x + m[2][1] * v.y + m[2][2] * v.z)};
    }
    // The transposed linear part times v: on this matrix's inverse, carries a surface
    // normal (the inverse transpose keeps it perpendicular to the moved surface and
    // on the same side of it). Not normalised.
    Vec3 transposed_vector(Vec3 v) const {
        return {Real(m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z),
                Real(m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z),
                Real(m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z)};
    }
};

// a after b: (a * b) p = a (b p).
inline Affine operator*(const Affine& a, const Affine& b) {
    Affine r;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 4; ++j) {
            double s = a.m[i][0] * b.m[0][j] + a.m[i][1] * b.m[1][j] + a.m[i][2] * b.m[2][j];
            if (j == 3) s += a.m[i][3];
            r.m[i][j] = s;
        }
    }
    return r;
}

}  // namespace rt
