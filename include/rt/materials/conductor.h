// A conductor (spec 2.6, _type "conductor"): a mirror whose reflectance is the
// Fresnel reflectance of the complex index RefractionIndex + i AbsorptionIndex,
// times MirrorReflectance.
#pragma once
#include "rt/materials/material.h"

namespace rt {

struct ConductorMaterial {
    using Format = ConductorMaterialFormat;  // what the scene file says (rt/loader/material_desc.h)
    static constexpr bool kShadedFromInside = true;
    static constexpr bool kRefracts = false;

    static void scatter(const Material& m, const ScatterIn& in, ScatterOut& out) {
        out.has_fresnel = true;
        out.fresnel = fresnel_conductor_terms(in.cos_i, m.refraction_index, m.absorption_index);
        out.add(m.mirror * out.fresnel.reflectance, in.reflected(), kNoMedium, RayKind::Reflection);
    }

    // MTL: illum 3 reflects with weight Ks.
    template <class Mtl>
    static void mtl(const MaterialDesc& m, Mtl& w) {
        w.vec("Ks", m.mirror).num("Ns", m.phong_exponent).line("illum 3").num("Ni", m.refraction_index);
    }
};

}  // namespace rt
