// SceneDesc -> Scene: flat arrays, normals, BVH.
#include <chrono>
#include <utility>

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
    const bool smooth = m.shading == ShadingMode::Smooth;
    s.vertex_normals.resize(s.positions.size(), Vec3{});
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
        Triangle t;
        t.v[0] = a;
        t.v[1] = b;
        t.v[2] = c;
        t.material = m.material;
        t.smooth = smooth ? 1 : 0;
        s.triangles.push_back(t);
    }
    if (smooth) {
        for (size_t i = base; i < s.positions.size(); ++i) {
            const Real len = length(s.vertex_normals[i]);
            if (len > 0) s.vertex_normals[i] = s.vertex_normals[i] / len;
        }
    }
}

BuildBox make_box(Vec3 lo, Vec3 hi) {
    BuildBox b{};
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = round_down_to_float(lo[a]);
        b.hi[a] = round_up_to_float(hi[a]);
    }
    return b;
}

// Builds everything; `release(i)` is called once mesh i has been copied.
template <class Release>
Scene build(const SceneDesc& d, const BvhBuildOptions& bvh, Release release) {
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
    for (size_t i = 0; i < d.meshes.size(); ++i) {
        add_mesh(s, d.meshes[i]);
        release(i);
    }
    s.triangles.shrink_to_fit();
    for (const SphereDesc& sp : d.spheres) s.spheres.push_back({sp.center, sp.radius, sp.material});
    for (const PlaneDesc& p : d.planes) s.planes.push_back({p.point, normalize(p.normal), p.material});

    const auto t0 = std::chrono::steady_clock::now();
    std::vector<BuildBox> boxes(s.triangles.size() + s.spheres.size());
    for (size_t i = 0; i < s.triangles.size(); ++i) {
        const Triangle& t = s.triangles[i];
        const Vec3 a = s.positions[t.v[0]], b = s.positions[t.v[1]], c = s.positions[t.v[2]];
        boxes[i] = make_box(vmin(a, vmin(b, c)), vmax(a, vmax(b, c)));
    }
    for (size_t i = 0; i < s.spheres.size(); ++i) {
        const Sphere& sp = s.spheres[i];
        const Vec3 r{sp.radius, sp.radius, sp.radius};
        boxes[s.triangles.size() + i] = make_box(sp.center - r, sp.center + r);
    }
    s.bvh.build(std::move(boxes), bvh);
    s.build_seconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

}  // namespace

Scene build_scene(const SceneDesc& d, const BvhBuildOptions& bvh) {
    return build(d, bvh, [](size_t) {});
}

Scene build_scene(SceneDesc&& d, const BvhBuildOptions& bvh) {
    return build(d, bvh, [&d](size_t i) {
        std::vector<Vec3>().swap(d.meshes[i].positions);
        std::vector<uint32_t>().swap(d.meshes[i].indices);
    });
}

}  // namespace rt
