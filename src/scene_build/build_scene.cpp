// SceneDesc -> Scene: flat arrays, normals, BVH.
#include <algorithm>
#include <chrono>
#include <memory>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

#include "rt/core/threads.h"
#include "rt/scene_build/build_scene.h"

namespace rt {
namespace {

// Twice the area vector of triangle (a, b, c) and whether it is degenerate
// (spec 2.10: two vertices coincide or all three are collinear).
inline bool degenerate(const std::vector<Vec3>& p, uint32_t a, uint32_t b, uint32_t c, Vec3& n) {
    n = cross(p[b] - p[a], p[c] - p[a]);
    const Real len = length(n);
    return !(len > 0) || !std::isfinite(len);
}

// Meshes with at least this many faces are converted by two threads.
constexpr size_t kParallelFaces = size_t(1) << 16;

// Starts a run of triangles at `first` (Geometry::runs): a new one unless the last
// run has the same material and shading, or is empty (it then gives way).
void add_run(Geometry& g, uint32_t first, uint32_t material, bool smooth) {
    if (!g.runs.empty() && g.runs.back().first == first) g.runs.pop_back();
    if (!g.runs.empty() && g.runs.back().material == material && g.runs.back().smooth == smooth) return;
    g.runs.push_back({first, material, smooth});
}

// Appends one mesh: its vertices (taken from `m` when it is the first, else
// copied, and `m`'s released before anything else is written), its
// non-degenerate triangles with their BVH boxes (boxes[id] for triangle id;
// room for every triangle of the scene), and, when smooth, vertex normals
// averaged over this mesh only, weighted by area (spec section 3, "Mesh";
// pooling across meshes does not match the references). Flat scenes get no
// vertex normals at all. The degenerate faces' indices in `m` go to `skipped`.
void add_mesh(Geometry& s, BuildReport& report, MeshDesc& m, BuildBox* boxes, std::vector<uint32_t>& skipped) {
    const uint32_t base = static_cast<uint32_t>(s.positions.size());
    if (base == 0 && s.positions.capacity() <= m.positions.size())
        s.positions = std::move(m.positions);
    else {
        s.positions.insert(s.positions.end(), m.positions.begin(), m.positions.end());
        std::vector<Vec3>().swap(m.positions);
    }
    const bool smooth = m.shading == ShadingMode::Smooth;
    const std::vector<uint32_t>& idx = m.indices;
    const std::vector<Vec3>& pos = s.positions;
    const size_t faces = idx.size() / 3, first = s.triangles.size();

    // Each face's normal is added to its vertices in face order, so the sums
    // (and the images) do not depend on the threads.
    auto accumulate_normals = [&s, &idx, &pos, base] {
        for (size_t f = 0; f + 2 < idx.size(); f += 3) {
            const uint32_t a = base + idx[f], b = base + idx[f + 1], c = base + idx[f + 2];
            Vec3 n;
            if (degenerate(pos, a, b, c, n)) continue;
            // |n| is twice the area, so adding n weights each face by its area.
            s.vertex_normals[a] += n;
            s.vertex_normals[b] += n;
            s.vertex_normals[c] += n;
        }
        for (size_t i = base; i < pos.size(); ++i) {
            const Real len = length(s.vertex_normals[i]);
            if (len > 0) s.vertex_normals[i] = s.vertex_normals[i] / len;
        }
    };
    // Triangles and boxes of faces [f0, f1) go to slots first + f (pages
    // first touched by the thread that writes them); degenerate faces are
    // marked with a first vertex no mesh has and squeezed out below.
    constexpr uint32_t kDropped = ~0u;
    add_run(s, static_cast<uint32_t>(first), m.material, smooth);
    s.triangles.resize(first + faces);
    // Every allocation happens here, not on the helper thread, where running out
    // of memory would end the process instead of reaching main's error message.
    if (smooth) s.vertex_normals.resize(pos.size(), Vec3{});
    // Returns the number of degenerate faces among them.
    auto convert = [&](size_t f0, size_t f1) {
        size_t dropped = 0;
        for (size_t f = f0; f < f1; ++f) {
            const uint32_t a = base + idx[3 * f], b = base + idx[3 * f + 1], c = base + idx[3 * f + 2];
            Triangle& t = s.triangles[first + f];
            t.v[0] = a;
            t.v[1] = b;
            t.v[2] = c;
            Vec3 n;
            if (degenerate(pos, a, b, c, n)) {
                t.v[0] = kDropped;
                ++dropped;
                continue;
            }
            boxes[first + f] = BuildBox::of(s.bounds({ShapeKind::Triangle, static_cast<uint32_t>(first + f)}));
        }
        return dropped;
    };
    size_t dropped = 0;
    if (faces >= kParallelFaces && std::thread::hardware_concurrency() > 1) {
        // One thread: the normals (about an eighth of the work) when smooth, then
        // the first part of the faces; this thread: the rest. Both compute the
        // faces' cross products (degenerate()): sharing them would make one wait.
        const size_t split = smooth ? faces * 2 / 5 : faces / 2;
        size_t helper_dropped = 0;
        in_parallel(
            [&] {
                if (smooth) accumulate_normals();
                helper_dropped = convert(0, split);
            },
            [&] { dropped = convert(split, faces); });
        dropped += helper_dropped;
    } else {
        if (smooth) accumulate_normals();
        dropped = convert(0, faces);
    }
    if (dropped == 0) return;
    // Degenerate faces out, the order of the others kept (their ids are the
    // tie-break between equally near hits).
    size_t out = first;
    for (size_t i = first; i < first + faces; ++i) {
        if (s.triangles[i].v[0] == kDropped) {
            ++report.degenerate_triangles;
            skipped.push_back(static_cast<uint32_t>(i - first));
            continue;
        }
        if (out != i) {
            s.triangles[out] = s.triangles[i];
            boxes[out] = boxes[i];
        }
        ++out;
    }
    s.triangles.resize(out);
}

// boxes[id] for the bounded primitives from id `first` on.
void add_boxes(const Geometry& g, uint32_t first, BuildBox* boxes) {
    for (uint32_t id = first; id < g.bounded_count(); ++id) {
        const ShapeRef shape = g.shape_of<true>(id);
        boxes[id] = BuildBox::of(g.bounds(shape), shape.kind != ShapeKind::Triangle);
    }
}

}  // namespace

UninitVector<BuildBox> primitive_boxes(const Geometry& g) {
    UninitVector<BuildBox> boxes(g.bounded_count());
    add_boxes(g, 0, boxes.data());
    return boxes;
}

namespace {

// x is a float exactly.
inline bool is_float(Real x) { return Real(float(x)) == x; }

// Copies the vertices of the leaf at prims[first, first + n) into out (layout:
// LeafVertices::at); returns whether the copy can stand in for them: all are
// triangles, and their coordinates are all T exactly.
template <class T>
bool copy_leaf(const Geometry& g, const std::vector<uint32_t>& prims, uint32_t first, uint32_t n, T* out) {
    bool exact = true;
    for (uint32_t j = 0; j < n; ++j) {
        const ShapeRef shape = g.shape_of<true>(prims[first + j]);
        if (shape.kind != ShapeKind::Triangle) {
            for (int k = 0; k < 3; ++k)
                for (int a = 0; a < 3; ++a) out[LeafVertices::at(first, n, j, k, a)] = 0;
            exact = false;
            continue;
        }
        const Triangle& t = g.triangles[shape.index];
        for (int k = 0; k < 3; ++k) {
            const Vec3& v = g.positions[t.v[k]];
            out[LeafVertices::at(first, n, j, k, 0)] = T(v.x);
            out[LeafVertices::at(first, n, j, k, 1)] = T(v.y);
            out[LeafVertices::at(first, n, j, k, 2)] = T(v.z);
            if constexpr (std::is_same_v<T, float>) exact = exact && is_float(v.x) && is_float(v.y) && is_float(v.z);
        }
    }
    return exact;
}

// Copies every leaf into `out` (LeafVertices::coordinates_for(prims) of T), two
// threads half the nodes each for large trees, marking the leaves the copy cannot
// stand in for BvhNode::kIndexedLeaf; returns the number of leaves it serves.
template <class T>
size_t copy_leaves(const Geometry& g, Bvh& bvh, T* out) {
    const size_t end = LeafVertices::coordinates_for(bvh.prims.size());
    std::fill(out + 9 * bvh.prims.size(), out + end, T(0));
    auto copy = [&g, &bvh, out](size_t begin, size_t stop) {
        size_t served = 0;
        for (size_t k = begin; k < stop; ++k) {
            BvhNode& node = bvh.nodes[k];
            for (int i = 0; i < BvhNode::kWidth; ++i) {
                if (!node.is_leaf(i) || node.child[i] == BvhNode::kEmpty) continue;
                const uint32_t first = ~static_cast<uint32_t>(node.child[i]);
                if (copy_leaf(g, bvh.prims, first, node.leaf_size(i), out))
                    ++served;
                else
                    node.count[i] |= BvhNode::kIndexedLeaf;
            }
        }
        return served;
    };
    if (bvh.prims.size() < (1u << 16)) return copy(0, bvh.nodes.size());
    const size_t half = bvh.nodes.size() / 2;
    size_t first = 0, second = 0;
    in_parallel([&] { second = copy(half, bvh.nodes.size()); }, [&] { first = copy(0, half); });
    return first + second;
}

// The leaf-order vertices (rt/geometry/leaf_vertices.h): in double for small scenes; in
// float otherwise, written into `storage` once the BVH build is done with the
// boxes there (sized for both), and kept only when some leaf is served.
void copy_leaf_vertices(Scene& s, ReusableStorage& storage, const BvhBuildOptions& options) {
    const Geometry& g = s.geometry;
    if (kLeafBlock == 1 || g.triangles.empty()) return;
    Bvh& bvh = s.accel.bvh;
    const size_t n = bvh.prims.size();
    if (options.double_copies(n)) {
        ReusableStorage doubles(LeafVertices::coordinates_for(n) * sizeof(double));
        double* const out = doubles.emplace<double>(LeafVertices::coordinates_for(n));
        if (copy_leaves(g, bvh, out) > 0) s.accel.leaf_vertices = LeafVertices(std::move(doubles), out);
        return;
    }
    // The boxes' lifetime ends here: the bytes now hold floats.
    float* const out = storage.emplace<float>(LeafVertices::coordinates_for(n));
    if (copy_leaves(g, bvh, out) > 0) s.accel.leaf_vertices = LeafVertices(std::move(storage), out);
}

// Builds everything, moving or releasing each mesh of `d` once it is copied.
Scene build(SceneDesc& d, const BvhBuildOptions& bvh, MeshCache* cache) {
    Scene s;
    SceneSetup& setup = s.setup;
    setup.background = d.background;
    setup.ambient_light = d.ambient_light;
    setup.shadow_ray_epsilon = d.shadow_ray_epsilon;
    setup.max_recursion_depth = d.max_recursion_depth;
    for (const CameraDesc& c : d.cameras) setup.cameras.push_back(make_camera(c));
    setup.lights.reserve(d.point_lights.size() + d.area_lights.size());
    for (const PointLightDesc& l : d.point_lights) setup.lights.push_back(Light::point(l.position, l.intensity));
    for (const AreaLightDesc& l : d.area_lights)
        setup.lights.push_back(Light::square(l.position, normalize(l.normal), l.size, l.radiance));
    setup.materials.reserve(d.materials.size());
    for (const MaterialDesc& m : d.materials) setup.materials.push_back(make_material(m));

    Geometry& g = s.geometry;
    // The meshes that instances show: in their own space, each with its own BVH
    // (rt/shapes/instance.h); the rest go into the scene's arrays.
    BuildInputs inputs;
    inputs.mesh_scenes.resize(d.meshes.size());
    for (size_t i = 0; i < d.meshes.size(); ++i) {
        MeshDesc& m = d.meshes[i];
        if (!m.instanced) continue;
        // A mesh read through the cache has its BVH there, made by the first frame.
        const std::string key =
            m.content_key.empty() ? "" : m.content_key + (m.shading == ShadingMode::Smooth ? "|smooth" : "|flat");
        SceneDesc own;
        own.path = d.path;
        own.meshes.push_back(std::move(m));
        own.meshes[0].transform = Affine{};
        own.meshes[0].motion = Vec3{};
        own.meshes[0].instanced = false;
        own.meshes[0].content_key.clear();
        const auto make = [&own, &bvh] { return build(own, bvh, nullptr); };
        std::shared_ptr<const Scene> mesh_scene =
            cache && !key.empty() ? cache->mesh_scene(key, make) : std::make_shared<const Scene>(make());
        s.report.degenerate_triangles += mesh_scene->report.degenerate_triangles;
        inputs.mesh_scenes[i] = std::move(mesh_scene);
        m = MeshDesc{};
        m.instanced = true;
    }
    size_t ntri = 0, nvert = 0;
    for (const MeshDesc& m : d.meshes) {
        ntri += m.indices.size() / 3;
        nvert += m.positions.size();
    }
    if (d.meshes.size() > 1) g.positions.reserve(nvert);
    g.triangles.reserve(ntri);
    // One allocation for the BVH's primitive boxes (boxes[id], triangles first) and
    // afterwards the leaf-order vertices that may take their place (copy_leaf_vertices).
    size_t nboxes = ntri;
    for_each_shape([&](auto k) {
        if constexpr (decltype(k)::kBounded) nboxes += d.all<typename decltype(k)::Desc>().size();
    });
    ReusableStorage storage(std::max(nboxes * sizeof(BuildBox), LeafVertices::coordinates_for(nboxes) * sizeof(float)));
    BuildBox* const boxes = storage.emplace<BuildBox>(nboxes);
    for (MeshDesc& m : d.meshes) {
        if (m.instanced) continue;
        s.names.meshes.push_back({static_cast<uint32_t>(g.triangles.size()), m.triangle_object, m.id, {}});
        add_mesh(g, s.report, m, boxes, s.names.meshes.back().skipped);
        std::vector<Vec3>().swap(m.positions);
        std::vector<uint32_t>().swap(m.indices);
    }
    for_each_shape([&](auto k) {
        using S = decltype(k);
        std::vector<typename S::Desc>& descs = d.all<typename S::Desc>();
        const size_t n = descs.size();
        g.all<S>().reserve(n);
        s.names.ids[size_t(kind_of<S>)].reserve(n);
        for (const typename S::Desc& e : descs) {
            if (!is_still(e.motion)) g.moves = true;
            g.all<S>().push_back(S::build(e, inputs));
            s.names.ids[size_t(kind_of<S>)].push_back(e.id, e.key);
        }
        // Released before the BVH is built: a scene of many instances would otherwise
        // hold each one twice at its peak, as desc and as shape.
        std::vector<typename S::Desc>().swap(descs);
    });
    for (auto& m : inputs.mesh_scenes)
        if (m) g.mesh_scenes.push_back(std::move(m));

    // Boxes of the bounded shapes after the triangles (add_mesh made theirs).
    add_boxes(g, g.count(ShapeKind::Triangle), boxes);
    const auto t0 = std::chrono::steady_clock::now();
    s.accel.bvh.build(boxes, g.bounded_count(), bvh);
    copy_leaf_vertices(s, storage, bvh);
    s.report.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

}  // namespace

Scene build_scene(const SceneDesc& d, const BvhBuildOptions& bvh, MeshCache* meshes) {
    SceneDesc copy = d;
    return build(copy, bvh, meshes);
}

Scene build_scene(SceneDesc&& d, const BvhBuildOptions& bvh, MeshCache* meshes) { return build(d, bvh, meshes); }

}  // namespace rt
