// The Fresnel equations (spec 2.6; rt/materials/optics.h).
#include <algorithm>
#include <cmath>

#include "rt/materials/optics.h"

namespace rt {

FresnelTerms fresnel_dielectric_terms(Real cos_i, Real eta_i, Real eta_t) {
    FresnelTerms f;
    f.eta_i = eta_i;
    f.eta_t = eta_t;
    cos_i = std::clamp(cos_i, Real(0), Real(1));
    f.cos_i = cos_i;
    const Real sin_i2 = std::max(Real(0), 1 - cos_i * cos_i);
    const Real ratio = eta_i / eta_t;
    f.sin_t2 = ratio * ratio * sin_i2;
    if (f.sin_t2 >= 1) {  // total internal reflection
        f.r_par = f.r_perp = f.reflectance = 1;
        return f;
    }
    const Real cos_t = std::sqrt(1 - f.sin_t2);
    f.cos_t = cos_t;
    const Real r_par = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
    const Real r_perp = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
    f.r_par = r_par * r_par;
    f.r_perp = r_perp * r_perp;
    f.reflectance = (f.r_par + f.r_perp) / 2;
    return f;
}

// Exact Fresnel equations for a complex relative index (as in pbrt-v3's FrConductor):
// a^2 + b^2 = sqrt((n^2 - k^2 - sin^2)^2 + 4 n^2 k^2).
FresnelTerms fresnel_conductor_terms(Real cos_i, Real n, Real k) {
    FresnelTerms f;
    f.formula = FresnelFormula::Conductor;
    f.eta_t = n;
    f.k = k;
    cos_i = std::clamp(cos_i, Real(0), Real(1));
    f.cos_i = cos_i;
    const Real cos2 = cos_i * cos_i;
    const Real sin2 = 1 - cos2;
    const Real t0 = n * n - k * k - sin2;
    const Real a2b2 = std::sqrt(t0 * t0 + 4 * n * n * k * k);
    const Real a = std::sqrt(std::max(Real(0), (a2b2 + t0) / 2));
    const Real t1 = a2b2 + cos2;
    const Real t2 = 2 * cos_i * a;
    const Real rs = (t1 - t2) / (t1 + t2);
    const Real t3 = cos2 * a2b2 + sin2 * sin2;
    const Real t4 = t2 * sin2;
    const Real rp = rs * (t3 - t4) / (t3 + t4);
    f.r_perp = rs;
    f.r_par = rp;
    f.reflectance = (rs + rp) / 2;
    return f;
}

}  // namespace rt
