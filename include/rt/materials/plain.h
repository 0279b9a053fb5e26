// A material without _type (spec 3, "Material"): Blinn-Phong only, no secondary rays.
#pragma once
#include "rt/materials/material.h"

namespace rt {

struct PlainMaterial {
    static constexpr const char* kName = "plain";
    static constexpr const char* kTypeWord = nullptr;
    static constexpr const char* kKeys[] = {"MirrorReflectance"};
    static constexpr bool kShadedFromInside = true;
    static constexpr bool kRefracts = false;

    // MirrorReflectance is read (and checked) but not used: the akif_uslu scenes
    // carry it on plain materials (reference-conventions.md, "Shading").
    template <class Reader>
    static void read(Reader& r, MaterialDesc& d) {
        d.mirror = r.color_or("MirrorReflectance", {1, 1, 1});
    }
    static void scatter(const MaterialDesc&, const ScatterIn&, ScatterOut&) {}

    template <class Mtl>
    static void mtl(const MaterialDesc& m, Mtl& w) {
        w.vec("Ks", m.specular).num("Ns", m.phong_exponent).line("illum 2");
    }
};

}  // namespace rt
