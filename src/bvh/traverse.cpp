// BVH traversal: near child first with a fixed stack; closest hit and any hit.
#include <algorithm>
#include <limits>

#include "rt/intersect.h"
#include "rt/scene.h"

namespace rt {
namespace {

constexpr int kStackSize = 128;  // the builder bounds depth to well below this
constexpr Real kTieSlack = 1 + 64 * std::numeric_limits<Real>::epsilon();

// Widening of the exit distance that makes the slab test conservative despite
// rounding in (bound - org) * inv_dir (pbrt-v3 section 3.9.2: 1 + 2 gamma(3)).
constexpr Real kSlabWiden = 1 + 2 * (3 * std::numeric_limits<Real>::epsilon() / 2) /
                                    (1 - 3 * std::numeric_limits<Real>::epsilon() / 2);

// Slab test against a float box; returns the entry distance or HUGE_VAL on a miss.
// Flat boxes (axis-aligned walls) make the slabs meet at one t, so without the
// widening a ray along a wall's edge could miss both walls.
inline Real box_entry(const BvhNode& n, const RayPre& p, Real tmin, Real tmax) {
    Real t0 = tmin, t1 = tmax;
    for (int a = 0; a < 3; ++a) {
        Real ta = (Real(n.lo[a]) - p.ray.org[a]) * p.inv_dir[a];
        Real tb = (Real(n.hi[a]) - p.ray.org[a]) * p.inv_dir[a];
        if (ta > tb) std::swap(ta, tb);
        tb *= kSlabWiden;
        // NaN (0 * inf, ray in the slab plane) leaves the interval unchanged.
        t0 = ta > t0 ? ta : t0;
        t1 = tb < t1 ? tb : t1;
    }
    return t0 <= t1 ? t0 : HUGE_VAL;
}

// Tests one BVH primitive; returns true with t (and weights) on a hit in (tmin, tmax).
template <bool kCull>
inline bool hit_prim(const Scene& s, const RayPre& p, uint32_t id, Real tmin, Real tmax, Real& t, Real w[3]) {
    const size_t ntri = s.triangles.size();
    if (id < ntri) {
        if (kCull && dot(p.ray.dir, s.face_normals[id]) > 0) return false;
        const Triangle& tri = s.triangles[id];
        return intersect_triangle(p, s.positions[tri.v[0]], s.positions[tri.v[1]], s.positions[tri.v[2]],
                                  tmin, tmax, t, w);
    }
    const Sphere& sp = s.spheres[id - ntri];
    return intersect_sphere(p.ray, sp.center, sp.radius, tmin, tmax, t);
}

template <bool kCull>
bool closest(const Scene& s, const Ray& ray, Real tmin, Real tmax, Hit& hit) {
    const RayPre p = prepare(ray);
    bool found = false;
    Real best_t = tmax;
    uint32_t best_id = ~0u;  // global id: BVH primitive id, then planes after them
    Real w[3] = {0, 0, 0};  // spheres leave them untouched
    auto consider = [&](uint32_t gid, Real t) {
        // Inclusive bound plus an id tie-break: equal t resolves to the lower id.
        if (t < best_t || (t == best_t && gid < best_id)) {
            best_t = t;
            best_id = gid;
            hit.w[0] = w[0]; hit.w[1] = w[1]; hit.w[2] = w[2];
            found = true;
        }
    };
    // Primitive tests accept t <= best_t, so ties reach consider() and are settled by id.
    auto limit = [&]() { return found ? std::nextafter(best_t, Real(HUGE_VAL)) : tmax; };
    // Boxes get more slack: the entry distance of a flat box around a primitive hit at
    // exactly best_t can round a few ulps above it (kTieSlack covers the error of both
    // the slab distances and the triangle's t).
    auto box_limit = [&]() { return found ? best_t * kTieSlack : tmax; };

    if (!s.bvh.nodes.empty()) {
        uint32_t stack[kStackSize];
        int sp = 0;
        uint32_t node = 0;
        if (box_entry(s.bvh.nodes[0], p, tmin, tmax) == HUGE_VAL) goto planes;
        for (;;) {
            const BvhNode& n = s.bvh.nodes[node];
            if (n.count > 0) {
                for (uint32_t i = n.first, e = n.first + n.count; i < e; ++i) {
                    const uint32_t id = s.bvh.prims[i];
                    Real t;
                    if (hit_prim<kCull>(s, p, id, tmin, limit(), t, w)) consider(id, t);
                }
            } else {
                const Real lim = box_limit();
                const Real tl = box_entry(s.bvh.nodes[n.first], p, tmin, lim);
                const Real tr = box_entry(s.bvh.nodes[n.first + 1], p, tmin, lim);
                if (tl != HUGE_VAL && tr != HUGE_VAL) {
                    const bool left_first = tl <= tr;
                    stack[sp++] = left_first ? n.first + 1 : n.first;
                    node = left_first ? n.first : n.first + 1;
                    continue;
                }
                if (tl != HUGE_VAL) { node = n.first; continue; }
                if (tr != HUGE_VAL) { node = n.first + 1; continue; }
            }
            // Pop, skipping nodes now farther than the best hit.
            if (sp == 0) break;
            node = stack[--sp];
        }
    }
planes:
    const uint32_t base = static_cast<uint32_t>(s.triangles.size() + s.spheres.size());
    for (size_t i = 0; i < s.planes.size(); ++i) {
        Real t;
        if (intersect_plane(ray, s.planes[i].point, s.planes[i].normal, tmin, limit(), t))
            consider(base + static_cast<uint32_t>(i), t);
    }
    if (!found) return false;
    hit.t = best_t;
    const size_t ntri = s.triangles.size();
    if (best_id < ntri) {
        hit.kind = HitKind::Triangle;
        hit.index = best_id;
    } else if (best_id < base) {
        hit.kind = HitKind::Sphere;
        hit.index = static_cast<uint32_t>(best_id - ntri);
    } else {
        hit.kind = HitKind::Plane;
        hit.index = best_id - base;
    }
    return true;
}

}  // namespace

bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit) {
    return cull ? closest<true>(scene, ray, tmin, tmax, hit) : closest<false>(scene, ray, tmin, tmax, hit);
}

bool any_hit(const Scene& s, const Ray& ray, Real tmin, Real tmax) {
    for (const Plane& pl : s.planes) {
        Real t;
        if (intersect_plane(ray, pl.point, pl.normal, tmin, tmax, t)) return true;
    }
    if (s.bvh.nodes.empty()) return false;
    const RayPre p = prepare(ray);
    uint32_t stack[kStackSize];
    int sp = 0;
    uint32_t node = 0;
    if (box_entry(s.bvh.nodes[0], p, tmin, tmax) == HUGE_VAL) return false;
    Real w[3] = {0, 0, 0};  // spheres leave them untouched
    for (;;) {
        const BvhNode& n = s.bvh.nodes[node];
        if (n.count > 0) {
            for (uint32_t i = n.first, e = n.first + n.count; i < e; ++i) {
                Real t;
                if (hit_prim<false>(s, p, s.bvh.prims[i], tmin, tmax, t, w)) return true;
            }
        } else {
            const bool l = box_entry(s.bvh.nodes[n.first], p, tmin, tmax) != HUGE_VAL;
            const bool r = box_entry(s.bvh.nodes[n.first + 1], p, tmin, tmax) != HUGE_VAL;
            if (l && r) {
                stack[sp++] = n.first + 1;
                node = n.first;
                continue;
            }
            if (l) { node = n.first; continue; }
            if (r) { node = n.first + 1; continue; }
        }
        if (sp == 0) return false;
        node = stack[--sp];
    }
}

}  // namespace rt
