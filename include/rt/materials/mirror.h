// A mirror (spec 2.6, _type "mirror"): reflects MirrorReflectance of the light.
#pragma once
#include "rt/materials/material.h"

namespace rt {

struct MirrorMaterial {
    using Format = MirrorMaterialFormat;  // what the scene file says (rt/loader/material_desc.h)
    static constexpr bool kShadedFromInside = true;
    static constexpr bool kRefracts = false;

    static void scatter(const Material& m, const ScatterIn& in, ScatterOut& out) {
        out.add(m.mirror, in.reflected(), kNoMedium, RayKind::Reflection);
    }

    // MTL: illum 3 reflects with weight Ks.
    template <class Mtl>
    static void mtl(const MaterialDesc& m, Mtl& w) {
        w.vec("Ks", m.mirror).num("Ns", m.phong_exponent).line("illum 3");
    }
};

}  // namespace rt
