// A loaded scene as Wavefront OBJ + MTL, for Blender, MeshLab and friends: meshes as
// they are, spheres as UV spheres, planes as large quads, materials mapped back onto
// MTL's fields. Faces keep our counter-clockwise-is-front winding.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <string>

#include "rt/convert/convert.h"
#include "rt/materials/materials.h"
#include "rt/shapes/shapes.h"

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

// What a material kind's mtl() writes with: "key value" lines.
struct MtlLines {
    std::string& text;
    MtlLines& vec(const char* key, Vec3 v) { return line(key + (" " + rt::vec(v))); }
    MtlLines& num(const char* key, Real x) { return line(key + (" " + rt::num(x))); }
    MtlLines& line(const std::string& l) {
        text += l + "\n";
        return *this;
    }
};

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
    // A face of vertices numbered from 0 after the first `base` written.
    void face(const std::vector<uint32_t>& local, size_t base) {
        text += "f";
        for (uint32_t i : local) text += " " + std::to_string(base + i + 1);
        text += "\n";
    }
    void object(const std::string& name, uint32_t material, bool smooth, const Vec3& motion) {
        text += "o " + name + "\n";
        if (!is_still(motion)) text += "# MotionBlur " + vec(motion) + "\n";
        text += "usemtl material_" + std::to_string(material + 1) + "\ns " + (smooth ? "1" : "off") + "\n";
    }
};

std::string mtl_material(const MaterialDesc& m, size_t index) {
    std::string s = "newmtl material_" + std::to_string(index + 1) + "\n";
    s += std::string("# ") + material_type_name(m.type) + "; exact values: Ks " + vec(m.specular) +
         ", MirrorReflectance " + vec(m.mirror) + ", RefractionIndex " + num(m.refraction_index) +
         ", AbsorptionIndex " + num(m.absorption_index) + ", AbsorptionCoefficient " + vec(m.absorption_coefficient) +
         ", Roughness " + num(m.roughness) + "\n";
    s += "Ka " + vec(m.ambient) + "\n";
    s += "Kd " + vec(m.diffuse) + "\n";
    MtlLines lines{s};  // the kind's own lines (rt/materials/)
    visit_material<void>(m.type, [&](auto k) { decltype(k)::mtl(m, lines); });
    return s + "\n";
}

}  // namespace

ExportFrame export_frame(const SceneDesc& scene, int sphere_segments) {
    // The scene's extent sizes the planes.
    Bounds b;
    for (const MeshDesc& m : scene.meshes)
        if (!m.instanced)
            for (const Vec3& p : m.positions) b.add(m.transform.point(p));
    for_each_shape([&](auto k) {
        using S = decltype(k);
        for (const typename S::Desc& e : scene.all<typename S::Desc>())
            S::extent(e, scene.meshes, [&b](Vec3 p) { b.add(p); });
    });
    for (const CameraDesc& c : scene.cameras) b.add(c.position);
    for (const PointLightDesc& l : scene.point_lights) b.add(l.position);
    const Vec3 center = b.empty() ? Vec3{0, 0, 0} : (b.lo + b.hi) * Real(0.5);
    const Real extent = b.empty() ? Real(1) : std::max(length(b.hi - b.lo), Real(1));
    return ExportFrame{sphere_segments, center, extent, &scene.meshes};
}

ObjText scene_to_obj(const SceneDesc& scene, const std::string& mtl_file_name, int sphere_segments) {
    ObjText out;
    ObjWriter w;
    w.text = "# " + (scene.path.empty() ? std::string("scene") : scene.path) + ", exported by rtconvert\n";
    for (size_t i = 0; i < scene.cameras.size(); ++i) {
        const CameraDesc& c = scene.cameras[i];
        w.text += "# camera " + std::to_string(i + 1) + ": position " + vec(c.position) + ", gaze " + vec(c.gaze) +
                  ", up " + vec(c.up) + ", image " + c.image_name;
        if (c.num_samples > 0) w.text += ", NumSamples " + std::to_string(c.num_samples);
        if (c.aperture_size > 0 || c.focus_distance > 0)
            w.text += ", ApertureSize " + num(c.aperture_size) + ", FocusDistance " + num(c.focus_distance);
        w.text += "\n";
    }
    for (size_t i = 0; i < scene.point_lights.size(); ++i)
        w.text += "# point light " + std::to_string(i + 1) + ": position " + vec(scene.point_lights[i].position) +
                  ", intensity " + vec(scene.point_lights[i].intensity) + "\n";
    for (size_t i = 0; i < scene.area_lights.size(); ++i) {
        const AreaLightDesc& l = scene.area_lights[i];
        w.text += "# area light " + std::to_string(i + 1) + ": position " + vec(l.position) + ", normal " +
                  vec(l.normal) + ", size " + num(l.size) + ", radiance " + vec(l.radiance) + "\n";
    }
    w.text += "mtllib " + mtl_file_name + "\n";

    auto write = [&w](const std::string& name, uint32_t material, const Polygons& poly, const Vec3& motion) {
        w.object(name, material, poly.smooth, motion);
        const size_t base = w.vertices;
        for (const Vec3& v : poly.vertices) w.vertex(v);
        for (const std::vector<uint32_t>& f : poly.faces) w.face(f, base);
    };
    // A mesh an instance shows is written as the instance of itself (rt/shapes/instance.h).
    for (size_t i = 0; i < scene.meshes.size(); ++i) {
        const MeshDesc& m = scene.meshes[i];
        if (!m.instanced) write("mesh_" + std::to_string(i + 1), m.material, mesh_polygons(m, m.transform), m.motion);
    }

    // The other kinds (rt/shapes/shapes.h) as their polygons.
    const ExportFrame frame = export_frame(scene, sphere_segments);
    for_each_shape([&](auto k) {
        using S = decltype(k);
        const std::vector<typename S::Desc>& list = scene.all<typename S::Desc>();
        for (size_t i = 0; i < list.size(); ++i)
            write(std::string(S::Desc::kNoun) + "_" + std::to_string(i + 1), list[i].material,
                  S::polygons(list[i], frame), list[i].motion);
    });
    out.obj = std::move(w.text);

    out.mtl =
        "# materials of " + (scene.path.empty() ? std::string("scene") : scene.path) + ", exported by rtconvert\n\n";
    for (size_t i = 0; i < scene.materials.size(); ++i) out.mtl += mtl_material(scene.materials[i], i);
    return out;
}

}  // namespace rt
