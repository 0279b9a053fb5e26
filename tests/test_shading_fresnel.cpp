// Shading tests, formulas: the reflectance formulas of include/rt/materials/optics.h (the
// Fresnel equations for dielectrics and conductors, Beer's law), against values worked out
// by hand in the comments, Snell's law, reciprocity and the complex Fresnel equations.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>

#include "rt/materials/optics.h"

namespace {

using rt::Real;
using rt::Vec3;

const Real kTol = 64 * std::numeric_limits<Real>::epsilon();
// Tolerances for values worked out by hand: tight ones for a single formula, loose ones for
// results of a few chained operations (double by default; float with PRECISION=float).
const Real kClose = sizeof(Real) == sizeof(double) ? Real(1e-12) : Real(2e-5);
const Real kLoose = sizeof(Real) == sizeof(double) ? Real(1e-9) : Real(2e-4);

// --- fresnel_dielectric ------------------------------------------------------------

TEST(ShadingFresnelDielectric, NormalIncidenceBothDirections) {
    // ((n - 1) / (n + 1))^2 = (0.5 / 2.5)^2 = 0.2^2 = 0.04
    Real cos_t = -1;
    EXPECT_NEAR(rt::fresnel_dielectric(1, 1, 1.5, &cos_t), 0.04, kTol);
    EXPECT_NEAR(cos_t, 1, kTol);
    cos_t = -1;
    EXPECT_NEAR(rt::fresnel_dielectric(1, 1.5, 1, &cos_t), 0.04, kTol);
    EXPECT_NEAR(cos_t, 1, kTol);
    // n = 2.4 (diamond): (1.4 / 3.4)^2 = 0.16955017...
    EXPECT_NEAR(rt::fresnel_dielectric(1, 1, 2.4), (1.4 * 1.4) / (3.4 * 3.4), kTol);
    // Matched indices reflect nothing.
    EXPECT_NEAR(rt::fresnel_dielectric(1, 1.33, 1.33), 0, kTol);
    EXPECT_NEAR(rt::fresnel_dielectric(Real(0.6), 1, 1), 0, kTol);
}

TEST(ShadingFresnelDielectric, GrazingIsOne) {
    // cos_i = 0: r_par = (0 - cos_t)/(0 + cos_t) = -1, r_perp = -1, F = 1.
    EXPECT_NEAR(rt::fresnel_dielectric(0, 1, 1.5), 1, kTol);
    EXPECT_NEAR(rt::fresnel_dielectric(0, 1, 2.4), 1, kTol);
    // Glass to air at grazing is total internal reflection anyway.
    EXPECT_EQ(rt::fresnel_dielectric(0, 1.5, 1), 1);
}

TEST(ShadingFresnelDielectric, TotalInternalReflection) {
    // Glass -> air: critical angle sin = 1/1.5 = 0.6667 (41.81 degrees).
    // sin_i = 0.7: cos_i = sqrt(1 - 0.49) = 0.714143; sin_t = 1.5 * 0.7 = 1.05 > 1.
    EXPECT_EQ(rt::fresnel_dielectric(std::sqrt(Real(0.51)), 1.5, 1), 1);
    // sin_i = 0.9, 0.99: deeper into TIR.
    EXPECT_EQ(rt::fresnel_dielectric(std::sqrt(Real(1 - 0.81)), 1.5, 1), 1);
    EXPECT_EQ(rt::fresnel_dielectric(std::sqrt(Real(1 - 0.9801)), 1.5, 1), 1);
    // Just inside the critical angle (sin_i = 0.66) light still gets through: F < 1.
    Real cos_t = -1;
    const Real f = rt::fresnel_dielectric(std::sqrt(Real(1 - 0.66 * 0.66)), 1.5, 1, &cos_t);
    EXPECT_LT(f, 1);
    EXPECT_GT(f, 0.04);
    // sin_t = 1.5 * 0.66 = 0.99, cos_t = sqrt(1 - 0.9801) = 0.141067
    EXPECT_NEAR(cos_t, std::sqrt(Real(1 - 0.99 * 0.99)), kClose);
    // Air -> glass never has TIR.
    EXPECT_LT(rt::fresnel_dielectric(std::sqrt(Real(0.51)), 1, 1.5), 1);
}

TEST(ShadingFresnelDielectric, FortyFiveDegreesByHand) {
    // Air -> glass (n = 1.5) at 45 degrees: cos_i = sin_i = 0.70710678.
    //   sin_t = 0.70710678 / 1.5 = 0.47140452, cos_t = sqrt(1 - 0.22222222) = 0.88191710
    //   r_par  = (1.5 cos_i - cos_t) / (1.5 cos_i + cos_t) = (1.06066017 - 0.88191710) / 1.94257727 = 0.09201336
    //   r_perp = (cos_i - 1.5 cos_t) / (cos_i + 1.5 cos_t) = (0.70710678 - 1.32287566) / 2.02998244 = -0.30333705
    //   F = (0.09201336^2 + 0.30333705^2) / 2 = (0.00846646 + 0.09201336) / 2 = 0.05023991
    Real cos_t = -1;
    EXPECT_NEAR(rt::fresnel_dielectric(std::sqrt(Real(0.5)), 1, 1.5, &cos_t), 0.05023991101223592, kClose);
    EXPECT_NEAR(cos_t, 0.8819171036881968, kClose);
}

TEST(ShadingFresnelDielectric, SnellsLawAndReciprocity) {
    for (Real eta_i : {Real(1), Real(1.5), Real(1.33)}) {
        for (Real eta_t : {Real(1), Real(1.5), Real(2.4)}) {
            for (Real cos_i : {Real(1), Real(0.95), Real(0.8), Real(0.5), Real(0.3), Real(0.05)}) {
                const Real sin_i = std::sqrt(1 - cos_i * cos_i);
                if (eta_i * sin_i >= eta_t) continue;  // TIR, checked above
                Real cos_t = -1;
                const Real f = rt::fresnel_dielectric(cos_i, eta_i, eta_t, &cos_t);
                ASSERT_GE(cos_t, 0);
                ASSERT_LE(cos_t, 1);
                // Snell: eta_i sin_i = eta_t sin_t.
                const Real sin_t = std::sqrt(1 - cos_t * cos_t);
                EXPECT_NEAR(eta_i * sin_i, eta_t * sin_t, kLoose)
                    << "eta " << eta_i << " -> " << eta_t << ", cos_i " << cos_i;
                EXPECT_GE(f, 0);
                EXPECT_LE(f, 1);
                // Reciprocity: the same pair of angles seen from the other side reflects alike.
                Real back_cos = -1;
                EXPECT_NEAR(rt::fresnel_dielectric(cos_t, eta_t, eta_i, &back_cos), f, kLoose);
                EXPECT_NEAR(back_cos, cos_i, kLoose);
            }
        }
    }
}

TEST(ShadingFresnelDielectric, ClampsCosineOutsideUnitRange) {
    // Shading normals can make cos_i slightly negative or above 1: treated as 0 or 1.
    EXPECT_NEAR(rt::fresnel_dielectric(Real(1.0000001), 1, 1.5), 0.04, kLoose);
    EXPECT_NEAR(rt::fresnel_dielectric(Real(-0.01), 1, 1.5), 1, kLoose);
}

// --- fresnel_conductor --------------------------------------------------------------

// Independent reference: Fresnel amplitudes with the complex index eta = n + i k, from air.
Real conductor_reference(Real cos_i, Real n, Real k) {
    using C = std::complex<double>;
    const C eta(n, k);
    const double c = cos_i, s2 = 1 - c * c;
    const C root = std::sqrt(eta * eta - s2);
    const C rs = (c - root) / (c + root);
    const C rp = (eta * eta * c - root) / (eta * eta * c + root);
    return static_cast<Real>((std::norm(rs) + std::norm(rp)) / 2);
}

TEST(ShadingFresnelConductor, NormalIncidenceGold) {
    // ((n-1)^2 + k^2) / ((n+1)^2 + k^2) with n = 0.37, k = 2.82:
    //   (0.3969 + 7.9524) / (1.8769 + 7.9524) = 8.3493 / 9.8293 = 0.84942977
    EXPECT_NEAR(rt::fresnel_conductor(1, 0.37, 2.82), 0.8494297661074542, kClose);
    // Silver-ish n = 0.15, k = 3.6: (0.7225 + 12.96) / (1.3225 + 12.96) = 13.6825 / 14.2825 = 0.95799
    EXPECT_NEAR(rt::fresnel_conductor(1, 0.15, 3.6), 13.6825 / 14.2825, kClose);
}

TEST(ShadingFresnelConductor, GrazingIsOne) {
    EXPECT_NEAR(rt::fresnel_conductor(0, 0.37, 2.82), 1, kTol);
    EXPECT_NEAR(rt::fresnel_conductor(0, 1.5, 0), 1, kTol);
    EXPECT_NEAR(rt::fresnel_conductor(0, 0.2, 5), 1, kTol);
}

TEST(ShadingFresnelConductor, ZeroAbsorptionEqualsDielectric) {
    for (Real n : {Real(1.5), Real(2.4), Real(1.2)}) {
        for (Real cos_i : {Real(1), Real(0.9), Real(0.7071), Real(0.5), Real(0.3), Real(0.1), Real(0.01)}) {
            EXPECT_NEAR(rt::fresnel_conductor(cos_i, n, 0), rt::fresnel_dielectric(cos_i, 1, n), kClose)
                << "n " << n << ", cos_i " << cos_i;
        }
    }
}

TEST(ShadingFresnelConductor, MatchesComplexFresnelEquations) {
    const Real metals[][2] = {{0.37, 2.82}, {0.15, 3.6}, {1.5, 0.5}, {2.9, 3.1}, {0.2, 0.2}};
    for (const auto& m : metals) {
        for (int i = 0; i <= 20; ++i) {
            const Real cos_i = Real(i) / 20;
            const Real f = rt::fresnel_conductor(cos_i, m[0], m[1]);
            EXPECT_NEAR(f, conductor_reference(cos_i, m[0], m[1]), kLoose)
                << "n " << m[0] << ", k " << m[1] << ", cos_i " << cos_i;
            EXPECT_GE(f, 0);
            EXPECT_LE(f, 1 + kTol);
        }
    }
}

// --- beer_attenuation ---------------------------------------------------------------

TEST(ShadingBeer, PerChannelExponential) {
    // c = (0.1, 0.5, 2), d = 3: (e^-0.3, e^-1.5, e^-6) = (0.74081822, 0.22313016, 0.00247875)
    const Vec3 a = rt::beer_attenuation({0.1, 0.5, 2}, 3);
    EXPECT_NEAR(a.x, 0.7408182206817179, kClose);
    EXPECT_NEAR(a.y, 0.22313016014842982, kClose);
    EXPECT_NEAR(a.z, 0.0024787521766663585, kClose);
    const Vec3 one = rt::beer_attenuation({0.1, 0.5, 2}, 0);
    EXPECT_EQ(one.x, 1);
    EXPECT_EQ(one.y, 1);
    EXPECT_EQ(one.z, 1);
    const Vec3 clear = rt::beer_attenuation({0, 0, 0}, 100);
    EXPECT_EQ(clear.x, 1);
    EXPECT_EQ(clear.z, 1);
}

}  // namespace
