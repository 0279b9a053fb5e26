// Mesh instances (rt/shapes/instance.h): a ray carried into the mesh's own space and
// traced through its BVH; the surface carried back.
#include "rt/shapes/instance.h"

#include "rt/bvh/traverse.h"
#include "rt/loader/scene_desc.h"

namespace rt {

Instance Instance::build(const Desc& d, const BuildInputs& in) {
    Instance i;
    i.mesh = in.mesh_scenes.at(d.mesh).get();
    i.to_object = d.transform.inverse();
    i.material = d.material;
    // The world box around the mesh's object-space box, moved.
    const std::vector<Vec3>& pos = i.mesh->geometry.positions;
    if (i.mesh->geometry.triangles.empty()) return i;  // an empty box: never entered
    Vec3 lo = pos[0], hi = pos[0];
    for (const Vec3& p : pos) {
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    Vec3 wlo{Real(HUGE_VAL), Real(HUGE_VAL), Real(HUGE_VAL)}, whi = -wlo;
    for (int c = 0; c < 8; ++c) {
        const Vec3 p = d.transform.point({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
        wlo = vmin(wlo, p);
        whi = vmax(whi, p);
    }
    i.box = Box::around(wlo, whi);
    return i;
}

bool Instance::trace(const Ray& ray, Real tmin, Real tmax, bool cull, bool shadow, Real& t, Real w[3],
                     uint32_t& part) const {
    // Not renormalised: a point at t along the object ray is the point at t along `ray`.
    const Ray object{to_object.point(ray.org), to_object.vector(ray.dir)};
    if (shadow) {
        if (!any_hit(*mesh, object, tmin, tmax)) return false;
        t = tmin;  // shadow rays ask only whether something is there
        return true;
    }
    Hit h;
    if (!closest_hit(*mesh, object, tmin, tmax, cull, h)) return false;
    t = h.t;
    w[0] = h.w[0];
    w[1] = h.w[1];
    w[2] = h.w[2];
    part = h.index;
    return true;
}

Surface Instance::surface(Vec3, const Real w[3], uint32_t part) const {
    Hit h;
    h.kind = ShapeKind::Triangle;
    h.index = part;
    h.w[0] = w[0];
    h.w[1] = w[1];
    h.w[2] = w[2];
    // The object-space point is not needed: a triangle's surface comes from w.
    const Surface s = mesh->geometry.surface(h, Vec3{});
    // Normals go to the world by the inverse transpose: (M^-1)^T n.
    return {normalize(to_object.transposed_vector(s.ng)), normalize(to_object.transposed_vector(s.ns)), material};
}

const std::vector<Vec3>& Instance::mesh_positions(const Desc& d, const std::vector<MeshDesc>& meshes) {
    return meshes.at(d.mesh).positions;
}

Polygons mesh_polygons(const MeshDesc& m, const Affine& to_world) {
    Polygons out;
    out.smooth = m.shading == ShadingMode::Smooth;
    out.vertices = m.positions;
    out.faces.reserve(m.indices.size() / 3);
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
        out.faces.push_back({m.indices[i], m.indices[i + 1], m.indices[i + 2]});
    out.move(to_world);
    return out;
}

Polygons Instance::polygons(const Desc& d, const ExportFrame& f) {
    return mesh_polygons(f.meshes->at(d.mesh), d.transform);
}

}  // namespace rt
