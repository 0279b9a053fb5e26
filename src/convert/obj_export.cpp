// A loaded scene as Wavefront OBJ + MTL, for Blender, MeshLab and friends: meshes as
// they are, spheres as UV spheres, planes as large quads, materials mapped back onto
// MTL's fields. Faces keep our counter-clockwise-is-front winding.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "rt/convert/convert.h"

namespace rt {
namespace {

// The shortest text that reads back as the same Real (a float's own digits, not
// its double's: 0.6f is "0.6", not "0.6000000238418579").
std::string num(Real d) {
    if (d == 0) return "0";
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    return std::string(buf, r.ptr);
}

std::string vec(const Vec3& v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }

struct Bounds {
    Vec3 lo{INFINITY, INFINITY, INFINITY}, hi{-INFINITY, -INFINITY, -INFINITY};
    void add(const Vec3& p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    bool empty() const { return !(lo.x <= hi.x); }
};

class ObjWriter {
public:
    std::string text;
    size_t vertices = 0;  // written so far; OBJ indices are 1-based

    size_t vertex(const Vec3& p) {
        text += "v " + vec(p) + "\n";
        return ++vertices;
    }
    void face(std::initializer_list<size_t> ids) {
        text += "f";
        for (size_t i : ids) text += " " + std::to_string(i);
        text += "\n";
    }
    void object(const std::string& name, uint32_t material, bool smooth) {
        text +=
            "o " + name + "\nusemtl material_" + std::to_string(material + 1) + "\ns " + (smooth ? "1" : "off") + "\n";
    }
};

std::string mtl_material(const MaterialDesc& m, size_t index) {
    std::string s = "newmtl material_" + std::to_string(index + 1) + "\n";
    s += std::string("# ") + material_type_name(m.type) + "; exact values: Ks " + vec(m.specular) +
         ", MirrorReflectance " + vec(m.mirror) + ", RefractionIndex " + num(m.refraction_index) +
         ", AbsorptionIndex " + num(m.absorption_index) + ", AbsorptionCoefficient " + vec(m.absorption_coefficient) +
         "\n";
    s += "Ka " + vec(m.ambient) + "\n";
    s += "Kd " + vec(m.diffuse) + "\n";
    switch (m.type) {
        case MaterialType::Plain:
            s += "Ks " + vec(m.specular) + "\nNs " + num(m.phong_exponent) + "\nillum 2\n";
            break;
        case MaterialType::Mirror:
        case MaterialType::Conductor:
            // MTL: illum 3 reflects with weight Ks.
            s += "Ks " + vec(m.mirror) + "\nNs " + num(m.phong_exponent) + "\nillum 3\n";
            if (m.type == MaterialType::Conductor) s += "Ni " + num(m.refraction_index) + "\n";
            break;
        case MaterialType::Dielectric: {
            // MTL: illum 7 refracts with index Ni; Tf is the fraction transmitted per unit length.
            const Vec3& c = m.absorption_coefficient;
            const Vec3 tf{std::exp(-c.x), std::exp(-c.y), std::exp(-c.z)};
            s += "Ks " + vec(m.specular) + "\nNs " + num(m.phong_exponent) + "\nNi " + num(m.refraction_index) +
                 "\nTf " + vec(tf) + "\nillum 7\n";
            break;
        }
    }
    return s + "\n";
}

}  // namespace

ObjText scene_to_obj(const SceneDesc& scene, const std::string& mtl_file_name, int sphere_segments) {
    const int segments = std::max(sphere_segments, 3);
    const int rings = std::max(segments / 2, 2);
    ObjText out;
    ObjWriter w;
    w.text = "# " + (scene.path.empty() ? std::string("scene") : scene.path) + ", exported by rtconvert\n";
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        const CameraDesc& c = scene.cameras[i];
        w.text += "# camera " + std::to_string(i + 1) + ": position " + vec(c.position) + ", gaze " + vec(c.gaze) +
                  ", up " + vec(c.up) + ", image " + c.image_name + "\n";
    }
    for (size_t i = 0; i < scene.point_lights.size(); ++i)
        w.text += "# point light " + std::to_string(i + 1) + ": position " + vec(scene.point_lights[i].position) +
                  ", intensity " + vec(scene.point_lights[i].intensity) + "\n";
    w.text += "mtllib " + mtl_file_name + "\n";

    // The scene's extent sizes the planes.
    Bounds b;
    for (const MeshDesc& m : scene.meshes)
        for (const Vec3& p : m.positions) b.add(p);
    for (const SphereDesc& s : scene.spheres) {
        b.add(s.center - Vec3{s.radius, s.radius, s.radius});
        b.add(s.center + Vec3{s.radius, s.radius, s.radius});
    }
    for (const CameraDesc& c : scene.cameras) b.add(c.position);
    for (const PointLightDesc& l : scene.point_lights) b.add(l.position);
    for (const PlaneDesc& p : scene.planes) b.add(p.point);
    const Vec3 center = b.empty() ? Vec3{0, 0, 0} : (b.lo + b.hi) * Real(0.5);
    const Real extent = b.empty() ? Real(1) : std::max(length(b.hi - b.lo), Real(1));

    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const MeshDesc& m = scene.meshes[i];
        w.object("mesh_" + std::to_string(i + 1), m.material, m.shading == ShadingMode::Smooth);
        const size_t base = w.vertices;
        for (const Vec3& p : m.positions) w.vertex(p);
        for (size_t t = 0; t + 2 < m.indices.size(); t += 3)
            w.face({base + m.indices[t] + 1, base + m.indices[t + 1] + 1, base + m.indices[t + 2] + 1});
    }

    const Real pi = kPi;
    for (size_t i = 0; i < scene.spheres.size(); ++i) {
        const SphereDesc& s = scene.spheres[i];
        w.object("sphere_" + std::to_string(i + 1), s.material, true);
        // Rings of constant polar angle from +y; quads (a b c d) run along the ring,
        // then down: counter-clockwise seen from outside.
        const size_t north = w.vertex(s.center + Vec3{0, s.radius, 0});
        const size_t first = w.vertices + 1;
        for (int r = 1; r < rings; ++r) {
            const Real theta = pi * Real(r) / Real(rings);
            for (int k = 0; k < segments; ++k) {
                const Real phi = 2 * pi * Real(k) / Real(segments);
                w.vertex(s.center +
                         Vec3{std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)} *
                             s.radius);
            }
        }
        const size_t south = w.vertex(s.center - Vec3{0, s.radius, 0});
        auto at = [&](int r, int k) { return first + size_t(r - 1) * size_t(segments) + size_t(k % segments); };
        for (int k = 0; k < segments; ++k) w.face({north, at(1, k + 1), at(1, k)});
        for (int r = 1; r + 1 < rings; ++r)
            for (int k = 0; k < segments; ++k) w.face({at(r, k), at(r, k + 1), at(r + 1, k + 1), at(r + 1, k)});
        for (int k = 0; k < segments; ++k) w.face({at(rings - 1, k), at(rings - 1, k + 1), south});
    }

    for (size_t i = 0; i < scene.planes.size(); ++i) {
        const PlaneDesc& p = scene.planes[i];
        w.object("plane_" + std::to_string(i + 1), p.material, false);
        const Vec3 n = normalize(p.normal);
        const Vec3 helper = std::fabs(n.x) < Real(0.9) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 u = normalize(cross(n, helper));
        const Vec3 v = cross(n, u);  // u x v = n: (-u-v, u-v, u+v, -u+v) is counter-clockwise about n
        const Vec3 c = center - n * dot(center - p.point, n);
        const Real h = 5 * extent;
        const size_t a = w.vertex(c - u * h - v * h);
        w.vertex(c + u * h - v * h);
        w.vertex(c + u * h + v * h);
        w.vertex(c - u * h + v * h);
        w.face({a, a + 1, a + 2, a + 3});
    }
    out.obj = std::move(w.text);

    out.mtl =
        "# materials of " + (scene.path.empty() ? std::string("scene") : scene.path) + ", exported by rtconvert\n\n";
    for (size_t i = 0; i < scene.materials.size(); ++i) out.mtl += mtl_material(scene.materials[i], i);
    return out;
}

}  // namespace rt
