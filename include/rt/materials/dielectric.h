// A dielectric (spec 2.6, _type "dielectric"): reflects the Fresnel reflectance F
// (times MirrorReflectance) and refracts 1 - F through its surface; Beer's law with
// AbsorptionCoefficient inside. Not shaded by the lights from inside
// (reference-conventions.md, "Materials").
#pragma once
#include <cmath>

#include "rt/materials/material.h"

namespace rt {

struct DielectricMaterial {
    using Format = DielectricMaterialFormat;  // what the scene file says (rt/loader/material_desc.h)
    static constexpr bool kShadedFromInside = false;
    static constexpr bool kRefracts = true;

    // A ray reflected off the inside or refracted in travels inside this dielectric
    // (docs/conventions.md, "Inside a dielectric").
    static void scatter(const Material& m, const ScatterIn& in, ScatterOut& out) {
        const Real eta_i = in.front ? Real(1) : m.refraction_index;
        const Real eta_t = in.front ? m.refraction_index : Real(1);
        const FresnelTerms f = fresnel_dielectric_terms(in.cos_i, eta_i, eta_t);
        const Real fr = f.reflectance;
        out.has_fresnel = true;
        out.fresnel = f;
        out.tir = !(fr < 1) && eta_i > eta_t;
        out.add(m.mirror * fr, in.reflected(), in.front ? kNoMedium : in.self, RayKind::Reflection);
        if (fr < 1) {
            const Real eta = eta_i / eta_t;
            const Vec3 t_dir = normalize(in.ray.dir * eta + in.nf * (eta * in.cos_i - f.cos_t));
            out.refracts = true;
            out.refracted = t_dir;
            out.add(Vec3{1, 1, 1} * (1 - fr), spawn_ray(in.p, -in.nf, in.eps, t_dir), in.front ? in.self : kNoMedium,
                    RayKind::Refraction);
        }
    }

    // MTL: illum 7 refracts with index Ni; Tf is the fraction transmitted per unit length.
    template <class Mtl>
    static void mtl(const MaterialDesc& m, Mtl& w) {
        const Vec3& c = m.absorption_coefficient;
        const Vec3 tf{std::exp(-c.x), std::exp(-c.y), std::exp(-c.z)};
        w.vec("Ks", m.specular).num("Ns", m.phong_exponent).num("Ni", m.refraction_index).vec("Tf", tf).line("illum 7");
    }
};

}  // namespace rt
