// The shapes of a built scene: one vertex array shared by the triangles, and one array
// per other kind of shape (rt/shapes/shapes.h), with the one decoding of primitive ids
// and the per-kind dispatch of bounds, ray tests and surfaces.
//
// Every primitive has an id: ids number the kinds in ShapeKind order, triangles first.
// The bounded kinds come first: their ids are the BVH's; the unbounded ones after them
// are tested by every ray on its own (src/geometry/closest.cpp, any_hit.cpp). Ids are the closest-hit
// tie-break, so their order is part of the images.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"
#include "rt/core/uninit_vector.h"
#include "rt/shapes/shapes.h"

namespace rt {

// A triangle is its three vertices; its material and shading are those of its run
// (TriangleRun), so that a triangle costs 12 bytes.
struct Triangle {
    uint32_t v[3];  // into Geometry::positions (and vertex_normals when smooth)
};
static_assert(sizeof(Triangle) == 12, "Triangle must stay 12 bytes");

// Consecutive triangles with one material and shading: a mesh, or a Triangle object,
// merged with the run before when both are the same.
struct TriangleRun {
    uint32_t first;     // its first triangle in Geometry::triangles
    uint32_t material;  // into SceneSetup::materials
    bool smooth;        // interpolate vertex normals (else flat)
};

// The last of `items` (ascending by `first`) whose `first` is at most `index`, or
// null when there is none. Items left empty share their `first` with the next one,
// which is the one found.
template <class T>
const T* last_starting_at(const std::vector<T>& items, uint32_t index, uint32_t T::*first) {
    auto it = std::upper_bound(items.begin(), items.end(), index,
                               [first](uint32_t i, const T& item) { return i < item.*first; });
    return it == items.begin() ? nullptr : &*--it;
}

// A primitive: its kind and its index in that kind's array.
struct ShapeRef {
    ShapeKind kind;
    uint32_t index;
};

// A ray's closest hit.
struct Hit {
    Real t = HUGE_VAL;
    ShapeKind kind = ShapeKind::Triangle;
    uint32_t index = 0;     // into Geometry::triangles, or its kind's array
    Real w[3] = {0, 0, 0};  // barycentric weights (triangles, and an instance's triangle)
    uint32_t part = 0;      // an instance's triangle (in its mesh's own Geometry)
    // A triangle found in the leaf-order vertices (LeafVertices): its coordinate
    // `axis` of vertex k is corners[(3 * k + axis) * stride], equal to its
    // position's. Shading reads them there, already in cache. Null otherwise.
    const float* corners = nullptr;
    uint32_t stride = 0;
};

struct Geometry {
    bool moves = false;  // some shape has a MotionBlur: rays carry a time (rt/core/math.h, Ray)
    std::vector<Vec3> positions;
    std::vector<Vec3> vertex_normals;  // area-weighted, per mesh; unit length or zero
    UninitVector<Triangle> triangles;
    std::vector<TriangleRun> runs;  // cover every triangle, ascending, runs[0].first == 0
    ShapeVectors shapes;            // the other kinds: all<Sphere>(), ...
    // The meshes instances show, each with its own BVH (rt/shapes/instance.h), which
    // the instances point into.
    std::vector<std::shared_ptr<const Scene>> mesh_scenes;

    // The primitives of kind S (rt/shapes/shapes.h).
    template <class S>
    std::vector<S>& all() {
        return std::get<IndexIn<S, Shapes>::value>(shapes);
    }
    template <class S>
    const std::vector<S>& all() const {
        return std::get<IndexIn<S, Shapes>::value>(shapes);
    }

    // Primitives of one kind.
    uint32_t count(ShapeKind kind) const {
        if (kind == ShapeKind::Triangle) return static_cast<uint32_t>(triangles.size());
        return visit_shape<uint32_t>(kind, [this](auto s) { return uint32_t(all<decltype(s)>().size()); });
    }
    // The first primitive id of `kind`.
    // Straight-line code once inlined (the traversal asks it for every ray).
    uint32_t first_id(ShapeKind kind) const {
        if (kind == ShapeKind::Triangle) return 0;
        uint32_t id = static_cast<uint32_t>(triangles.size());
        for_each_shape([&](auto s) {
            if (size_t(kind_of<decltype(s)>) < size_t(kind)) id += static_cast<uint32_t>(all<decltype(s)>().size());
        });
        return id;
    }
    // Ids [0, bounded_count()) are the BVH's primitives.
    uint32_t bounded_count() const {
        uint32_t n = static_cast<uint32_t>(triangles.size());
        for_each_shape([&](auto s) {
            if constexpr (decltype(s)::kBounded) n += uint32_t(all<decltype(s)>().size());
        });
        return n;
    }

    // The one decoding of a primitive id into its kind and index. kBvh: the id is a
    // BVH primitive's (bounded), which spares the traversal the last comparison.
    template <bool kBvh = false>
    ShapeRef shape_of(uint32_t id) const {
        const uint32_t ntri = static_cast<uint32_t>(triangles.size());
        if (id < ntri) return {ShapeKind::Triangle, id};
        return shape_in<kBvh>(Shapes{}, id - ntri);
    }

    // The run of triangle i (i < triangles.size()).
    const TriangleRun& run_of(uint32_t i) const { return *last_starting_at(runs, i, &TriangleRun::first); }

    // Unit geometric normal of the triangle a, b, c, counter-clockwise front (spec 3, "Triangle").
    static Vec3 face_normal(Vec3 a, Vec3 b, Vec3 c) { return normalize(cross(b - a, c - a)); }
    Vec3 face_normal(uint32_t i) const {
        const Triangle& t = triangles[i];
        return face_normal(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]]);
    }

    // Bounds of a primitive, rounded outwards to float (infinite for an unbounded kind).
    Box bounds(ShapeRef s) const {
        if (s.kind == ShapeKind::Triangle) {
            const Triangle& t = triangles[s.index];
            const Vec3 a = positions[t.v[0]], b = positions[t.v[1]], c = positions[t.v[2]];
            return Box::around(vmin(a, vmin(b, c)), vmax(a, vmax(b, c)));
        }
        return visit_shape<Box>(s.kind, [&](auto k) { return all<decltype(k)>()[s.index].bounds(); });
    }

    // Ray test of one primitive: true with the distance t in (tmin, tmax) on a hit,
    // and for triangles the barycentric weights w (others leave w alone; an instance
    // sets them and `part`, the triangle of its mesh). kCull, kShadow: see
    // intersect_triangle.
    template <bool kCull, bool kShadow = false>
    [[gnu::always_inline]] bool intersect(const RayPre& p, ShapeRef s, Real tmin, Real tmax, Real& t, Real w[3],
                                          uint32_t& part) const {
        if (s.kind == ShapeKind::Triangle) {
            const Triangle& tri = triangles[s.index];
            return intersect_triangle<kCull, kShadow>(p, positions[tri.v[0]], positions[tri.v[1]], positions[tri.v[2]],
                                                      tmin, tmax, t, w);
        }
        return visit_shape<bool>(s.kind, [&](auto k) {
            return all<decltype(k)>()[s.index].template intersect<kCull, kShadow>(p.ray, tmin, tmax, t, w, part);
        });
    }

    // Vertex k of the triangle of `h` from its leaf-order vertices (h.corners).
    static Vec3 corner(const Hit& h, int k) {
        const float* c = h.corners + size_t(3 * k) * h.stride;
        return {c[0], c[h.stride], c[2 * size_t(h.stride)]};
    }

    // Starts loading what surface(h, p) reads from memory (a smooth triangle's vertex
    // normals), for a caller that shades several hits: their loads overlap.
    void prefetch_surface(const Hit& h) const {
        if (h.kind != ShapeKind::Triangle || !run_of(h.index).smooth) return;
        const Triangle& tri = triangles[h.index];
        for (int k = 0; k < 3; ++k) __builtin_prefetch(&vertex_normals[tri.v[k]]);
    }

    // The surface at hit point p of `h`.
    Surface surface(const Hit& h, Vec3 p) const {
        if (h.kind == ShapeKind::Triangle) {
            const Triangle& tri = triangles[h.index];
            const TriangleRun& run = run_of(h.index);
            const Vec3 ng = h.corners ? face_normal(corner(h, 0), corner(h, 1), corner(h, 2)) : face_normal(h.index);
            Vec3 ns = ng;
            if (run.smooth) {
                const Vec3 n = vertex_normals[tri.v[0]] * h.w[0] + vertex_normals[tri.v[1]] * h.w[1] +
                               vertex_normals[tri.v[2]] * h.w[2];
                const Real len = length(n);
                if (len > 0) ns = n / len;
            }
            return {ng, ns, run.material};
        }
        return visit_shape<Surface>(h.kind,
                                    [&](auto k) { return all<decltype(k)>()[h.index].surface(p, h.w, h.part); });
    }

private:
    // shape_of past the triangles: `id` counts from the first primitive of S.
    template <bool kBvh, class S, class... Rest>
    ShapeRef shape_in(ShapeList<S, Rest...>, uint32_t id) const {
        if constexpr (sizeof...(Rest) == 0) {
            return {kind_of<S>, id};
        } else {
            // The last bounded kind is the only one a BVH id can reach past here.
            constexpr bool kLastBounded = S::kBounded && !std::tuple_element_t<0, std::tuple<Rest...>>::kBounded;
            if ((kBvh && kLastBounded) || id < all<S>().size()) return {kind_of<S>, id};
            return shape_in<kBvh>(ShapeList<Rest...>{}, id - static_cast<uint32_t>(all<S>().size()));
        }
    }
};

}  // namespace rt
