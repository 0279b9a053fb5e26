// A loaded scene as glTF 2.0 (docs/gltf.md): each mesh, triangle, sphere (tessellated)
// and plane (a large quad) a node, instances nodes sharing their mesh's accessors,
// Transformations node matrices, cameras and point lights (KHR_lights_punctual) nodes,
// area lights nodes of their own, materials by the table of gltf_materials.h. What glTF
// cannot hold exactly (the course's material values, a camera's near plane and image, the
// scene's settings, positions that are not floats, the exact sphere or plane behind a
// tessellation, an area light's place) goes into "ceng795" extras, which the import uses
// while they agree with the glTF values; what glTF has no place for at all (samples,
// lens, radiance, motion, Roughness) into those of gltf_extras.h.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>

#include "gltf_extras.h"
#include "gltf_io.h"
#include "rt/convert/convert.h"
#include "rt/convert/gltf_materials.h"
#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/io/atomic_file.h"
#include "rt/io/files.h"
#include "rt/loader/scene_desc.h"
#include "rt/shapes/shapes.h"
#include "scene_import.h"

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using json = nlohmann::json;
using rtgltf::to_value;

std::array<double, 3> arr(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

// One buffer; each accessor its own view.
class BufferWriter {
public:
    explicit BufferWriter(tinygltf::Model& model) : model_(model) { model_.buffers.emplace_back(); }

    int floats(const std::vector<float>& v, int components, bool bounds) {
        const int a = add(v.data(), v.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_FLOAT,
                          v.size() / size_t(components), components == 3 ? TINYGLTF_TYPE_VEC3 : TINYGLTF_TYPE_SCALAR);
        if (bounds && !v.empty()) {  // glTF requires min and max of POSITION
            tinygltf::Accessor& acc = model_.accessors[size_t(a)];
            acc.minValues.assign(size_t(components), HUGE_VAL);
            acc.maxValues.assign(size_t(components), -HUGE_VAL);
            for (size_t i = 0; i < v.size(); ++i) {
                const size_t c = i % size_t(components);
                acc.minValues[c] = std::min(acc.minValues[c], double(v[i]));
                acc.maxValues[c] = std::max(acc.maxValues[c], double(v[i]));
            }
        }
        return a;
    }
    int indices(const std::vector<uint32_t>& v) {
        return add(v.data(), v.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT,
                   v.size(), TINYGLTF_TYPE_SCALAR);
    }

private:
    int add(const void* data, size_t bytes, int target, int component, size_t count, int type) {
        std::vector<unsigned char>& buf = model_.buffers[0].data;
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = buf.size();
        view.byteLength = bytes;
        view.target = target;
        buf.insert(buf.end(), static_cast<const unsigned char*>(data), static_cast<const unsigned char*>(data) + bytes);
        model_.bufferViews.push_back(view);
        tinygltf::Accessor acc;
        acc.bufferView = int(model_.bufferViews.size() - 1);
        acc.componentType = component;
        acc.count = count;
        acc.type = type;
        model_.accessors.push_back(acc);
        return int(model_.accessors.size() - 1);
    }
    tinygltf::Model& model_;
};

// A triangle mesh's accessors: POSITION, indices, and NORMAL for smooth shading.
struct Geometry {
    int positions = -1, indices = -1, normals = -1;
    json extras;  // the mesh's "ceng795" extras (exact positions, sphere, plane), or null
};

// Area-weighted vertex normals (glTF wants unit normals; the import does not read them:
// the renderer makes its own).
std::vector<float> vertex_normals(const std::vector<Vec3>& p, const std::vector<uint32_t>& idx) {
    std::vector<Vec3> n(p.size(), Vec3{0, 0, 0});
    for (size_t i = 0; i + 2 < idx.size(); i += 3) {
        const Vec3 c = cross(p[idx[i + 1]] - p[idx[i]], p[idx[i + 2]] - p[idx[i]]);
        for (int k = 0; k < 3; ++k) n[idx[i + size_t(k)]] = n[idx[i + size_t(k)]] + c;
    }
    std::vector<float> out;
    out.reserve(3 * n.size());
    for (const Vec3& v : n) {
        const Real l = length(v);
        const Vec3 u = l > 0 ? v / l : Vec3{0, 1, 0};
        out.insert(out.end(), {float(u.x), float(u.y), float(u.z)});
    }
    return out;
}

// `exact`: positions a float cannot hold go into the extras as doubles (not needed for
// a tessellation, which the import replaces by its sphere or plane).
Geometry add_geometry(BufferWriter& buffers, const std::vector<Vec3>& positions, const std::vector<uint32_t>& indices,
                      bool smooth, bool keep_exact) {
    Geometry g;
    std::vector<float> p;
    p.reserve(3 * positions.size());
    bool exact = true;
    for (const Vec3& v : positions)
        for (int k = 0; k < 3; ++k) {
            p.push_back(float(v[k]));
            exact = exact && double(p.back()) == double(v[k]);
        }
    g.positions = buffers.floats(p, 3, true);
    g.indices = buffers.indices(indices);
    if (smooth) {
        g.normals = buffers.floats(vertex_normals(positions, indices), 3, false);
        // The import welds vertices other tools split; these are as the scene has them.
        g.extras["vertices"] = positions.size();
    }
    if (!exact && keep_exact) {  // positions a float cannot hold: their doubles
        json exact_positions = json::array();
        for (const Vec3& v : positions)
            for (int k = 0; k < 3; ++k) exact_positions.push_back(double(v[k]));
        g.extras["positions"] = std::move(exact_positions);
    }
    return g;
}

// A polygon list (rt/shapes/shape.h) as a triangle list, fan-split.
std::vector<uint32_t> triangles_of(const Polygons& poly) {
    std::vector<uint32_t> out;
    for (const std::vector<uint32_t>& f : poly.faces)
        for (size_t k = 2; k < f.size(); ++k) out.insert(out.end(), {f[0], f[k - 1], f[k]});
    return out;
}

// A row-major affine as glTF's column-major 4x4; none for the identity.
std::vector<double> node_matrix(const Affine& m) {
    if (m.is_identity()) return {};
    std::vector<double> out(16, 0.0);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) out[size_t(4 * c + r)] = m.m[r][c];
    out[15] = 1;
    return out;
}

// The rotation taking a node's -z axis (where glTF's lights point) to `n`, a unit vector,
// as a unit quaternion x y z w: the shortest arc, or a half turn about x when n is +z.
std::vector<double> rotation_to(const Vec3& n) {
    if (!(n.z < 1)) return {1, 0, 0, 0};
    const double x = n.y, y = -n.x, w = 1 - n.z, l = std::sqrt(x * x + y * y + w * w);
    return {x / l, y / l, 0, w / l};
}

// The rotation taking glTF's camera frame (looking down -z, +y up) to the camera's
// (spec 2.1: w = -gaze, u = up x w, v = w x u), as a unit quaternion x y z w.
std::vector<double> camera_rotation(const CameraDesc& c) {
    const Vec3 w = normalize(-c.gaze), u = normalize(cross(c.up, w)), v = cross(w, u);
    const double m[3][3] = {{u.x, v.x, w.x}, {u.y, v.y, w.y}, {u.z, v.z, w.z}};
    double x, y, z, s;
    const double tr = m[0][0] + m[1][1] + m[2][2];
    if (tr > 0) {
        s = 2 * std::sqrt(1 + tr);
        return {(m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, s / 4};
    }
    if (m[0][0] > m[1][1] && m[0][0] > m[2][2]) {
        s = 2 * std::sqrt(1 + m[0][0] - m[1][1] - m[2][2]);
        x = s / 4, y = (m[0][1] + m[1][0]) / s, z = (m[0][2] + m[2][0]) / s;
        return {x, y, z, (m[2][1] - m[1][2]) / s};
    }
    if (m[1][1] > m[2][2]) {
        s = 2 * std::sqrt(1 + m[1][1] - m[0][0] - m[2][2]);
        x = (m[0][1] + m[1][0]) / s, y = s / 4, z = (m[1][2] + m[2][1]) / s;
        return {x, y, z, (m[0][2] - m[2][0]) / s};
    }
    s = 2 * std::sqrt(1 + m[2][2] - m[0][0] - m[1][1]);
    x = (m[0][2] + m[2][0]) / s, y = (m[1][2] + m[2][1]) / s, z = s / 4;
    return {x, y, z, (m[1][0] - m[0][1]) / s};
}

class Exporter {
public:
    Exporter(const SceneDesc& scene, tinygltf::Model& model, const ConvertOptions& options, ConvertResult& result)
        : scene_(scene), model_(model), options_(options), result_(result), buffers_(model) {}

    void run() {
        model_.asset.version = "2.0";
        model_.asset.generator = "rtconvert (raytracer, CENG 795 scene format)";
        model_.scenes.emplace_back();
        model_.defaultScene = 0;
        tinygltf::Scene& s = model_.scenes[0];
        // The file's name, not its path: a shared file carries none of its author's folders.
        s.name = std::filesystem::path(scene_.path).filename().string();
        add_materials();
        add_meshes();
        add_shapes();
        add_cameras();
        add_lights();
        add_area_lights();
        // The settings, and every material, plane and area light once more: pipelines that
        // merge materials (glTF Transform's palette) or meshes (its join) keep one element's
        // extras of those they merge, and those that prune nodes without content (its prune)
        // drop the area lights' nodes; the scene's extras stay (docs/gltf.md).
        json extras = {{"backgroundColor", arr(scene_.background)},
                       {"shadowRayEpsilon", double(scene_.shadow_ray_epsilon)},
                       {"intersectionTestEpsilon", double(scene_.intersection_test_epsilon)},
                       {"maxRecursionDepth", scene_.max_recursion_depth},
                       {"ambientLight", arr(scene_.ambient_light)},
                       {"materials", material_extras_}};
        if (!plane_extras_.empty()) extras["planes"] = plane_extras_;
        if (!area_light_extras_.empty()) extras["areaLights"] = area_light_extras_;
        if (const json boxes = material_boxes(); !boxes.empty()) extras["materialBoxes"] = boxes;
        model_.scenes[0].extras = ours_as_extras(extras);
        for (size_t i = 0; i < model_.nodes.size(); ++i) model_.scenes[0].nodes.push_back(int(i));
    }

private:
    // The world boxes of the objects drawn with each material that glTF cannot tell from
    // another (the same PBR values, other course values): a pipeline that merges materials
    // (glTF Transform's palette) merges those into one texel, and the import tells their
    // triangles apart by where they are. {"index": [[lo x y z, hi x y z], ...]}.
    json material_boxes() const {
        std::vector<bool> twin(scene_.materials.size(), false);
        for (size_t i = 0; i < scene_.materials.size(); ++i)
            for (size_t j = i + 1; j < scene_.materials.size(); ++j)
                if (same_pbr(pbr_of(scene_.materials[i]), pbr_of(scene_.materials[j])) &&
                    material_extras_[i] != material_extras_[j])
                    twin[i] = twin[j] = true;
        json out = json::object();
        // The box of `points` (or of [lo, hi] when `points` is null), moved by `to_world`.
        auto add = [&](uint32_t material, const std::vector<Vec3>* points, Vec3 lo, Vec3 hi, const Affine& to_world) {
            if (material >= twin.size() || !twin[material]) return;
            if (points) {
                if (points->empty()) return;
                lo = hi = (*points)[0];
                for (const Vec3& q : *points) lo = vmin(lo, q), hi = vmax(hi, q);
            }
            Vec3 wlo = to_world.point(lo), whi = wlo;
            for (int c = 1; c < 8; ++c) {
                const Vec3 q = to_world.point({c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z});
                wlo = vmin(wlo, q), whi = vmax(whi, q);
            }
            out[std::to_string(material)].push_back(json::array({wlo.x, wlo.y, wlo.z, whi.x, whi.y, whi.z}));
        };
        for (const MeshDesc& m : scene_.meshes)
            if (!m.instanced) add(m.material, &m.positions, {}, {}, Affine{});
        for (const InstanceDesc& d : scene_.all<InstanceDesc>())
            add(d.material, &scene_.meshes.at(d.mesh).positions, {}, {}, d.transform);
        for (const SphereDesc& d : scene_.all<SphereDesc>()) {
            const Vec3 r{d.radius, d.radius, d.radius};
            add(d.material, nullptr, d.center - r, d.center + r, d.transform);
        }
        return out;
    }

    void add_materials() {
        bool transmission = false, ior = false, volume = false;
        for (const MaterialDesc& m : scene_.materials) {
            const PbrMaterial p = pbr_of(m);
            tinygltf::Material g;
            g.name = "Material " + m.id;
            g.pbrMetallicRoughness.baseColorFactor = {p.base[0], p.base[1], p.base[2], 1.0};
            g.pbrMetallicRoughness.metallicFactor = p.metallic;
            g.pbrMetallicRoughness.roughnessFactor = p.roughness;
            if (p.transmission > 0) {
                transmission = ior = true;
                g.extensions["KHR_materials_transmission"] = to_value({{"transmissionFactor", p.transmission}});
                g.extensions["KHR_materials_ior"] = to_value({{"ior", p.ior}});
                if (std::isfinite(p.attenuation_distance)) {
                    volume = true;
                    g.extensions["KHR_materials_volume"] =
                        to_value({{"thicknessFactor", 1.0},
                                  {"attenuationDistance", p.attenuation_distance},
                                  {"attenuationColor", {p.attenuation[0], p.attenuation[1], p.attenuation[2]}}});
                }
            }
            json extras = material_extras(m);
            extras.update(extras_of(kMaterialExtras, m));
            g.extras = ours_as_extras(extras);
            material_extras_.push_back(std::move(extras));
            model_.materials.push_back(std::move(g));
        }
        if (transmission) model_.extensionsUsed.push_back("KHR_materials_transmission");
        if (ior) model_.extensionsUsed.push_back("KHR_materials_ior");
        if (volume) model_.extensionsUsed.push_back("KHR_materials_volume");
    }

    // A glTF mesh of one primitive: `geometry` drawn with `material`, made once per pair.
    int mesh_of(size_t geometry, uint32_t material, const std::string& name) {
        const auto key = std::make_pair(geometry, material);
        if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
        const Geometry& g = geometries_[geometry];
        tinygltf::Primitive prim;
        prim.mode = TINYGLTF_MODE_TRIANGLES;
        prim.attributes["POSITION"] = g.positions;
        if (g.normals >= 0) prim.attributes["NORMAL"] = g.normals;
        prim.indices = g.indices;
        prim.material = int(material);
        tinygltf::Mesh mesh;
        mesh.name = name;
        mesh.primitives.push_back(prim);
        if (!g.extras.is_null()) mesh.extras = ours_as_extras(g.extras);
        model_.meshes.push_back(std::move(mesh));
        meshes_[key] = int(model_.meshes.size() - 1);
        return meshes_[key];
    }

    // A node showing `mesh`; `motion` its object's MotionBlur.
    void add_node(const std::string& name, int mesh, const Affine& transform, const Vec3& motion) {
        tinygltf::Node n;
        n.name = name;
        n.mesh = mesh;
        n.matrix = node_matrix(transform);
        if (const json extras = extras_of(kMotionExtras, motion); !extras.empty()) n.extras = ours_as_extras(extras);
        model_.nodes.push_back(std::move(n));
    }

    // Meshes and triangles: one geometry each. One that is drawn as an instance of
    // itself (moved, or shown by instances) is drawn by its InstanceDesc, below.
    void add_meshes() {
        for (size_t i = 0; i < scene_.meshes.size(); ++i) {
            const MeshDesc& m = scene_.meshes[i];
            geometries_.push_back(
                add_geometry(buffers_, m.positions, m.indices, m.shading == ShadingMode::Smooth, true));
            const std::string name = std::string(m.triangle_object ? "Triangle " : "Mesh ") + m.id;
            if (!m.instanced) add_node(name, mesh_of(i, m.material, name), Affine{}, m.motion);
        }
    }

    // Every kind of shape, instances first (the meshes drawn as themselves, in the loader's
    // order), then spheres and planes: one add_kind per kind of ShapeDescs, and a kind
    // missing from ExportedKinds does not compile.
    using ExportedKinds = KindList<InstanceDesc, SphereDesc, PlaneDesc>;
    static_assert(ExportedKinds::size == ShapeDescs::size && covers(ExportedKinds{}, ShapeDescs{}),
                  "the glTF export writes every kind of ShapeDescs");

    void add_shapes() {
        const ExportFrame frame = export_frame(scene_, options_.sphere_segments);
        for_each_kind(ExportedKinds{}, [&](auto k) { add_kind(k, frame); });
    }

    void add_kind(InstanceDesc, const ExportFrame&) {
        for (const InstanceDesc& d : scene_.all<InstanceDesc>()) {
            const MeshDesc& m = scene_.meshes.at(d.mesh);
            const std::string name = std::string(d.key ? d.key : InstanceDesc::kKey) + " " + d.id;
            add_node(name, mesh_of(d.mesh, d.material, std::string(m.triangle_object ? "Triangle " : "Mesh ") + m.id),
                     d.transform, d.motion);
        }
    }

    void add_kind(SphereDesc, const ExportFrame& frame) {
        for (const SphereDesc& d : scene_.all<SphereDesc>()) {
            SphereDesc local = d;
            local.transform = Affine{};
            const Polygons poly = Sphere::polygons(local, frame);
            geometries_.push_back(add_geometry(buffers_, poly.vertices, triangles_of(poly), true, false));
            geometries_.back().extras["sphere"] = {{"center", arr(d.center)}, {"radius", double(d.radius)}};
            const std::string name = "Sphere " + d.id;
            add_node(name, mesh_of(geometries_.size() - 1, d.material, name), d.transform, d.motion);
        }
        if (!scene_.all<SphereDesc>().empty())
            result_.notes.push_back(count_of(scene_.all<SphereDesc>().size(), SphereDesc::kNoun, SphereDesc::kNouns) +
                                    " tessellated, " + count_of(size_t(options_.sphere_segments), "segment"));
    }

    void add_kind(PlaneDesc, const ExportFrame& frame) {
        for (const PlaneDesc& d : scene_.all<PlaneDesc>()) {
            const Polygons poly = Plane::polygons(d, frame);
            geometries_.push_back(add_geometry(buffers_, poly.vertices, triangles_of(poly), false, false));
            geometries_.back().extras["plane"] = {{"point", arr(d.point)}, {"normal", arr(d.normal)}};
            plane_extras_.push_back(geometries_.back().extras["plane"]);
            const std::string name = "Plane " + d.id;
            add_node(name, mesh_of(geometries_.size() - 1, d.material, name), Affine{}, d.motion);
        }
        if (!scene_.all<PlaneDesc>().empty())
            result_.notes.push_back(count_of(scene_.all<PlaneDesc>().size(), PlaneDesc::kNoun, PlaneDesc::kNouns) +
                                    " as squares of side " + course_number(10 * double(frame.extent)));
    }

    void add_cameras() {
        for (size_t i = 0; i < scene_.cameras.size(); ++i) {
            const CameraDesc& c = scene_.cameras[i];
            const std::string where = "camera " + std::to_string(i + 1);
            tinygltf::Camera g;
            g.type = "perspective";
            g.name = "Camera " + std::to_string(i + 1);
            const double d = double(c.near_distance);
            g.perspective.yfov = std::atan(double(c.top) / d) - std::atan(double(c.bottom) / d);
            g.perspective.aspectRatio = double(c.width) / double(c.height);
            g.perspective.znear = d;
            if (c.left != -c.right || c.bottom != -c.top)
                result_.warnings.push_back(scene_.path + ": " + where +
                                           ": its near plane is off-centre; glTF keeps its vertical field of view "
                                           "only (the exact camera is in the extras)");
            if (const json lens = extras_of(kCameraExtras, c); !lens.empty()) g.extras = ours_as_extras(lens);
            model_.cameras.push_back(g);
            tinygltf::Node n;
            n.name = g.name;
            n.camera = int(model_.cameras.size() - 1);
            n.translation = {double(c.position.x), double(c.position.y), double(c.position.z)};
            n.rotation = camera_rotation(c);
            n.extras =
                ours_as_extras({{"camera",
                                 {{"position", arr(c.position)},
                                  {"gaze", arr(c.gaze)},
                                  {"up", arr(c.up)},
                                  {"nearPlane", {double(c.left), double(c.right), double(c.bottom), double(c.top)}},
                                  {"nearDistance", d},
                                  {"imageResolution", {c.width, c.height}},
                                  {"imageName", c.image_name}}}});
            model_.nodes.push_back(std::move(n));
        }
    }

    void add_lights() {
        for (size_t i = 0; i < scene_.point_lights.size(); ++i) {
            const PointLightDesc& l = scene_.point_lights[i];
            tinygltf::Light g;
            g.type = "point";
            g.name = "PointLight " + std::to_string(i + 1);
            const double peak = std::max({double(l.intensity.x), double(l.intensity.y), double(l.intensity.z)});
            g.color = peak > 0 ? std::vector<double>{l.intensity.x / peak, l.intensity.y / peak, l.intensity.z / peak}
                               : std::vector<double>{1, 1, 1};
            g.intensity = std::max(peak, 0.0) / options_.light_scale;
            g.extras = ours_as_extras({{"intensity", arr(l.intensity)}});
            model_.lights.push_back(g);
            tinygltf::Node n;
            n.name = g.name;
            n.translation = {double(l.position.x), double(l.position.y), double(l.position.z)};
            n.extensions["KHR_lights_punctual"] = to_value({{"light", int(model_.lights.size() - 1)}});
            model_.nodes.push_back(std::move(n));
        }
        if (!scene_.point_lights.empty()) model_.extensionsUsed.push_back("KHR_lights_punctual");
        if (scene_.ambient_light.x > 0 || scene_.ambient_light.y > 0 || scene_.ambient_light.z > 0)
            result_.notes.push_back("ambient light: glTF has none; kept in the scene's extras");
    }

    // glTF has no area lights: each is a node of its own, centred at its Position, its -z
    // axis along its Normal, scaled by its Size (a modelling tool shows, moves and turns
    // it), and its values, Radiance too, in the node's extras.
    void add_area_lights() {
        for (size_t i = 0; i < scene_.area_lights.size(); ++i) {
            const AreaLightDesc& l = scene_.area_lights[i];
            tinygltf::Node n;
            n.name = "AreaLight " + std::to_string(i + 1);
            n.translation = {double(l.position.x), double(l.position.y), double(l.position.z)};
            n.rotation = rotation_to(normalize(l.normal));
            n.scale = {double(l.size), double(l.size), double(l.size)};
            n.extras = ours_as_extras({{"areaLight", extras_of(kAreaLightExtras, l)}});
            area_light_extras_.push_back(extras_of(kAreaLightExtras, l));
            model_.nodes.push_back(std::move(n));
        }
        if (!scene_.area_lights.empty())
            result_.notes.push_back(count_of(scene_.area_lights.size(), "area light") +
                                    ": glTF has none; nodes of their own, their values in the extras");
    }

    const SceneDesc& scene_;
    tinygltf::Model& model_;
    const ConvertOptions& options_;
    ConvertResult& result_;
    BufferWriter buffers_;
    std::vector<Geometry> geometries_;
    json material_extras_ = json::array(), plane_extras_ = json::array(),
         area_light_extras_ = json::array();  // for the scene's extras
    std::map<std::pair<size_t, uint32_t>, int> meshes_;
};

}  // namespace

std::vector<std::string> write_gltf(const SceneDesc& scene, const std::string& path, const ConvertOptions& options,
                                    ConvertResult& result) {
    tinygltf::Model model;
    Exporter(scene, model, options, result).run();
    result.notes.push_back(
        count_of(model.nodes.size(), "node") + ", " + count_of(model.meshes.size(), "mesh", "meshes") + ", " +
        count_of(model.materials.size(), "material") + ", " + count_of(model.cameras.size(), "camera") + ", " +
        count_of(model.lights.size(), "point light"));
    namespace fs = std::filesystem;
    const bool binary = lower_extension(path) == ".glb";
    const std::string bin_name = fs::path(path).stem().string() + ".bin";
    rtgltf::Serialized bytes;
    try {
        bytes = rtgltf::serialize(model, binary, bin_name);
    } catch (const rtgltf::Error& e) {
        throw InputError(path + ": cannot write: " + e.what());
    }
    std::vector<std::string> written{path};
    if (!bytes.bin.empty() || (!binary && !model.buffers.empty())) {
        const std::string bin_path = (fs::path(path).parent_path() / bin_name).string();
        write_file_atomic(bin_path, bytes.bin);
        written.push_back(bin_path);
    }
    write_file_atomic(path, bytes.main);  // last, so that it never names a missing buffer
    return written;
}
#else
std::vector<std::string> write_gltf(const SceneDesc&, const std::string& path, const ConvertOptions&, ConvertResult&) {
    throw InputError(path + ": glTF is not supported by this build (it was made without tinygltf, libtinygltf-dev)");
}
#endif  // RT_NO_GLTF

}  // namespace rt
