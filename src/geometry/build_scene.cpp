// SceneDesc -> Scene: flat arrays, normals, BVH.
#include <chrono>

#include "rt/scene.h"

namespace rt {
namespace {

Material make_material(const MaterialDesc& d) {
    Material m;
    m.type = d.type;
    m.ambient = d.ambient;
    m.diffuse = d.diffuse;
    m.specular = d.specular;
    m.phong_exponent = d.phong_exponent;
    // MirrorReflectance on a material without _type is ignored
    // (reference-conventions.md, "Shading"): the akif_uslu scenes carry it.
    m.mirror = d.type == MaterialType::Plain ? Vec3{} : d.mirror;
    m.refraction_index = d.refraction_index;
    m.absorption_index = d.absorption_index;
    m.absorption_coefficient = d.absorption_coefficient;
    return m;
}

// Appends one mesh: its vertices, its non-degenerate triangles, and, when
// smooth, vertex normals averaged over this mesh only, weighted by area
// (spec section 3, "Mesh"; pooling across meshes does not match the references).
void add_mesh(Scene& s, const MeshDesc& m) {
    const uint32_t base = static_cast<uint32_t>(s.positions.size());
    s.positions.insert(s.positions.end(), m.positions.begin(), m.positions.end());
    s.vertex_normals.resize(s.positions.size(), Vec3{});
    const uint32_t smooth = m.shading == ShadingMode::Smooth ? 1 : 0;
    for (size_t f = 0; f + 2 < m.indices.size(); f += 3) {
        const uint32_t a = base + m.indices[f], b = base + m.indices[f + 1], c = base + m.indices[f + 2];
        const Vec3 n = cross(s.positions[b] - s.positions[a], s.positions[c] - s.positions[a]);
        const Real len = length(n);
        // Degenerate (spec 2.10): two vertices coincide or all three are collinear.
        if (!(len > 0) || !std::isfinite(len)) {
            ++s.degenerate_triangles;
            continue;
        }
        if (smooth) {
            // |n| is twice the area, so adding n weights each face by its area.
            s.vertex_normals[a] += n;
            s.vertex_normals[b] += n;
            s.vertex_normals[c] += n;
        }
        s.triangles.push_back({{a, b, c}, m.material, smooth});
        s.face_normals.push_back(n / len);
    }
    if (smooth) {
        for (size_t i = base; i < s.positions.size(); ++i) {
            const Real len = length(s.vertex_normals[i]);
            if (len > 0) s.vertex_normals[i] = s.vertex_normals[i] / len;
        }
    }
}

}  // namespace

Scene build_scene(const SceneDesc& d) {
    Scene s;
    s.path = d.path;
    s.background = d.background;
    s.ambient_light = d.ambient_light;
    s.shadow_ray_epsilon = d.shadow_ray_epsilon;
    s.max_recursion_depth = d.max_recursion_depth;
    for (const CameraDesc& c : d.cameras) s.cameras.push_back(make_camera(c));
    for (const PointLightDesc& l : d.point_lights) s.lights.push_back({l.position, l.intensity});
    for (const MaterialDesc& m : d.materials) s.materials.push_back(make_material(m));

    size_t ntri = 0, nvert = 0;
    for (const MeshDesc& m : d.meshes) {
        ntri += m.indices.size() / 3;
        nvert += m.positions.size();
    }
    s.positions.reserve(nvert);
    s.vertex_normals.reserve(nvert);
    s.triangles.reserve(ntri);
    s.face_normals.reserve(ntri);
    for (const MeshDesc& m : d.meshes) add_mesh(s, m);
    for (const SphereDesc& sp : d.spheres) s.spheres.push_back({sp.center, sp.radius, sp.material});
    for (const PlaneDesc& p : d.planes) s.planes.push_back({p.point, normalize(p.normal), p.material});

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<Aabb> bounds(s.triangles.size() + s.spheres.size());
    for (size_t i = 0; i < s.triangles.size(); ++i)
        for (uint32_t v : s.triangles[i].v) bounds[i].extend(s.positions[v]);
    for (size_t i = 0; i < s.spheres.size(); ++i) {
        const Sphere& sp = s.spheres[i];
        const Vec3 r{sp.radius, sp.radius, sp.radius};
        bounds[s.triangles.size() + i] = Aabb{sp.center - r, sp.center + r};
    }
    s.bvh.build(bounds);
    s.build_seconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

}  // namespace rt
