// Render data, built once from a SceneDesc (build_scene); constructors never see
// JSON. A Scene has four parts:
//   setup     what the scene says besides its shapes: settings, cameras, lights, materials
//   geometry  the shapes: one vertex array shared by the triangles, spheres, planes
//   accel     the acceleration structure over the bounded shapes (BVH, leaf-order vertices)
//   report    what the build measured and skipped
// Triangles and spheres sit under one BVH; infinite planes are tested by every ray.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/camera/camera.h"
#include "rt/geometry/intersect.h"
#include "rt/loader/scene_desc.h"
#include "rt/core/uninit_vector.h"

namespace rt {

// The materials and lights are rendered as loaded. (A Plain material's
// MirrorReflectance is never read: reference-conventions.md, "Shading".)
using Material = MaterialDesc;
using PointLight = PointLightDesc;

// What the scene file says, apart from its shapes.
struct SceneSetup {
    Vec3 background, ambient_light;
    Real shadow_ray_epsilon = Real(1e-3);
    int max_recursion_depth = 6;
    std::vector<Camera> cameras;
    std::vector<PointLight> lights;
    std::vector<Material> materials;
};

// ---- The shapes -------------------------------------------------------------------
// Every shape has a kind, an array in Geometry and a primitive id: ids number the
// kinds in ShapeKind order, triangles first, then spheres, then planes. The bounded
// kinds come first: their ids are the BVH's; the planes after them are infinite,
// and every ray tests them on its own (src/bvh/traverse.cpp). Ids are the
// closest-hit tie-break, so their order is part of the images.
//
// To add a shape (-Wswitch-enum points at every switch to extend):
//  1. include/rt/geometry/scene.h (here): its struct (with a `material`); its enumerator in
//     ShapeKind and kShapeKinds (a bounded shape goes before Plane); its array in
//     Geometry; its case in Geometry's shape_of (the one decoding of an id), count,
//     bounds, intersect and surface.
//  2. include/rt/geometry/intersect.h: its ray test, beside intersect_sphere.
//  3. src/geometry/build_scene.cpp: its array filled from the SceneDesc (build()).
// The loader reads it into the SceneDesc (scene_desc.h, src/loader/scene_from_json.cpp).
// A new unbounded shape also needs the planes' loops in src/bvh/traverse.cpp.
enum class ShapeKind : uint32_t { Triangle, Sphere, Plane };
inline constexpr ShapeKind kShapeKinds[] = {ShapeKind::Triangle, ShapeKind::Sphere, ShapeKind::Plane};
static_assert(std::size(kShapeKinds) == size_t(ShapeKind::Plane) + 1, "kShapeKinds lists every kind, in order");

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

struct Sphere {
    Vec3 center;
    Real radius;
    uint32_t material;
};

struct Plane {
    Vec3 point, normal;  // normal has unit length
    uint32_t material;
};

// A primitive: its kind and its index in that kind's array.
struct ShapeRef {
    ShapeKind kind;
    uint32_t index;
};

// A ray's closest hit.
struct Hit {
    Real t = HUGE_VAL;
    ShapeKind kind = ShapeKind::Triangle;
    uint32_t index = 0;     // into Geometry::triangles, spheres or planes
    Real w[3] = {0, 0, 0};  // barycentric weights (triangles)
    // A triangle found in the leaf-order vertices (LeafVertices): its coordinate
    // `axis` of vertex k is corners[(3 * k + axis) * stride], equal to its
    // position's. Shading reads them there, already in cache. Null otherwise.
    const float* corners = nullptr;
    uint32_t stride = 0;
};

// What shading needs to know about a hit point.
struct Surface {
    Vec3 ng;            // unit geometric normal, the outward (counter-clockwise) side
    Vec3 ns;            // unit shading normal, on ng's side
    uint32_t material;  // into SceneSetup::materials
};

struct Geometry {
    std::vector<Vec3> positions;
    std::vector<Vec3> vertex_normals;  // area-weighted, per mesh; unit length or zero
    UninitVector<Triangle> triangles;
    std::vector<TriangleRun> runs;  // cover every triangle, ascending, runs[0].first == 0
    std::vector<Sphere> spheres;
    std::vector<Plane> planes;

    // Primitives of one kind.
    uint32_t count(ShapeKind kind) const {
        switch (kind) {
            case ShapeKind::Triangle:
                return static_cast<uint32_t>(triangles.size());
            case ShapeKind::Sphere:
                return static_cast<uint32_t>(spheres.size());
            case ShapeKind::Plane:
                return static_cast<uint32_t>(planes.size());
        }
        return 0;
    }
    // The first primitive id of `kind`.
    uint32_t first_id(ShapeKind kind) const {
        uint32_t id = 0;
        for (ShapeKind k : kShapeKinds) {
            if (k == kind) break;
            id += count(k);
        }
        return id;
    }
    // Ids [0, bounded_count()) are the BVH's primitives.
    uint32_t bounded_count() const { return first_id(ShapeKind::Plane); }

    // The one decoding of a primitive id into its kind and index. kBvh: the id is a
    // BVH primitive's (bounded), which spares the traversal a comparison.
    template <bool kBvh = false>
    ShapeRef shape_of(uint32_t id) const {
        const uint32_t ntri = static_cast<uint32_t>(triangles.size());
        if (id < ntri) return {ShapeKind::Triangle, id};
        id -= ntri;
        if (kBvh || id < spheres.size()) return {ShapeKind::Sphere, id};
        return {ShapeKind::Plane, id - static_cast<uint32_t>(spheres.size())};
    }

    // The run of triangle i (i < triangles.size()).
    const TriangleRun& run_of(uint32_t i) const { return *last_starting_at(runs, i, &TriangleRun::first); }

    // Unit geometric normal of the triangle a, b, c, counter-clockwise front (spec 3, "Triangle").
    static Vec3 face_normal(Vec3 a, Vec3 b, Vec3 c) { return normalize(cross(b - a, c - a)); }
    Vec3 face_normal(uint32_t i) const {
        const Triangle& t = triangles[i];
        return face_normal(positions[t.v[0]], positions[t.v[1]], positions[t.v[2]]);
    }

    // Bounds of a primitive, rounded outwards to float (infinite for a plane).
    Box bounds(ShapeRef s) const {
        switch (s.kind) {
            case ShapeKind::Triangle: {
                const Triangle& t = triangles[s.index];
                const Vec3 a = positions[t.v[0]], b = positions[t.v[1]], c = positions[t.v[2]];
                return Box::around(vmin(a, vmin(b, c)), vmax(a, vmax(b, c)));
            }
            case ShapeKind::Sphere: {
                const Sphere& sp = spheres[s.index];
                const Vec3 r{sp.radius, sp.radius, sp.radius};
                return Box::around(sp.center - r, sp.center + r);
            }
            case ShapeKind::Plane:
                return {{-HUGE_VALF, -HUGE_VALF, -HUGE_VALF}, {HUGE_VALF, HUGE_VALF, HUGE_VALF}};
        }
        return {};
    }

    // Ray test of one primitive: true with the distance t in (tmin, tmax) on a hit,
    // and for triangles the barycentric weights w (others leave w alone). kCull,
    // kShadow: see intersect_triangle.
    template <bool kCull, bool kShadow = false>
    bool intersect(const RayPre& p, ShapeRef s, Real tmin, Real tmax, Real& t, Real w[3]) const {
        switch (s.kind) {
            case ShapeKind::Triangle: {
                const Triangle& tri = triangles[s.index];
                return intersect_triangle<kCull, kShadow>(p, positions[tri.v[0]], positions[tri.v[1]],
                                                          positions[tri.v[2]], tmin, tmax, t, w);
            }
            case ShapeKind::Sphere: {
                const Sphere& sp = spheres[s.index];
                return intersect_sphere(p.ray, sp.center, sp.radius, tmin, tmax, t);
            }
            case ShapeKind::Plane: {
                const Plane& pl = planes[s.index];
                return intersect_plane(p.ray, pl.point, pl.normal, tmin, tmax, t);
            }
        }
        return false;
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
        switch (h.kind) {
            case ShapeKind::Triangle: {
                const Triangle& tri = triangles[h.index];
                const TriangleRun& run = run_of(h.index);
                const Vec3 ng =
                    h.corners ? face_normal(corner(h, 0), corner(h, 1), corner(h, 2)) : face_normal(h.index);
                Vec3 ns = ng;
                if (run.smooth) {
                    const Vec3 n = vertex_normals[tri.v[0]] * h.w[0] + vertex_normals[tri.v[1]] * h.w[1] +
                                   vertex_normals[tri.v[2]] * h.w[2];
                    const Real len = length(n);
                    if (len > 0) ns = n / len;
                }
                return {ng, ns, run.material};
            }
            case ShapeKind::Sphere: {
                const Sphere& sp = spheres[h.index];
                const Vec3 n = (p - sp.center) / sp.radius;
                return {n, n, sp.material};
            }
            case ShapeKind::Plane: {
                const Plane& pl = planes[h.index];
                return {pl.normal, pl.normal, pl.material};
            }
        }
        return {};
    }
};

// Each BVH leaf triangle's vertices a, b, c as 9 coordinates, in leaf order
// (entry i is triangle bvh.prims[i]), so that a leaf's triangles are one block of
// memory instead of a chain of loads (prims, triangles, positions). Within a leaf
// of n triangles the coordinates are grouped (at(), below), so that four
// triangles' x of vertex a, say, are one plain load, not a gather. build_scene
// makes them when leaves test several triangles at once (kLeafBlock), in one of two
// precisions, and only where they change no number the tests see (with Real =
// float: always in float, serving every leaf of triangles):
//  - doubles, for scenes of at most BvhBuildOptions::double_copy_max primitives
//    (the official scenes, whose JSON coordinates are seldom floats): every leaf
//    of triangles;
//  - floats, for larger ones: the leaves of triangles whose every coordinate is a
//    float exactly (PLY meshes are), at 36 bytes a triangle, in the storage the
//    BVH build's boxes were in (ReusableStorage: its pages are already touched,
//    and on this VM a fresh page costs more than the copy into it).
// Every other leaf (a sphere, a coordinate that is not a float) is marked
// BvhNode::kIndexedLeaf and reads its primitives through their ids.
class LeafVertices {
public:
    // Coordinates for n triangles: loads of kLeafBlock lanes from the last leaf's
    // last triangle read up to kLeafBlock - 1 past its end.
    static constexpr size_t coordinates_for(size_t n) { return 9 * n + kLeafBlock - 1; }
    // Index of coordinate `axis` of vertex `k` of the triangle at leaf position
    // first + j, in the leaf at prims[first, first + n).
    static size_t at(uint32_t first, uint32_t n, uint32_t j, int k, int axis) {
        return 9 * size_t(first) + size_t(3 * k + axis) * n + j;
    }

    LeafVertices() = default;
    // `coordinates` (coordinates_for(the BVH's primitive count) of them, float or
    // double) is the array `storage` holds.
    template <class T>
    LeafVertices(ReusableStorage&& storage, const T* coordinates) : storage_(std::move(storage)) {
        static_assert(std::is_same_v<T, float> || std::is_same_v<T, double>);
        if constexpr (std::is_same_v<T, float>)
            floats_ = coordinates;
        else
            doubles_ = coordinates;
    }
    // The copy in its precision; null when it is in the other one, or there is none.
    const float* floats() const { return floats_; }
    const double* doubles() const { return doubles_; }

private:
    ReusableStorage storage_;
    const float* floats_ = nullptr;
    const double* doubles_ = nullptr;
};

// Over primitive ids [0, geometry.bounded_count()).
struct Acceleration {
    Bvh bvh;
    LeafVertices leaf_vertices;
};

// What building the scene measured and skipped, for messages and --stats.
struct BuildReport {
    double build_seconds = 0;         // BVH build (and leaf-order copy) time
    size_t degenerate_triangles = 0;  // skipped (spec 2.10)
};

// What the scene file calls each primitive (--trace names hits by it): one entry per
// Objects/Mesh or Objects/Triangle in triangle order, and the spheres' and planes' _ids.
struct ShapeNames {
    struct Mesh {
        uint32_t first_triangle = 0;    // its first triangle in Geometry::triangles
        bool triangle_object = false;   // an Objects/Triangle (one face)
        std::string id;                 // MeshDesc::id
        std::vector<uint32_t> skipped;  // its degenerate faces, not in Geometry (spec 2.10), ascending
    };
    std::vector<Mesh> meshes;
    std::vector<std::string> spheres, planes;

    // "Mesh 3, face 1207" (the face's 0-based index in the mesh's PLY or _data, skipped
    // faces counted), "Triangle 4", "Sphere 2", "Plane 1"; "triangle #i" (etc.) for a
    // primitive without a name (scenes built in code).
    std::string name(ShapeRef s) const;
};

struct Scene {
    SceneSetup setup;
    Geometry geometry;
    Acceleration accel;
    BuildReport report;
    ShapeNames names;
};

// Closest hit in (tmin, tmax). With `cull`, triangles whose geometric normal
// points along the ray are ignored (spec 2.9). Ties in t go to the lower
// primitive id, so the answer does not depend on the BVH layout.
bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit);

// closest_hit for n rays at once (1 <= n <= kPacket), found[i] its result for
// rays[i], hits[i] its hit: the same answers, for rays that are near each other
// (camera rays of neighbouring pixels) in less time, each node loaded once for all.
constexpr int kPacket = 16;
void closest_hits(const Scene& scene, const Ray* rays, int n, Real tmin, Real tmax, bool cull, Hit* hits, bool* found);

// True when anything lies in (tmin, tmax); never culls (spec 2.9: shadow rays).
// `occluder`, when given, is a hint: a BVH primitive id (or kNoOccluder) tested
// before the traversal, and on a BVH hit it receives the id that was found.
// Neighbouring shadow rays are mostly blocked by the same primitive; the answer
// never depends on the hint.
constexpr uint32_t kNoOccluder = ~0u;
bool any_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder = nullptr);

// any_hit for n queries at once (0 <= n <= kPacket), hit[i] the answer for
// queries[i]: the same answers, for rays that are near each other (the shadow rays
// of a camera packet's points towards one light) in less time, each node loaded
// once for all.
struct ShadowQuery {
    Ray ray;
    Real tmin, tmax;
    uint32_t* occluder;  // any_hit's hint, or null
};
void any_hits(const Scene& scene, const ShadowQuery* queries, int n, bool* hit);

// Float bounds, rounded outwards, of every bounded primitive (the BVH's ids).
UninitVector<BuildBox> primitive_boxes(const Geometry& g);

// Builds render data: gathers the meshes' vertices into one array, computes
// area-weighted vertex normals of smooth meshes, skips degenerate triangles
// (spec 2.10) and builds the BVH (`bvh`: build quality knobs, for measurements).
// Takes the vertices of the first mesh and releases each mesh of `desc` as soon
// as it is copied (lower peak memory).
Scene build_scene(SceneDesc&& desc, const BvhBuildOptions& bvh = {});
// The same on a copy of `desc`.
Scene build_scene(const SceneDesc& desc, const BvhBuildOptions& bvh = {});

}  // namespace rt
