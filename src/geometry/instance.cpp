// Mesh instances (rt/shapes/instance.h): a ray carried into the mesh's own space and
// traced through its BVH; the surface carried back. Here, beside the traversal, since an
// instance's ray test is a query of its mesh's scene.
#include "rt/shapes/instance.h"
#include "rt/geometry/traverse.h"

namespace rt {

Box Instance::bounds() const {
    const Box& b = mesh->accel.bvh.bounds;
    if (mesh->geometry.triangles.empty() || !(b.lo[0] <= b.hi[0])) return {};  // never entered
    const Affine to_world = to_object.inverse();
    Vec3 lo{Real(HUGE_VAL), Real(HUGE_VAL), Real(HUGE_VAL)}, hi = -lo;
    for (int c = 0; c < 8; ++c) {
        const Vec3 p =
            to_world.point({c & 1 ? b.hi[0] : b.lo[0], c & 2 ? b.hi[1] : b.lo[1], c & 4 ? b.hi[2] : b.lo[2]});
        lo = vmin(lo, p);
        hi = vmax(hi, p);
    }
    return moving ? swept(Box::around(lo, hi), motion) : Box::around(lo, hi);
}

bool Instance::trace(const Ray& ray, Real tmin, Real tmax, bool cull, bool shadow, Real& t, Real w[3],
                     uint32_t& part) const {
    // Not renormalised: a point at t along the object ray is the point at t along `ray`.
    // A moving instance is where its motion has taken it at the ray's time.
    const Vec3 org = moving ? ray.org - motion * ray.time : ray.org;
    const Ray object{to_object.point(org), to_object.vector(ray.dir)};
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

}  // namespace rt
