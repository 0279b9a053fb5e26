// A material without _type (spec 3, "Material"): Blinn-Phong only, no secondary rays.
#pragma once
#include "rt/materials/material.h"

namespace rt {

struct PlainMaterial {
    using Format = PlainMaterialFormat;  // what the scene file says (rt/loader/material_desc.h)
    static constexpr bool kShadedFromInside = true;
    static constexpr bool kRefracts = false;

    static void scatter(const Material&, const ScatterIn&, ScatterOut&) {}

    template <class Mtl>
    static void mtl(const MaterialDesc& m, Mtl& w) {
        w.vec("Ks", m.specular).num("Ns", m.phong_exponent).line("illum 2");
    }
};

}  // namespace rt
