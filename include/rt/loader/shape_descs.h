// The shapes as the scene file writes them: one desc per kind past triangles (what its
// Objects/<kKey> entry says, and how the loader reads it), and the list of those kinds
// in primitive-id order. The renderer's form of each kind is in rt/shapes/ (shapes.h
// lists them in the same order); see docs/extending.md.
//
// A kind's desc D provides, each used by the loader or the messages:
//   D::kKey, D::kKeys, D::read   Objects/<kKey> entries, the keys each may carry, and
//                                the reading of its own fields
//   D::kNoun, D::kNouns          counts in messages and --stats ("3 spheres")
//   D::kReadAsShape              false: the loader reads its entries itself (an instance
//                                refers to meshes by id)
//   D::apply_transform(desc, m)  its Transformations (rt/core/affine.h)
#pragma once
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string>
#include <vector>

#include "rt/core/affine.h"
#include "rt/core/kind_list.h"
#include "rt/core/math.h"

namespace rt {

// Whether a MotionBlur translation leaves the shape where it is.
inline bool is_still(Vec3 motion) { return motion.x == 0 && motion.y == 0 && motion.z == 0; }

// The fields the loader reads for every kind: Material (a 1-based id in the file) and
// _id, as written (its 1-based position among its kind when it has none).
struct ShapeDescBase {
    uint32_t material = 0;  // into SceneDesc::materials
    std::string id;
    const char* key = nullptr;  // the entry's Objects/<key> when not its kind's (--trace)
    // MotionBlur: the world-space translation it makes over the shutter, after its
    // Transformations (zero: still; docs/conventions.md, "Assignment 3").
    Vec3 motion;
};

// Objects/Sphere: its Center a vertex id, its Radius > 0. Under Transformations it keeps
// the matrix (a non-uniform scaling makes an exact ellipsoid: docs/transformations.md).
struct SphereDesc : ShapeDescBase {
    static constexpr const char* kKey = "Sphere";
    static constexpr const char* kKeys[] = {"_id", "Material", "Center", "Radius", "Transformations", "MotionBlur"};
    static constexpr const char* kNoun = "sphere";
    static constexpr const char* kNouns = "spheres";
    static constexpr bool kReadAsShape = true;

    Vec3 center;
    Real radius = 1;
    Affine transform;  // the sphere as written -> the world

    // `r` reads this entry's fields by key (the loader's checks and messages).
    template <class Reader>
    static void read(Reader& r, SphereDesc& d) {
        d.center = r.vertex("Center");
        d.radius = r.positive("Radius");
    }
    static void apply_transform(SphereDesc& d, const Affine& m) { d.transform = m * d.transform; }
};

// Objects/MeshInstance: the triangles of a mesh shown again under a transformation of
// their own (rt/shapes/instance.h). A mesh that any instance shows is itself drawn as an
// InstanceDesc with key "Mesh". What _baseMeshId and _resetTransform mean:
// docs/transformations.md.
struct InstanceDesc : ShapeDescBase {
    static constexpr const char* kKey = "MeshInstance";
    static constexpr const char* kKeys[] = {"_id",      "_baseMeshId",     "_resetTransform",
                                            "Material", "Transformations", "MotionBlur"};
    static constexpr const char* kNoun = "instance";
    static constexpr const char* kNouns = "instances";
    // The loader reads Objects/MeshInstance with the meshes it refers to.
    static constexpr bool kReadAsShape = false;

    uint32_t mesh = 0;  // into SceneDesc::meshes: the triangles it shows
    Affine transform;   // the mesh as written -> the world

    static void apply_transform(InstanceDesc& d, const Affine& m) { d.transform = m * d.transform; }
};

// Objects/Plane: its Point a vertex id, its Normal any non-zero vector. Transformations
// move its point and carry its normal by the inverse transpose: a moved plane is a plane.
struct PlaneDesc : ShapeDescBase {
    static constexpr const char* kKey = "Plane";
    static constexpr const char* kKeys[] = {"_id", "Material", "Point", "Normal", "Transformations"};
    static constexpr const char* kNoun = "plane";
    static constexpr const char* kNouns = "planes";
    static constexpr bool kReadAsShape = true;

    Vec3 point, normal;

    template <class Reader>
    static void read(Reader& r, PlaneDesc& d) {
        d.point = r.vertex("Point");
        d.normal = r.nonzero_vec3("Normal");
    }
    static void apply_transform(PlaneDesc& d, const Affine& m) {
        d.point = m.point(d.point);
        d.normal = normalize(m.inverse().transposed_vector(d.normal));
    }
};

// ---- The list ------------------------------------------------------------------------

enum class ShapeKind : uint32_t { Triangle, Sphere, Instance, Plane };

// The kinds after triangles, in ShapeKind order. Bounded kinds (rt/shapes/shapes.h) come
// before unbounded ones, and ids are the closest-hit tie-break: this order is part of
// the images.
using ShapeDescs = KindList<SphereDesc, InstanceDesc, PlaneDesc>;

// A desc's ShapeKind: 1 + its place in ShapeDescs.
template <class D>
inline constexpr ShapeKind kind_of_desc = ShapeKind(1 + IndexIn<D, ShapeDescs>::value);
static_assert(kind_of_desc<SphereDesc> == ShapeKind::Sphere && kind_of_desc<InstanceDesc> == ShapeKind::Instance &&
                  kind_of_desc<PlaneDesc> == ShapeKind::Plane,
              "ShapeKind lists the kinds of ShapeDescs, in its order");

inline constexpr size_t kShapeKindCount = 1 + ShapeDescs::size;  // triangles too
inline constexpr ShapeKind kShapeKinds[] = {ShapeKind::Triangle, ShapeKind::Sphere, ShapeKind::Instance,
                                            ShapeKind::Plane};
static_assert(std::size(kShapeKinds) == kShapeKindCount, "kShapeKinds lists every kind, in order");

// f(D{}) for each desc D of ShapeDescs, in order (a default-constructed D as a tag).
template <class F>
void for_each_shape_desc(F&& f) {
    for_each_kind(ShapeDescs{}, f);
}

template <class D>
using DescVectorOf = std::vector<D>;
using ShapeDescVectors = ShapeDescs::Tuple<DescVectorOf>;

// The kind's name as the scene file writes it (Objects/<key>); "Triangle" for kind 0.
inline const char* shape_key(ShapeKind kind) {
    if (kind == ShapeKind::Triangle) return "Triangle";
    return visit_kind<const char*>(ShapeDescs{}, size_t(kind) - 1, [](auto d) { return decltype(d)::kKey; });
}

}  // namespace rt
