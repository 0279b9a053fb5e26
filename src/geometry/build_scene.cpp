// SceneDesc -> Scene: flat arrays, normals, BVH.
#include <algorithm>
#include <chrono>
#include <thread>
#include <utility>

#include "rt/scene.h"
#include "rt/threads.h"

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

BuildBox make_box(Vec3 lo, Vec3 hi) {
    BuildBox b{};
    for (int a = 0; a < 3; ++a) {
        b.lo[a] = round_down_to_float(lo[a]);
        b.hi[a] = round_up_to_float(hi[a]);
    }
    return b;
}

BuildBox triangle_box(const std::vector<Vec3>& pos, const uint32_t v[3]) {
    const Vec3 a = pos[v[0]], b = pos[v[1]], c = pos[v[2]];
    return make_box(vmin(a, vmin(b, c)), vmax(a, vmax(b, c)));
}

BuildBox sphere_box(const Sphere& sp) {
    const Vec3 r{sp.radius, sp.radius, sp.radius};
    return make_box(sp.center - r, sp.center + r);
}

// Twice the area vector of triangle (a, b, c) and whether it is degenerate
// (spec 2.10: two vertices coincide or all three are collinear).
inline bool degenerate(const std::vector<Vec3>& p, uint32_t a, uint32_t b, uint32_t c, Vec3& n) {
    n = cross(p[b] - p[a], p[c] - p[a]);
    const Real len = length(n);
    return !(len > 0) || !std::isfinite(len);
}

// Meshes with at least this many faces are converted by two threads.
constexpr size_t kParallelFaces = size_t(1) << 16;

// Appends one mesh: its vertices (taken from `m` when it is the first), its
// non-degenerate triangles with their BVH boxes (appended to `boxes`, which
// has one element per triangle of s), and, when smooth, vertex normals
// averaged over this mesh only, weighted by area (spec section 3, "Mesh";
// pooling across meshes does not match the references). Flat scenes get no
// vertex normals at all.
void add_mesh(Scene& s, MeshDesc& m, UninitVector<BuildBox>& boxes) {
    const uint32_t base = static_cast<uint32_t>(s.positions.size());
    if (base == 0 && s.positions.capacity() <= m.positions.size())
        s.positions = std::move(m.positions);
    else
        s.positions.insert(s.positions.end(), m.positions.begin(), m.positions.end());
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
    // marked with material 0x7fffffff and squeezed out below.
    constexpr uint32_t kDropped = 0x7fffffff;
    s.triangles.resize(first + faces);
    boxes.resize(first + faces);
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
            t.smooth = smooth ? 1 : 0;
            Vec3 n;
            if (degenerate(pos, a, b, c, n)) {
                t.material = kDropped;
                ++dropped;
                continue;
            }
            t.material = m.material;
            boxes[first + f] = triangle_box(pos, t.v);
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
        std::thread helper = start_or_run([&] {
            if (smooth) accumulate_normals();
            helper_dropped = convert(0, split);
        });
        dropped = convert(split, faces);
        if (helper.joinable()) helper.join();
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
        if (s.triangles[i].material == kDropped) {
            ++s.degenerate_triangles;
            continue;
        }
        if (out != i) {
            s.triangles[out] = s.triangles[i];
            boxes[out] = boxes[i];
        }
        ++out;
    }
    s.triangles.resize(out);
    boxes.resize(out);
}

}  // namespace

UninitVector<BuildBox> primitive_boxes(const Scene& s) {
    UninitVector<BuildBox> boxes(s.triangles.size() + s.spheres.size());
    for (size_t i = 0; i < s.triangles.size(); ++i) boxes[i] = triangle_box(s.positions, s.triangles[i].v);
    for (size_t i = 0; i < s.spheres.size(); ++i) boxes[s.triangles.size() + i] = sphere_box(s.spheres[i]);
    return boxes;
}

namespace {

// x is a float exactly. Out of line on purpose: GCC 12 at -O2, given three such
// (double)(float) round trips side by side, vectorised them and dropped two
// (seen on `v = {double(float(v.x)), double(float(v.y)), double(float(v.z))}`).
[[gnu::noinline]] bool is_float(Real x) { return Real(float(x)) == x; }

// Boxes of storage that hold the leaf-order vertices of n triangles (9 floats each).
size_t leaf_storage_boxes(size_t n) { return (n * 9 * sizeof(float) + sizeof(BuildBox) - 1) / sizeof(BuildBox); }

// Scene::leaf_vertices(), when every position is a float exactly, written over
// `boxes` once the BVH build is done with them (reserved with room for 36 bytes
// per primitive, so the resize moves nothing); two threads copy half each.
void copy_leaf_vertices(Scene& s, UninitVector<BuildBox>& boxes) {
    if (kLeafBlock == 1 || !s.spheres.empty() || s.triangles.empty()) return;
    for (const Vec3& p : s.positions)
        if (!is_float(p.x) || !is_float(p.y) || !is_float(p.z)) return;
    const size_t n = s.bvh.prims.size();
    boxes.resize(leaf_storage_boxes(n));
    float* const out = reinterpret_cast<float*>(boxes.data());
    auto copy = [&s, out](size_t begin, size_t end) {
        for (size_t i = begin; i < end; ++i) {
            const Triangle& t = s.triangles[s.bvh.prims[i]];
            float* o = out + i * 9;
            for (int k = 0; k < 3; ++k) {
                const Vec3& v = s.positions[t.v[k]];
                o[3 * k] = float(v.x);
                o[3 * k + 1] = float(v.y);
                o[3 * k + 2] = float(v.z);
            }
        }
    };
    if (n < (1u << 16)) {
        copy(0, n);
    } else {
        std::thread helper = start_or_run([&] { copy(0, n / 2); });
        copy(n / 2, n);
        if (helper.joinable()) helper.join();
    }
    s.leaf_storage = std::move(boxes);
}

// Builds everything, moving or releasing each mesh of `d` once it is copied.
Scene build(SceneDesc& d, const BvhBuildOptions& bvh) {
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
    if (d.meshes.size() > 1) s.positions.reserve(nvert);
    s.triangles.reserve(ntri);
    // Primitive boxes for the BVH: triangles first, in order, then spheres.
    UninitVector<BuildBox> boxes;
    // Room for the leaf-order vertices that may reuse this array (copy_leaf_vertices).
    boxes.reserve(std::max(ntri + d.spheres.size(), leaf_storage_boxes(ntri)));
    for (size_t i = 0; i < d.meshes.size(); ++i) {
        add_mesh(s, d.meshes[i], boxes);
        std::vector<Vec3>().swap(d.meshes[i].positions);
        std::vector<uint32_t>().swap(d.meshes[i].indices);
    }
    for (const SphereDesc& sp : d.spheres) s.spheres.push_back({sp.center, sp.radius, sp.material});
    for (const PlaneDesc& p : d.planes) s.planes.push_back({p.point, normalize(p.normal), p.material});

    for (const Sphere& sp : s.spheres) boxes.push_back(sphere_box(sp));
    const auto t0 = std::chrono::steady_clock::now();
    s.bvh.build(boxes, bvh);
    copy_leaf_vertices(s, boxes);
    s.build_seconds = std::chrono::duration<Real>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

}  // namespace

Scene build_scene(const SceneDesc& d, const BvhBuildOptions& bvh) {
    SceneDesc copy = d;
    return build(copy, bvh);
}

Scene build_scene(SceneDesc&& d, const BvhBuildOptions& bvh) {
    return build(d, bvh);
}

}  // namespace rt
