// glTF 2.0 -> the course's JSON (docs/gltf.md): triangle primitives become meshes (one
// PLY per accessor pair, further uses MeshInstances of the first), the node hierarchy
// Composite transformations, perspective cameras and KHR_lights_punctual point lights
// the scene's, materials by the table of gltf_materials.h (gltf_import_materials.cpp). "ceng795"
// extras written by the export are used where they still agree with what the glTF says;
// those glTF has no place for (gltf_extras.h: samples, lens, area lights, motion,
// Roughness) are checked and used as they are.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <filesystem>
#include <map>
#include <set>

#include "gltf_extras.h"
#include "gltf_import.h"
#include "gltf_io.h"
#include "gltf_palette.h"
#include "gltf_primitives.h"
#include "gltf_shapes.h"
#include "rt/convert/gltf_materials.h"
#include "rt/core/affine.h"
#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/io/files.h"
#include "rt/loader/scene_desc.h"
#include "scene_import.h"

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using rtgltf::to_json;

// Triangles drawn with one material (its _id).
struct Piece {
    const GltfTriangles* triangles;
    std::string material;
};

// What the import made of a primitive's triangles, the first time a node showed them.
struct FirstUse {
    int base = -1;   // the Objects/Mesh _id that shows it first
    size_t ply = 0;  // its ImportedMesh
};

// Deeper node hierarchies are refused (a bound on the importer's recursion).
constexpr int kMaxDepth = 1000;

struct CameraUse {
    int camera;
    int node;
    Affine world;
};

class Importer {
public:
    Importer(const std::string& path, const tinygltf::Model& model, const ConvertOptions& options,
             const std::string& ply_prefix, const std::string& image_stem, SceneImport& out)
        : path_(path),
          model_(model),
          options_(options),
          ply_prefix_(ply_prefix),
          image_stem_(image_stem),
          out_(out),
          primitives_(model, path, out.warnings) {}

    void run() {
        traverse();
        ojson scene = ojson::object();
        scene_settings(scene);
        scene["Cameras"] = {{"Camera", cameras()}};
        scene["Lights"] = lights();
        scene["Materials"] = {{"Material", import_materials(model_, path_, needs_default_material_, texels_,
                                                            scene_extras_, scene_at_, out_)}};
        if (!transforms_.empty()) scene["Transformations"] = {{"Composite", transforms_}};
        if (!vertex_data_.empty()) scene["VertexData"] = {{"_data", vertex_data_}, {"_type", "xyz"}};
        ojson objects = ojson::object();
        if (!mesh_objects_.empty()) objects["Mesh"] = mesh_objects_;
        if (!instance_objects_.empty()) objects["MeshInstance"] = instance_objects_;
        if (!sphere_objects_.empty()) objects["Sphere"] = sphere_objects_;
        if (!plane_objects_.empty()) objects["Plane"] = plane_objects_;
        if (objects.empty()) fail("", "no triangle meshes in the scene");
        scene["Objects"] = objects;
        out_.scene = {{"Scene", scene}};
        out_.notes.push_back(
            count_of(mesh_objects_.size(), "mesh", "meshes") + " (" + count_of(out_.meshes.size(), "PLY file") + "), " +
            count_of(instance_objects_.size(), "instance") + ", " + count_of(sphere_objects_.size(), "sphere") + ", " +
            count_of(plane_objects_.size(), "plane") + ", " + count_of(transforms_.size(), "transformation"));
    }

private:
    [[noreturn]] void fail(const std::string& element, const std::string& what) const {
        throw InputError(path_ + ": " + (element.empty() ? "" : element + ": ") + what);
    }
    // The file and an element's "ceng795" extras, as read_extras names them.
    std::string extras_at(const std::string& element) const {
        return path_ + ": " + element + "/extras/" + kGltfExtrasKey;
    }
    void warn(const std::string& what) { out_.warnings.push_back(path_ + ": " + what); }

    // ---- Nodes ----------------------------------------------------------------------

    Affine local_matrix(const tinygltf::Node& n, int index) const {
        const std::string np = "/nodes/" + std::to_string(index);
        if (!n.matrix.empty()) {
            if (n.matrix.size() != 16) fail(np + "/matrix", "needs 16 numbers");
            if (n.matrix[3] != 0 || n.matrix[7] != 0 || n.matrix[11] != 0 || n.matrix[15] != 1)
                fail(np + "/matrix", "is not affine (its last row must be 0 0 0 1)");
            double rows[12];
            for (int r = 0; r < 3; ++r)
                for (int c = 0; c < 4; ++c) rows[4 * r + c] = n.matrix[size_t(4 * c + r)];
            return Affine::rows(rows);
        }
        return trs(n.translation, n.rotation, n.scale, np);
    }

    // T * R * S, each left out where empty; `where` names the node or instance.
    Affine trs(const std::vector<double>& t, const std::vector<double>& q, const std::vector<double>& s,
               const std::string& where) const {
        Affine m;
        if (s.size() == 3) m = Affine::scaling(s[0], s[1], s[2]);
        if (q.size() == 4) {
            double x = q[0], y = q[1], z = q[2], w = q[3];
            const double len = std::sqrt(x * x + y * y + z * z + w * w);
            if (!(len > 0)) fail(where + "/rotation", "is not a rotation (zero quaternion)");
            x /= len, y /= len, z /= len, w /= len;
            const double r[12] = {1 - 2 * (y * y + z * z), 2 * (x * y - z * w),     2 * (x * z + y * w),     0,
                                  2 * (x * y + z * w),     1 - 2 * (x * x + z * z), 2 * (y * z - x * w),     0,
                                  2 * (x * z - y * w),     2 * (y * z + x * w),     1 - 2 * (x * x + y * y), 0};
            m = Affine::rows(r) * m;
        }
        if (t.size() == 3) m = Affine::translation(t[0], t[1], t[2]) * m;
        return m;
    }

    // EXT_mesh_gpu_instancing: the matrices of a node's instances, from its TRANSLATION,
    // ROTATION and SCALE accessors (floats, or quantised).
    std::vector<Affine> instances(const json& ext, const std::string& np) const {
        const std::string ep = np + "/extensions/EXT_mesh_gpu_instancing";
        const json none;
        const json& attributes = ext.is_object() ? ext.value("attributes", none) : none;
        if (!attributes.is_object()) fail(ep, "has no attributes");
        std::vector<double> columns[3];  // translation, rotation, scale
        const char* names[3] = {"TRANSLATION", "ROTATION", "SCALE"};
        const int types[3] = {TINYGLTF_TYPE_VEC3, TINYGLTF_TYPE_VEC4, TINYGLTF_TYPE_VEC3};
        size_t count = 0;
        bool any = false;
        for (size_t k = 0; k < 3; ++k) {
            if (!attributes.contains(names[k])) continue;
            const json& a = attributes[names[k]];
            if (!a.is_number_integer()) fail(ep + "/attributes/" + names[k], "must name an accessor");
            columns[k] = primitives_.numbers(a.get<int>(), types[k], ep + "/attributes/" + names[k]);
            const size_t n = columns[k].size() / (k == 1 ? 4 : 3);
            if (any && n != count) fail(ep + "/attributes/" + names[k], "has another count than the others");
            count = n;
            any = true;
        }
        if (!any) fail(ep, "has none of TRANSLATION, ROTATION and SCALE");
        std::vector<Affine> out;
        for (size_t i = 0; i < count; ++i) {
            auto part = [&](size_t k, size_t n) {
                return columns[k].empty() ? std::vector<double>()
                                          : std::vector<double>(columns[k].begin() + long(n * i),
                                                                columns[k].begin() + long(n * (i + 1)));
            };
            out.push_back(trs(part(0, 3), part(1, 4), part(2, 3), ep + "/" + std::to_string(i)));
        }
        return out;
    }

    void traverse() {
        std::vector<int> roots;
        if (!model_.scenes.empty()) {
            const int s = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size()
                              ? model_.defaultScene
                              : 0;
            if (model_.scenes.size() > 1)
                warn("scene " + std::to_string(s) + " of " + std::to_string(model_.scenes.size()) + " converted");
            roots = model_.scenes[size_t(s)].nodes;
            scene_extras_ = ours_in(model_.scenes[size_t(s)].extras);
            scene_at_ = "/scenes/" + std::to_string(s);
        } else {  // no scenes: every node that is nobody's child
            std::vector<bool> child(model_.nodes.size(), false);
            for (const tinygltf::Node& n : model_.nodes)
                for (int c : n.children)
                    if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
            for (size_t i = 0; i < child.size(); ++i)
                if (!child[i]) roots.push_back(int(i));
        }
        if (scene_extras_.is_object() && scene_extras_.value("planes", json()).is_array())
            for (const json& j : scene_extras_["planes"]) {
                V3 p, n;
                if (j.is_object() && vec3(j.value("point", json()), p) && vec3(j.value("normal", json()), n) &&
                    norm(n) > 0)
                    scene_planes_.push_back({p, n});
            }
        uses_.assign(model_.meshes.size(), 0);
        for (const tinygltf::Node& n : model_.nodes)
            if (n.mesh >= 0 && size_t(n.mesh) < uses_.size())
                uses_[size_t(n.mesh)] += n.extensions.count("EXT_mesh_gpu_instancing") ? 2 : 1;
        visited_.assign(model_.nodes.size(), false);
        locals_.assign(model_.nodes.size(), Affine{});
        for (int r : roots) visit(r, Affine{}, {}, "/scenes/nodes");
        // Area lights whose nodes a pipeline pruned (glTF Transform's prune drops nodes
        // without content): the export's, from the scene's extras, when no node has one.
        if (area_lights_.empty() && scene_extras_.is_object() && scene_extras_.contains("areaLights")) {
            const json& list = scene_extras_["areaLights"];
            const std::string where = extras_at(scene_at_) + "/areaLights";
            if (!list.is_array()) throw InputError(where + ": must be an array");
            for (size_t i = 0; i < list.size(); ++i) {
                if (!list[i].is_object()) throw InputError(where + "/" + std::to_string(i) + ": must be an object");
                ojson o = ojson::object();
                o["_id"] = std::to_string(area_lights_.size() + 1);
                read_extras(kAreaLightExtras, list[i], where + "/" + std::to_string(i), true, o);
                out_.notes.push_back("area light " + o["_id"].get<std::string>() +
                                     ": the exported values, from the scene's extras (no node holds it)");
                extent(list[i]["position"].get<V3>());
                area_lights_.push_back(o);
            }
        }
    }

    // `chain`: the nodes above (and with) this one whose matrices are not the identity,
    // innermost first, the order in which the course applies a Transformations list.
    void visit(int index, const Affine& parent, std::vector<int> chain, const std::string& from, int depth = 0) {
        if (index < 0 || size_t(index) >= model_.nodes.size())
            fail(from, "node " + std::to_string(index) + " does not exist");
        if (depth > kMaxDepth) fail(from, "nodes nested more than " + std::to_string(kMaxDepth) + " deep");
        if (visited_[size_t(index)])
            fail(from, "node " + std::to_string(index) + " is reached twice (a cycle, or two parents)");
        visited_[size_t(index)] = true;
        const tinygltf::Node& n = model_.nodes[size_t(index)];
        const std::string np = "/nodes/" + std::to_string(index);
        locals_[size_t(index)] = local_matrix(n, index);
        const Affine world = parent * locals_[size_t(index)];
        if (!(std::fabs(world.det()) > 0) || !std::isfinite(world.det())) {
            warn(np + ": its transformation is singular or not finite: the node and its children are skipped");
            return;
        }
        if (!locals_[size_t(index)].is_identity()) chain.insert(chain.begin(), index);
        const json extras = ours_in(n.extras);
        if (n.mesh >= 0) {
            if (size_t(n.mesh) >= model_.meshes.size())
                fail(np + "/mesh", "mesh " + std::to_string(n.mesh) + " does not exist");
            ojson motion = ojson::object();  // the objects' own keys: MotionBlur
            read_extras(kMotionExtras, extras, extras_at(np), false, motion);
            if (const auto gi = n.extensions.find("EXT_mesh_gpu_instancing"); gi != n.extensions.end()) {
                // Each instance under its own matrix, innermost: a Composite of its own.
                for (const Affine& local : instances(to_json(gi->second), np)) {
                    const Affine at = world * local;
                    if (!(std::fabs(at.det()) > 0) || !std::isfinite(at.det())) {
                        warn(np +
                             "/extensions/EXT_mesh_gpu_instancing: an instance's transformation is singular or "
                             "not finite: skipped");
                        continue;
                    }
                    std::vector<int> with = chain;
                    if (!local.is_identity()) {
                        locals_.push_back(local);
                        with.insert(with.begin(), int(locals_.size() - 1));
                    }
                    add_mesh(n.mesh, at, with, motion, np);
                }
            } else {
                add_mesh(n.mesh, world, chain, motion, np);
            }
        }
        if (extras.is_object() && extras.contains("areaLight")) add_area_light(extras["areaLight"], np, world);
        if (n.camera >= 0) {
            if (size_t(n.camera) >= model_.cameras.size())
                fail(np + "/camera", "camera " + std::to_string(n.camera) + " does not exist");
            camera_uses_.push_back({n.camera, index, world});
        }
        if (const auto it = n.extensions.find("KHR_lights_punctual"); it != n.extensions.end()) {
            const json l = to_json(it->second);
            if (!l.is_object() || !l.contains("light") || !l["light"].is_number_integer() ||
                l["light"].get<int>() < 0 || size_t(l["light"].get<int>()) >= model_.lights.size())
                fail(np + "/extensions/KHR_lights_punctual", "names no light of the file");
            add_light(l["light"].get<int>(), world);
        }
        for (int c : n.children) visit(c, world, chain, np + "/children", depth + 1);
    }

    // The Transformations list of a chain of nodes: one Composite per node, its local
    // matrix, made when an object first uses it.
    std::string transformations(const std::vector<int>& chain) {
        std::string list;
        for (int node : chain) {
            auto [it, fresh] = composite_of_.emplace(node, transforms_.size() + 1);
            if (fresh) {
                const Affine& m = locals_[size_t(node)];
                std::string data;
                for (int r = 0; r < 4; ++r)
                    for (int k = 0; k < 4; ++k)
                        data += (data.empty() ? "" : " ") + course_number(r < 3 ? m.m[r][k] : (k == 3 ? 1.0 : 0.0));
                ojson c = ojson::object();
                c["_id"] = std::to_string(it->second);
                c["_data"] = data;
                transforms_.push_back(c);
            }
            list += (list.empty() ? "c" : " c") + std::to_string(it->second);
        }
        return list;
    }

    // ---- Meshes, spheres, planes ------------------------------------------------------

    std::string material_ref(int material, const std::string& where) {
        if (material >= 0 && size_t(material) < model_.materials.size()) return std::to_string(material + 1);
        if (material >= 0)
            fail(where + "/material", "material " + std::to_string(material) + " does not exist (the file has " +
                                          std::to_string(model_.materials.size()) + ")");
        needs_default_material_ = true;
        return std::to_string(model_.materials.size() + 1);
    }

    void add_vertex(const V3& p) {
        vertex_data_ += (vertex_data_.empty() ? "" : " ") + course_vec(p);
        ++vertices_;
    }

    // The objects node `np` shows (`own`: the keys each of them takes from the node).
    void add_mesh(int m, const Affine& world, const std::vector<int>& nodes, const ojson& own, const std::string& np) {
        const tinygltf::Mesh& mesh = model_.meshes[size_t(m)];
        const json extras = ours_in(mesh.extras);
        for (size_t p = 0; p < mesh.primitives.size(); ++p) {
            const GltfTriangles* g = primitives_.get(m, int(p));
            if (!g || g->indices.empty()) continue;
            for (int c = 0; c < 8; ++c)  // the corners of its box, moved
                extent(apply(
                    world, {(c & 1 ? g->hi : g->lo)[0], (c & 2 ? g->hi : g->lo)[1], (c & 4 ? g->hi : g->lo)[2]}, true));
            for (const Piece& piece : pieces(m, int(p), *g, world)) {
                if (mesh.primitives.size() == 1 &&
                    as_shape(*piece.triangles, *g, extras, world, nodes, piece.material, own, np))
                    continue;
                // Planes a pipeline joined with other meshes: only where the mesh is shown
                // once, as the export's planes are in world space.
                const GltfTriangles* t = uses_[size_t(m)] == 1
                                             ? without_planes(*piece.triangles, world, piece.material, own, np)
                                             : piece.triangles;
                if (t) add_triangles(*t, piece.material, world, nodes, own);
            }
        }
    }

    // The triangles of primitive p of mesh m (read as `g`), by material: one piece, or a
    // piece per palette texel (gltf_palette.h).
    const std::vector<Piece>& pieces(int m, int p, const GltfTriangles& g, const Affine& world) {
        const int material = model_.meshes[size_t(m)].primitives[size_t(p)].material;
        const std::string ref =
            material_ref(material, "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p));
        // Per primitive: primitives that share their POSITION and indices (one `g`) may have
        // other texture coordinates, so other texels.
        const auto key = std::make_pair(m, p);
        if (const auto it = pieces_.find(key); it != pieces_.end()) return it->second;
        std::vector<Piece>& out = pieces_[key];
        std::vector<PaletteTexel> texels = palettes_.triangle_texels(m, p);
        if (texels.size() == g.indices.size() / 3 && uses_[size_t(m)] == 1) told_apart(texels, g, world);
        if (texels.size() != g.indices.size() / 3) {
            out.push_back({&g, ref});
            return out;
        }
        std::map<PaletteTexel, uint32_t> group_of;  // in the order of first use
        std::vector<uint32_t> groups;
        std::vector<std::string> refs;
        for (const PaletteTexel& t : texels) {
            const auto [it, added] = group_of.emplace(t, uint32_t(group_of.size()));
            groups.push_back(it->second);
            if (!added) continue;
            const auto [at, first] = texel_index_.emplace(t, texels_.size());
            if (first) texels_.push_back(t);
            refs.push_back(std::to_string(model_.materials.size() + 2 + at->second));
        }
        if (refs.size() == 1) {
            out.push_back({&g, refs[0]});
            return out;
        }
        std::vector<GltfTriangles> split = split_triangles(g, groups, refs.size());
        for (size_t i = 0; i < split.size(); ++i) {
            made_.push_back(std::move(split[i]));
            out.push_back({&made_.back(), refs[i]});
        }
        return out;
    }

    // Palette texels that several exported materials tie for (materials that differ only
    // where glTF has no place): the triangles of each part (sharing no vertex with the rest)
    // and texel take the one of them whose objects' boxes (the scene's extras,
    // "materialBoxes", in world space) the smallest contains them all, to within the 14 bits
    // glTF Transform keeps of the primitive's extent; where none does (a pipeline welded
    // objects together), each triangle so. For a primitive shown once (the boxes are the
    // world's).
    void told_apart(std::vector<PaletteTexel>& texels, const GltfTriangles& g, const Affine& world) {
        const json boxes = scene_extras_.is_object() ? scene_extras_.value("materialBoxes", json()) : json();
        if (!boxes.is_object()) return;
        const std::vector<json> exported = exported_materials(scene_extras_);
        std::map<PaletteTexel, std::vector<int>> tied;  // per texel: the tied materials with boxes
        for (const PaletteTexel& t : texels) {
            if (tied.count(t)) continue;
            std::vector<json> listed = exported;
            listed.push_back(ours_in(model_.materials[size_t(t.material)].extras));
            std::vector<int>& with_boxes = tied[t];
            for (int k : texel_matches(model_, t, listed))
                if (size_t(k) < exported.size() && boxes.value(std::to_string(k), json()).is_array())
                    with_boxes.push_back(k);
            if (with_boxes.size() < 2) with_boxes.clear();
        }
        const GltfTriangles at = moved(g, world);
        const double tolerance =
            2e-4 * std::max({at.hi[0] - at.lo[0], at.hi[1] - at.lo[1], at.hi[2] - at.lo[2], 1e-30});
        // The tied material whose smallest box holds `triangles` (indices into texels), or -1.
        auto holder = [&](const std::vector<int>& candidates, const std::vector<size_t>& triangles) {
            V3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
            for (size_t t : triangles)
                for (size_t v = 0; v < 3; ++v)
                    for (size_t c = 0; c < 3; ++c) {
                        const double x = at.positions[3 * size_t(at.indices[3 * t + v]) + c];
                        lo[c] = std::min(lo[c], x);
                        hi[c] = std::max(hi[c], x);
                    }
            double smallest = HUGE_VAL;
            int found = -1;
            for (int k : candidates)
                for (const json& b : boxes[std::to_string(k)]) {
                    if (!b.is_array() || b.size() != 6) continue;
                    bool inside = true;
                    double size = 0;
                    for (size_t c = 0; c < 3; ++c) {
                        if (!b[c].is_number() || !b[c + 3].is_number()) inside = false;
                        if (!inside) break;
                        size += b[c + 3].get<double>() - b[c].get<double>();
                        inside = lo[c] >= b[c].get<double>() - tolerance && hi[c] <= b[c + 3].get<double>() + tolerance;
                    }
                    if (inside && size < smallest) {
                        smallest = size;
                        found = k;
                    }
                }
            return found;
        };
        size_t parts = 0;
        const std::vector<uint32_t> part = part_of_triangles(g, parts);
        std::map<std::pair<uint32_t, PaletteTexel>, std::vector<size_t>> groups;
        for (size_t i = 0; i < texels.size(); ++i)
            if (!tied[texels[i]].empty()) groups[{part[i], texels[i]}].push_back(i);
        for (const auto& [key, triangles] : groups) {
            const std::vector<int>& candidates = tied[key.second];
            if (const int k = holder(candidates, triangles); k >= 0) {
                for (size_t t : triangles) texels[t].listed = k;
                continue;
            }
            for (size_t t : triangles) texels[t].listed = holder(candidates, {t});
        }
    }

    // `g` without the parts (sharing no vertex with the rest) that are the export's planes:
    // the square of two triangles it writes for one (gltf_export.cpp), its corners moved by
    // `world` on the plane of the scene's extras to within the 14 bits glTF Transform keeps
    // (2e-4 of their distance from its point), each added as that plane. nullptr when
    // nothing is left.
    const GltfTriangles* without_planes(const GltfTriangles& g, const Affine& world, const std::string& material,
                                        const ojson& own, const std::string& np) {
        if (scene_planes_.empty()) return &g;
        std::vector<GltfTriangles> parts = connected_parts(g);
        std::vector<uint32_t> group;  // per triangle: 0 kept, 1 a plane
        bool any = false;
        for (const GltfTriangles& part : parts) {
            uint32_t is_plane = 0;
            if (part.positions.size() == 12 && part.indices.size() == 6) {
                const GltfTriangles at = moved(part, world);
                for (const auto& [point, normal] : scene_planes_)
                    if (on_plane(at, point, normal, 2e-4)) {
                        add_plane(point, normal, material, "", own, np);
                        is_plane = 1;
                        any = true;
                        break;
                    }
            }
            group.insert(group.end(), part.indices.size() / 3, is_plane);
        }
        if (!any) return &g;
        // The kept parts, in one list of triangles (connected_parts' order).
        GltfTriangles joined;
        joined.smooth = g.smooth;
        for (size_t i = 0, t = 0; i < parts.size(); t += parts[i].indices.size() / 3, ++i) {
            if (group[t]) continue;
            const uint32_t base = uint32_t(joined.positions.size() / 3);
            joined.positions.insert(joined.positions.end(), parts[i].positions.begin(), parts[i].positions.end());
            for (uint32_t v : parts[i].indices) joined.indices.push_back(base + v);
            for (size_t k = 0; k < 3; ++k) {
                joined.lo[k] = std::min(joined.lo[k], parts[i].lo[k]);
                joined.hi[k] = std::max(joined.hi[k], parts[i].hi[k]);
            }
        }
        if (joined.indices.empty()) return nullptr;
        made_.push_back(std::move(joined));
        return &made_.back();
    }

    // A Mesh of `g`, or a MeshInstance of the Mesh its first use made.
    void add_triangles(const GltfTriangles& g, const std::string& material, const Affine& world,
                       const std::vector<int>& nodes, const ojson& own) {
        ojson o = ojson::object();
        if (options_.bake_transforms) {
            ImportedMesh baked;
            baked.ply_name = ply_prefix_ + "_" + std::to_string(out_.meshes.size() + 1) + ".ply";
            for (size_t i = 0; i < g.positions.size(); i += 3) {
                const V3 q = apply(world, {g.positions[i], g.positions[i + 1], g.positions[i + 2]}, true);
                baked.positions.insert(baked.positions.end(), q.begin(), q.end());
            }
            baked.indices = g.indices;
            if (world.det() < 0)  // keep the outside outside (rt/shapes/shape.h, Polygons::move)
                for (size_t i = 0; i < baked.indices.size(); i += 3)
                    std::swap(baked.indices[i + 1], baked.indices[i + 2]);
            o["_id"] = std::to_string(++object_ids_);
            o["_shadingMode"] = g.smooth ? "smooth" : "flat";
            o["Material"] = material;
            o["Faces"] = {{"_plyFile", baked.ply_name}};
            o.update(own);
            out_.meshes.push_back(std::move(baked));
            mesh_objects_.push_back(o);
            return;
        }
        const std::string chain = transformations(nodes);
        o["_id"] = std::to_string(++object_ids_);
        FirstUse& first = first_use_[&g];
        if (first.base < 0) {  // its first use: the mesh itself
            first.base = object_ids_;
            first.ply = out_.meshes.size();
            ImportedMesh im;
            im.ply_name = ply_prefix_ + "_" + std::to_string(out_.meshes.size() + 1) + ".ply";
            im.positions = g.positions;
            im.indices = g.indices;
            out_.meshes.push_back(std::move(im));
            o["_shadingMode"] = g.smooth ? "smooth" : "flat";
            o["Material"] = material;
            if (!chain.empty()) o["Transformations"] = chain;
            o["Faces"] = {{"_plyFile", out_.meshes[first.ply].ply_name}};
            o.update(own);
            mesh_objects_.push_back(o);
        } else {  // another use: an instance of the first, under its own matrix
            o["_baseMeshId"] = std::to_string(first.base);
            o["_resetTransform"] = "true";
            o["Material"] = material;
            if (!chain.empty()) o["Transformations"] = chain;
            o.update(own);
            instance_objects_.push_back(o);
        }
    }

    // A tessellated sphere or plane of the export, back as itself while its vertices are
    // still on it (docs/gltf.md).
    bool as_shape(const GltfTriangles& g, const GltfTriangles& whole, const json& extras, const Affine& world,
                  const std::vector<int>& nodes, const std::string& material, const ojson& own, const std::string& np) {
        if (!extras.is_object()) return false;
        const size_t n = g.positions.size() / 3;
        if (extras.contains("sphere") && n >= 4) {
            const json& s = extras["sphere"];
            V3 c;
            double r;
            if (!s.is_object() || !vec3(s.value("center", json()), c) || !number(s.value("radius", json()), r, 1e-30))
                return false;
            std::vector<std::pair<V3, double>> spheres;
            bool in_world = false;  // spheres in world space, under no transformation
            if (on_sphere(g, c, r, 1e-4)) {
                spheres.push_back({c, r});
            } else {
                const double extent =
                    std::max({whole.hi[0] - whole.lo[0], whole.hi[1] - whole.lo[1], whole.hi[2] - whole.lo[2]}) / 2;
                spheres = quantised_spheres(g, extent);
                if (spheres.empty()) {
                    // Joined under a node whose matrix is not a uniform scaling (optimize's
                    // flatten and join): spheres in world space, where a step is as long as
                    // the matrix's longest axis makes it.
                    double stretch = 0;
                    for (int k = 0; k < 3; ++k)
                        stretch = std::max(stretch, norm({world.m[0][k], world.m[1][k], world.m[2][k]}));
                    const GltfTriangles at = moved(g, world);
                    if (!world.is_identity()) spheres = quantised_spheres(at, extent * stretch);
                    in_world = true;
                    // Spheres flattened from under a non-uniform scaling: ellipsoids, each a
                    // unit sphere under the map onto it.
                    if (spheres.empty()) {
                        const std::vector<Affine> ellipsoids = quantised_ellipsoids(at, extent * stretch);
                        for (const Affine& e : ellipsoids) {
                            locals_.push_back(e);
                            add_sphere({0, 0, 0}, 1, material, transformations({int(locals_.size() - 1)}), own);
                        }
                        return !ellipsoids.empty();
                    }
                }
            }
            if (spheres.empty()) return false;
            const std::string chain = in_world ? "" : transformations(nodes);
            for (const auto& [centre, radius] : spheres) add_sphere(centre, radius, material, chain, own);
            return true;
        }
        if (extras.contains("plane") && n >= 3) {
            const json& s = extras["plane"];
            V3 p, nrm;
            if (!s.is_object() || !vec3(s.value("point", json()), p) || !vec3(s.value("normal", json()), nrm))
                return false;
            const double len = norm(nrm);
            if (!(len > 0)) return false;
            // Quantised (up to half a 14-bit step of the quad's size) with the node undoing
            // it, still on the export's plane, which is in world space: that plane, exactly.
            if (!on_plane(g, p, nrm, 1e-5) && !world.is_identity() && on_plane(moved(g, world), p, nrm, 2e-4)) {
                add_plane(p, nrm, material, "", own, np);
                return true;
            }
            if (!on_plane(g, p, nrm, 1e-5)) {
                // Quantised, and its node moved since: the plane of the extras' normal
                // through the vertices' centroid, while they lie on it to within the 14 bits
                // kept, under the node's transformation.
                p = {0, 0, 0};
                for (size_t i = 0; i < n; ++i)
                    for (size_t k = 0; k < 3; ++k) p[k] += g.positions[3 * i + k] / double(n);
                if (!on_plane(g, p, nrm, 2e-4)) return false;
            }
            std::string chain;
            if (options_.bake_transforms && !world.is_identity()) {  // a moved plane is a plane
                const Affine inv_t = world.inverse();
                p = apply(world, p, true);
                V3 t;  // the normal by the inverse transpose
                for (int r = 0; r < 3; ++r)
                    t[size_t(r)] = inv_t.m[0][r] * nrm[0] + inv_t.m[1][r] * nrm[1] + inv_t.m[2][r] * nrm[2];
                nrm = t;
            } else if (!nodes.empty()) {
                chain = transformations(nodes);
            }
            add_plane(p, nrm, material, chain, own, np);
            return true;
        }
        return false;
    }

    // A Sphere under the Transformations `chain` (none: ""), with the keys `own` of its node.
    void add_sphere(const V3& centre, double radius, const std::string& material, const std::string& chain,
                    const ojson& own) {
        ojson o = ojson::object();
        o["_id"] = std::to_string(sphere_objects_.size() + 1);
        o["Material"] = material;
        add_vertex(centre);
        o["Center"] = std::to_string(vertices_);
        o["Radius"] = course_number(radius);
        if (!chain.empty()) o["Transformations"] = chain;
        o.update(own);
        sphere_objects_.push_back(o);
    }

    // A Plane under the Transformations `chain` (none: ""); `own` the keys node `np` gives
    // its objects (a MotionBlur, which a plane cannot take).
    void add_plane(const V3& p, const V3& nrm, const std::string& material, const std::string& chain, const ojson& own,
                   const std::string& np) {
        ojson o = ojson::object();
        o["_id"] = std::to_string(plane_objects_.size() + 1);
        o["Material"] = material;
        if (!chain.empty()) o["Transformations"] = chain;
        add_vertex(p);
        o["Point"] = std::to_string(vertices_);
        o["Normal"] = course_vec(nrm);
        if (!own.empty())
            warn(np + "/extras/" + kGltfExtrasKey + "/motionBlur: a plane does not move in the format: left out");
        plane_objects_.push_back(o);
    }

    void extent(const V3& p) {
        for (size_t k = 0; k < 3; ++k) {
            lo_[k] = std::min(lo_[k], p[k]);
            hi_[k] = std::max(hi_[k], p[k]);
        }
    }

    // ---- Lights, cameras, settings, materials ---------------------------------------------

    void add_light(int index, const Affine& world) {
        const tinygltf::Light& l = model_.lights[size_t(index)];
        const std::string lp = "/extensions/KHR_lights_punctual/lights/" + std::to_string(index);
        if (l.type != "point") {
            warn(lp + ": a " + l.type + " light: only point lights are in the format; skipped");
            return;
        }
        V3 tint{1, 1, 1};
        if (l.color.size() == 3) tint = {l.color[0], l.color[1], l.color[2]};
        V3 intensity;
        for (size_t k = 0; k < 3; ++k) {
            intensity[k] = tint[k] * l.intensity * options_.light_scale;
            if (!(intensity[k] >= 0 && intensity[k] <= kMaxMagnitude))
                fail(lp, "its color times its intensity (times --light-scale) must be a number from 0 to 1e30");
        }
        // The export's exact intensity, while the light still gives it.
        const json extras = ours_in(l.extras);
        V3 exact;
        if (extras.is_object() && colour(extras.value("intensity", json()), exact)) {
            bool same = true;
            const double peak = std::max({exact[0], exact[1], exact[2], 1e-300});
            for (size_t k = 0; k < 3; ++k) same = same && std::fabs(exact[k] - intensity[k]) <= 1e-4 * peak;
            if (same) intensity = exact;
        }
        if (l.range > 0) warn(lp + ": its range is not in the format: the light reaches everywhere");
        ojson o = ojson::object();
        o["_id"] = std::to_string(lights_.size() + 1);
        o["Position"] = course_vec(apply(world, {0, 0, 0}, true));
        o["Intensity"] = course_vec(intensity);
        lights_.push_back(o);
        extent(apply(world, {0, 0, 0}, true));
    }

    // An area light's node (docs/gltf.md): its values from its extras, its place from the
    // extras while the node still puts it there (origin, -z axis, the side of the square its
    // x and y axes span), else from the node.
    void add_area_light(const json& e, const std::string& np, const Affine& world) {
        const std::string where = extras_at(np) + "/areaLight";
        if (!e.is_object()) throw InputError(where + ": must be an object");
        ojson o = ojson::object();
        o["_id"] = std::to_string(area_lights_.size() + 1);
        read_extras(kAreaLightExtras, e, where, true, o);
        const V3 origin = apply(world, {0, 0, 0}, true), axis = apply(world, {0, 0, -1}, false),
                 x = apply(world, {1, 0, 0}, false), y = apply(world, {0, 1, 0}, false);
        const double side =
            std::sqrt(norm({x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]}));
        const V3 p = e["position"].get<V3>(), n = e["normal"].get<V3>();  // checked above
        const double size = e["size"].get<double>();
        const double cos_n = (n[0] * axis[0] + n[1] * axis[1] + n[2] * axis[2]) / (norm(n) * norm(axis));
        const bool placed = norm(sub(p, origin)) <= 1e-5 * std::max(1.0, norm(p)) && cos_n > 1 - 1e-8 &&
                            std::fabs(side - size) <= 1e-5 * size;
        if (!placed) {
            o["Position"] = course_vec(origin);
            o["Normal"] = course_vec({axis[0] / norm(axis), axis[1] / norm(axis), axis[2] / norm(axis)});
            o["Size"] = course_number(side);
        }
        out_.notes.push_back("area light " + o["_id"].get<std::string>() + ": " +
                             (placed ? "the exported values" : "placed by its node " + np));
        area_lights_.push_back(o);
        extent(origin);
    }

    bool bounds_empty() const { return !(lo_[0] <= hi_[0]); }

    ModelFrame frame(int width, int height, const std::string& image) const {
        return bounds_empty() ? frame_model({-1, -1, -1}, {1, 1, 1}, width, height, image)
                              : frame_model(lo_, hi_, width, height, image);
    }

    std::string image_name(size_t k, size_t count) const {
        if (!options_.image_name.empty() && count == 1) return options_.image_name;
        return image_stem_ + (count == 1 ? "" : "_" + std::to_string(k)) + ".png";
    }

    ojson cameras() {
        // The first node of each camera, in the order of the file's cameras.
        std::map<int, const CameraUse*> first;
        for (const CameraUse& u : camera_uses_) first.emplace(u.camera, &u);
        for (size_t i = 0; i < model_.cameras.size(); ++i)
            if (!first.count(int(i))) warn("/cameras/" + std::to_string(i) + ": no node places it: skipped");
        std::vector<const CameraUse*> chosen;
        if (options_.camera == 0) {
            for (const auto& [c, u] : first) chosen.push_back(u);
        } else if (!model_.cameras.empty()) {
            const int c = options_.camera - 1;
            if (size_t(c) >= model_.cameras.size())
                fail("/cameras", "--camera " + std::to_string(options_.camera) + ": the file has " +
                                     count_of(model_.cameras.size(), "camera"));
            if (!first.count(c)) fail("/cameras/" + std::to_string(c), "no node places this camera");
            chosen.push_back(first[c]);
        }
        ojson list = ojson::array();
        for (const CameraUse* u : chosen) {
            ojson cam = camera(*u, chosen.size());
            if (!cam.is_null()) list.push_back(cam);
        }
        if (list.empty()) {
            if (!model_.cameras.empty()) warn("no perspective camera: a camera framing the model is used");
            ojson cam = frame(options_.width, options_.height, image_name(1, 1)).camera;
            out_.notes.push_back("camera: framing the model (the file has none)");
            list.push_back(cam);
        }
        for (size_t i = 0; i < list.size(); ++i) list[i]["_id"] = std::to_string(i + 1);
        return list;
    }

    ojson camera(const CameraUse& u, size_t count) {
        const tinygltf::Camera& c = model_.cameras[size_t(u.camera)];
        const std::string cp = "/cameras/" + std::to_string(u.camera);
        if (c.type != "perspective") {
            warn(cp + ": a " + c.type + " camera: only perspective cameras are in the format; skipped");
            return nullptr;
        }
        const double yfov = c.perspective.yfov;
        if (!(yfov > 0 && yfov < pi_v<double>)) fail(cp + "/perspective/yfov", "must be between 0 and pi");
        V3 pos = apply(u.world, {0, 0, 0}, true), gaze = apply(u.world, {0, 0, -1}, false),
           up = apply(u.world, {0, 1, 0}, false);
        const double gl = norm(gaze), ul = norm(up);
        for (size_t k = 0; k < 3; ++k) gaze[k] /= gl, up[k] /= ul;
        int width = options_.width, height = options_.height;
        const double aspect = c.perspective.aspectRatio;
        if (!options_.size_given && aspect > 0) {
            height = 600;
            width = std::max(1, int(std::lround(600 * aspect)));
        } else if (options_.size_given && aspect > 0 && std::fabs(aspect - double(width) / height) > 1e-3 * aspect) {
            warn(cp + ": aspect ratio " + course_number(aspect) +
                 " differs from --size: the vertical field of view is kept");
        }
        const double top = std::tan(yfov / 2), right = top * double(width) / double(height);
        std::string name = image_name(size_t(u.camera) + 1, count);
        std::array<double, 4> plane{-right, right, -top, top};
        double distance = 1;
        // The export's exact camera, while the node still places it there.
        const json extras = ours_in(model_.nodes[size_t(u.node)].extras);
        const json e = extras.is_object() ? extras.value("camera", json()) : json();
        V3 ep, eg, eu;
        std::array<double, 4> ep4;
        double ed, ew, eh;
        const json none;
        const json& np = e.is_object() ? e.value("nearPlane", none) : none;
        const json& er = e.is_object() ? e.value("imageResolution", none) : none;
        if (e.is_object() && vec3(e.value("position", none), ep) && vec3(e.value("gaze", none), eg) &&
            vec3(e.value("up", none), eu) && norm(eg) > 0 && norm(eu) > 0 && np.is_array() && np.size() == 4 &&
            number(np[0], ep4[0]) && number(np[1], ep4[1]) && number(np[2], ep4[2]) && number(np[3], ep4[3]) &&
            ep4[0] < ep4[1] && ep4[2] < ep4[3] && number(e.value("nearDistance", none), ed, 1e-30) && er.is_array() &&
            er.size() == 2 && er[0].is_number_integer() && er[1].is_number_integer() && number(er[0], ew, 1, 16384) &&
            number(er[1], eh, 1, 16384) && e.value("imageName", none).is_string() &&
            !e["imageName"].get<std::string>().empty()) {
            const double scale = std::max(1.0, norm(ep));
            const double eg_len = norm(eg), eu_len = norm(eu);
            const double cos_g = (eg[0] * gaze[0] + eg[1] * gaze[1] + eg[2] * gaze[2]) / eg_len;
            const double eyfov = std::atan(ep4[3] / ed) - std::atan(ep4[2] / ed);
            // The up vector only has to lie in the same half-plane about the gaze.
            const double cos_u = (eu[0] * up[0] + eu[1] * up[1] + eu[2] * up[2]) / eu_len;
            if (norm(sub(ep, pos)) <= 1e-5 * scale && cos_g > 1 - 1e-8 && cos_u > 0 &&
                std::fabs(eyfov - yfov) <= 1e-5 * yfov && !options_.size_given) {
                pos = ep, gaze = eg, up = eu;
                plane = ep4;
                distance = ed;
                width = int(ew);
                height = int(eh);
                if (options_.image_name.empty()) name = e["imageName"].get<std::string>();
            }
        }
        extent(pos);
        ojson o = ojson::object();
        o["_id"] = "0";
        o["Position"] = course_vec(pos);
        o["Gaze"] = course_vec(gaze);
        o["Up"] = course_vec(up);
        o["NearPlane"] = course_number(plane[0]) + " " + course_number(plane[1]) + " " + course_number(plane[2]) + " " +
                         course_number(plane[3]);
        o["NearDistance"] = course_number(distance);
        o["ImageResolution"] = std::to_string(width) + " " + std::to_string(height);
        o["ImageName"] = name;
        // Its samples and lens, which glTF has no place for.
        const json lens = ours_in(c.extras);
        read_extras(kCameraExtras, lens, extras_at(cp), false, o);
        if (o.contains("ApertureSize") && lens.at("apertureSize").get<double>() > 0 && !o.contains("FocusDistance"))
            fail(cp + "/extras/" + kGltfExtrasKey + "/apertureSize", "a lens (above 0) needs a focusDistance");
        out_.notes.push_back("camera " + std::to_string(u.camera + 1) + " (" + (c.name.empty() ? "unnamed" : c.name) +
                             ") -> " + std::to_string(width) + "x" + std::to_string(height) + " " + name);
        return o;
    }

    ojson lights() {
        ojson l = ojson::object();
        V3 ambient{0, 0, 0};
        const bool have_ambient =
            scene_extras_.is_object() && colour(scene_extras_.value("ambientLight", json()), ambient);
        if (lights_.empty() && area_lights_.empty()) {
            l = frame(options_.width, options_.height, "").lights;
            if (have_ambient) l["AmbientLight"] = course_vec(ambient);
            out_.notes.push_back("lights: the default lights (the file has no point light)");
            return l;
        }
        l["AmbientLight"] = course_vec(ambient);
        if (!lights_.empty()) l["PointLight"] = lights_;
        if (!area_lights_.empty()) l["AreaLight"] = area_lights_;
        return l;
    }

    void scene_settings(ojson& scene) {
        const json& e = scene_extras_;
        const json none;
        V3 background{40, 44, 56};
        if (e.is_object()) colour(e.value("backgroundColor", none), background);
        scene["BackgroundColor"] = course_vec(background);
        const double radius = bounds_empty() ? 1.0 : frame(1, 1, "").radius;
        double shadow = 1e-4 * radius, intersection;
        if (e.is_object()) number(e.value("shadowRayEpsilon", none), shadow, 0);
        scene["ShadowRayEpsilon"] = course_number(shadow);
        if (e.is_object() && number(e.value("intersectionTestEpsilon", none), intersection, 0))
            scene["IntersectionTestEpsilon"] = course_number(intersection);
        double depth = 6;
        if (e.is_object() && e.value("maxRecursionDepth", none).is_number_integer())
            number(e["maxRecursionDepth"], depth, 0, kMaxRecursionDepth);
        scene["MaxRecursionDepth"] = std::to_string(int(depth));
    }

    const std::string& path_;
    const tinygltf::Model& model_;
    const ConvertOptions& options_;
    const std::string ply_prefix_, image_stem_;
    SceneImport& out_;

    GltfPrimitives primitives_;
    GltfPalettes palettes_{model_, primitives_, path_, out_.warnings};
    std::map<const GltfTriangles*, FirstUse> first_use_;
    // A primitive's triangles drawn with each material (one, or a palette's: gltf_palette.h),
    // per primitive (mesh, index); triangles made here, at stable addresses.
    std::map<std::pair<int, int>, std::vector<Piece>> pieces_;
    std::deque<GltfTriangles> made_;
    std::vector<PaletteTexel> texels_;  // the palette texels' materials, in _id order
    std::map<PaletteTexel, size_t> texel_index_;
    std::vector<int> uses_;                        // the nodes (or GPU instances: 2) showing each mesh
    std::vector<std::pair<V3, V3>> scene_planes_;  // the export's planes (point, normal)
    std::string scene_at_ = "/scenes/0";
    std::vector<bool> visited_;
    std::vector<Affine> locals_;          // each node's own matrix, then each GPU instance's
    std::map<int, size_t> composite_of_;  // node -> its Composite's _id
    std::vector<CameraUse> camera_uses_;
    json scene_extras_;
    ojson transforms_ = ojson::array(), mesh_objects_ = ojson::array(), instance_objects_ = ojson::array(),
          sphere_objects_ = ojson::array(), plane_objects_ = ojson::array(), lights_ = ojson::array(),
          area_lights_ = ojson::array();
    std::string vertex_data_;
    size_t vertices_ = 0;
    int object_ids_ = 0;  // Mesh and MeshInstance share one id space
    bool needs_default_material_ = false;
    V3 lo_{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi_{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
};

}  // namespace

SceneImport import_gltf_bytes(const std::string& bytes, const std::string& path, const ConvertOptions& options,
                              const std::string& ply_prefix) {
    SceneImport out;
    tinygltf::Model model;
    const std::string dir = dirname_of(path);
    try {
        rtgltf::parse(bytes, path, dir.empty() ? "." : dir, model, out.warnings);
    } catch (const rtgltf::Error& e) {
        throw InputError(e.what());
    }
    Importer(path, model, options, ply_prefix, ply_prefix, out).run();
    return out;
}
#else
SceneImport import_gltf_bytes(const std::string&, const std::string& path, const ConvertOptions&, const std::string&) {
    throw InputError(path + ": glTF is not supported by this build (it was made without tinygltf, libtinygltf-dev)");
}
#endif  // RT_NO_GLTF

SceneImport import_gltf(const std::string& path, const ConvertOptions& options, const std::string& ply_prefix) {
    return import_gltf_bytes(read_text_file(path), path, options, ply_prefix);
}

std::string gltf_to_json_text(const std::string& gltf_bytes, const std::string& path, const ConvertOptions& options) {
    return import_gltf_bytes(gltf_bytes, path, options, "mesh").scene.dump(2) + "\n";
}

}  // namespace rt
