// What every kind of material shares in the renderer: the material the integrator
// shades with (built from the scene file's MaterialDesc, rt/loader/material_desc.h), and
// what a kind's scatter() gets and gives. One kind of material is one file of
// include/rt/materials/ (plain.h, mirror.h, conductor.h, dielectric.h); materials.h lists
// them.
//
// A kind M provides, each used by exactly one stage:
//   M::Format                its format (rt/loader/material_desc.h): name, _type word,
//                            keys and their reading
//   M::kShadedFromInside     whether the lights shade a hit on its back face
//   M::kRefracts             whether it sends rays through its surface (--trace)
//   M::scatter(m, in, out)   integrator: its secondary rays (spec 2.6)
//   M::mtl(desc, w)          OBJ export (rtconvert): its MTL lines
#pragma once
#include <cstdint>
#include <string>

#include "rt/core/math.h"
#include "rt/loader/material_desc.h"
#include "rt/materials/optics.h"

namespace rt {

// A material as the integrator shades with it (spec 2.6), made from its MaterialDesc
// when the scene is built (make_material). A Plain material's mirror is never read
// (reference-conventions.md, "Shading").
struct Material {
    MaterialType type{};
    Vec3 ambient, diffuse, specular;
    Real phong_exponent = 1;
    Vec3 mirror;                  // MirrorReflectance
    Real refraction_index = 1;    // conductors and dielectrics
    Real absorption_index = 0;    // conductors: imaginary part k of the complex index
    Vec3 absorption_coefficient;  // dielectrics: Beer's law c, per unit distance
    std::string id;               // its _id, for --trace
    Real roughness = 0;           // how far its secondary rays are perturbed (perturb_direction)
};

inline Material make_material(const MaterialDesc& d) {
    return {d.type,
            d.ambient,
            d.diffuse,
            d.specular,
            d.phong_exponent,
            d.mirror,
            d.refraction_index,
            d.absorption_index,
            d.absorption_coefficient,
            d.id,
            d.type == MaterialType::Plain ? Real(0) : d.roughness};
}

// The dielectric a ray travels inside: a material index, or none.
constexpr int kNoMedium = -1;

// A hit as scatter() sees it.
struct ScatterIn {
    Ray ray;     // the incoming ray
    Vec3 p;      // the hit point
    Vec3 nf;     // unit shading normal turned towards the incoming ray
    bool front;  // the ray meets the outward side
    Real cos_i;  // -dot(ray.dir, nf)
    Real eps;    // ShadowRayEpsilon: secondary rays start this far off the surface
    int self;    // this material's index (a medium for rays sent inside it)

    // The mirror reflection, spawned on the side the incoming ray came from.
    Ray reflected() const { return spawn_ray(p, nf, eps, normalize(ray.dir + nf * (2 * cos_i))); }
};

// The secondary rays a kind sends, in the order they are traced and summed, and what
// --trace records of its Fresnel terms.
struct ScatterOut {
    struct Secondary {
        Vec3 factor;  // what the ray's radiance is multiplied by
        Ray ray;
        int medium;  // the dielectric the ray travels inside, or kNoMedium
        RayKind kind;
    };
    Secondary rays[2];
    int n = 0;
    bool has_fresnel = false;
    FresnelTerms fresnel;
    bool tir = false;       // total internal reflection: no refracted ray
    bool refracts = false;  // a refracted ray was sent, along `refracted`
    Vec3 refracted;

    void add(Vec3 factor, const Ray& r, int medium, RayKind kind) { rays[n++] = {factor, r, medium, kind}; }
};

}  // namespace rt
