// The scene tree (rt/loader/scene_tree.h) -> SceneDesc. Every reference (material ids,
// vertex ids, transformations, base meshes) is resolved and range-checked here, once;
// errors name the file and the JSON pointer of the offending value (json_fields.h).
// PLY files are named here and read afterwards (mesh_files.cpp), once the tree can be
// released.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "json_fields.h"
#include "rt/core/affine.h"
#include "rt/io/files.h"
#include "rt/loader/scene_tree.h"

namespace rt {
namespace {

using nlohmann::json;

// Largest image we agree to allocate (refused before allocating).
constexpr long long kMaxPixels = 1LL << 28;

class Loader : JsonFields {
public:
    Loader(const std::string& path, SceneDesc& out, PlyCache* meshes)
        : JsonFields(path), dir_(dirname_of(path)), out_(out), meshes_(meshes) {}

    void load(const json& root) {
        if (!root.is_object()) fail("", std::string("expected a JSON object at the top, got ") + type_name(root));
        check_keys(root, "", {"Scene"});
        const json& scene = require(root, "", "Scene");
        const std::string sp = "/Scene";
        expect_object(scene, sp);
        check_keys(scene, sp,
                   {"BackgroundColor", "ShadowRayEpsilon", "IntersectionTestEpsilon", "MaxRecursionDepth", "Cameras",
                    "Lights", "Materials", "Transformations", "VertexData", "Objects"});

        if (const json* v = find(scene, "BackgroundColor")) out_.background = color(*v, sp + "/BackgroundColor");
        if (const json* v = find(scene, "ShadowRayEpsilon"))
            out_.shadow_ray_epsilon = non_negative(*v, sp + "/ShadowRayEpsilon");
        if (const json* v = find(scene, "IntersectionTestEpsilon"))
            out_.intersection_test_epsilon = non_negative(*v, sp + "/IntersectionTestEpsilon");
        if (const json* v = find(scene, "MaxRecursionDepth")) {
            const long long d = integer(*v, sp + "/MaxRecursionDepth");
            if (d < 0 || d > kMaxRecursionDepth)
                fail(sp + "/MaxRecursionDepth", "must be between 0 and " + std::to_string(kMaxRecursionDepth));
            out_.max_recursion_depth = static_cast<int>(d);
        }

        load_vertices(scene, sp);
        load_transformations(scene, sp);
        load_materials(scene, sp);
        load_cameras(scene, sp);
        load_lights(scene, sp);
        load_objects(scene, sp);

        for (std::string& w : warnings()) out_.warnings.push_back(std::move(w));
    }

private:
    std::string dir_;
    SceneDesc& out_;
    PlyCache* meshes_;                                        // an animation's shared meshes, or null
    std::vector<Vec3> vertices_;                              // VertexData, 0-based
    std::unordered_map<std::string, uint32_t> material_ids_;  // _id -> index
    std::unordered_map<std::string, Affine> transforms_;      // "t2", "s1", "r3", "c1" -> its matrix

    // A 1-based id into a list of `count` items; returns the 0-based index.
    uint32_t vertex_id(double d, const std::string& path) const {
        if (d != std::floor(d)) fail(path, "vertex id must be an integer");
        if (d < 1 || d > static_cast<double>(vertices_.size()))
            fail(path, "vertex id " + format_number(d) + " out of range (VertexData has " +
                           std::to_string(vertices_.size()) + " vertices)");
        return static_cast<uint32_t>(d) - 1;
    }

    // The VertexData entry a one-id key (Center, Point) names.
    const Vec3& vertex_ref(const json& obj, const std::string& path, const char* key) const {
        const std::string kp = path + "/" + key;
        return vertices_[vertex_id(exactly(require(obj, path, key), kp, 1)[0], kp)];
    }

    uint32_t material_ref(const json& obj, const std::string& path) const {
        const json& v = require(obj, path, "Material");
        const std::string mp = path + "/Material";
        const long long id = integer(v, mp);
        auto it = material_ids_.find(std::to_string(id));
        if (it == material_ids_.end())
            fail(mp, "material id " + std::to_string(id) + " does not exist (" + std::to_string(material_ids_.size()) +
                         (material_ids_.size() == 1 ? " material" : " materials") + " defined)");
        return it->second;
    }

    // --- sections -------------------------------------------------------------

    void load_vertices(const json& scene, const std::string& sp) {
        const json* v = find(scene, "VertexData");
        if (!v || v->is_null()) return;
        std::string path = sp + "/VertexData";
        const json* data = v;
        if (v->is_object()) {
            check_keys(*v, path, {"_data", "_type"});
            if (const json* t = find(*v, "_type"); t && text(*t, path + "/_type") != "xyz")
                fail(path + "/_type", "unsupported vertex data type '" + t->get<std::string>() + "'");
            data = &require(*v, path, "_data");
            path += "/_data";
        }
        const std::vector<double> xs = numbers(*data, path);
        if (xs.size() % 3 != 0) fail(path, "expected x y z triples, got " + std::to_string(xs.size()) + " numbers");
        vertices_.resize(xs.size() / 3);
        for (size_t i = 0; i < vertices_.size(); ++i)
            vertices_[i] = {static_cast<Real>(xs[3 * i]), static_cast<Real>(xs[3 * i + 1]),
                            static_cast<Real>(xs[3 * i + 2])};
    }

    // Scene/Transformations: Translation "tx ty tz", Scaling "sx sy sz", Rotation
    // "degrees ax ay az", Composite (16 numbers, a row-major 4x4 matrix), each one object or
    // an array, named by their letter and _id ("t2") where objects refer to them
    // (docs/transformations.md).
    void load_transformations(const json& scene, const std::string& sp) {
        const json* ts = find(scene, "Transformations");
        const std::string path = sp + "/Transformations";
        if (!ts || ts->is_null()) return;
        expect_object(*ts, path);
        static constexpr const char* kKinds[] = {"Translation", "Scaling", "Rotation", "Composite"};
        check_keys(*ts, path, kKinds);
        for (const char* kind : kKinds) {
            const char letter = static_cast<char>(std::tolower(static_cast<unsigned char>(kind[0])));
            size_t position = 0;
            for_each_item(*ts, path, kind, [&](const json& t, const std::string& tp) {
                check_keys(t, path + "/" + kind, {"_id", "_data"});
                ++position;
                const std::string id =
                    find(t, "_id") ? std::to_string(integer(*find(t, "_id"), tp + "/_id")) : std::to_string(position);
                const std::string dp = tp + "/_data";
                const json& data = require(t, tp, "_data");
                Affine a;
                if (letter == 't') {
                    const std::vector<double> v = exactly(data, dp, 3);
                    a = Affine::translation(v[0], v[1], v[2]);
                } else if (letter == 's') {
                    const std::vector<double> v = exactly(data, dp, 3);
                    if (v[0] == 0 || v[1] == 0 || v[2] == 0) fail(dp, "a scaling factor is zero");
                    a = Affine::scaling(v[0], v[1], v[2]);
                } else if (letter == 'r') {
                    const std::vector<double> v = exactly(data, dp, 4);
                    if (v[1] == 0 && v[2] == 0 && v[3] == 0) fail(dp, "the rotation axis is the zero vector");
                    a = Affine::rotation(v[0], v[1], v[2], v[3]);
                } else {
                    const std::vector<double> v = exactly(data, dp, 16);
                    if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
                        fail(dp, "the last row of a composite transformation must be 0 0 0 1");
                    a = Affine::rows(v.data());
                    if (!(std::fabs(a.det()) > 0)) fail(dp, "the composite transformation is singular");
                }
                if (!transforms_.emplace(std::string(1, letter) + id, a).second)
                    fail(tp + "/_id", std::string("duplicate ") + kind + " id " + id);
            });
        }
    }

    // An entry's MotionBlur, three finite numbers; zero when it has none.
    Vec3 motion_ref(const json& obj, const std::string& path) const {
        const json* v = find(obj, "MotionBlur");
        return v ? vec3(*v, path + "/MotionBlur") : Vec3{};
    }

    // An entry's Transformations ("t2 s3 r1": applied in the order written, the first
    // to the object as written), composed into one matrix; nullopt when it has none.
    std::optional<Affine> transform_ref(const json& obj, const std::string& path) const {
        const json* v = find(obj, "Transformations");
        if (!v || v->is_null()) return std::nullopt;
        const std::string tp = path + "/Transformations";
        std::istringstream words(text(*v, tp));
        Affine m;
        std::string w;
        while (words >> w) {
            auto it = transforms_.find(w);
            if (it == transforms_.end()) {
                const bool form = w.size() > 1 && std::strchr("tsrc", w[0]) &&
                                  std::all_of(w.begin() + 1, w.end(),
                                              [](char c) { return std::isdigit(static_cast<unsigned char>(c)); });
                fail(tp, form ? "transformation '" + w + "' does not exist (Scene/Transformations defines no " +
                                    transform_kind(w[0]) + " with _id " + w.substr(1) + ")"
                              : "'" + w +
                                    "' is not a transformation reference (a letter t, s, r or c and an _id, as in t1)");
            }
            m = it->second * m;
        }
        return m;
    }

    static const char* transform_kind(char letter) {
        switch (letter) {
            case 't':
                return "Translation";
            case 's':
                return "Scaling";
            case 'r':
                return "Rotation";
            default:
                return "Composite";
        }
    }

    // What a kind's read() (rt/shapes/shape.h, rt/materials/material.h) asks for, by
    // key, with the loader's checks and messages.
    struct FieldReader {
        const Loader& l;
        const json& obj;
        const std::string& path;
        Vec3 vertex(const char* key) const { return l.vertex_ref(obj, path, key); }
        Real positive(const char* key) const { return l.positive(l.require(obj, path, key), path + "/" + key); }
        Real non_negative(const char* key) const { return l.non_negative(l.require(obj, path, key), path + "/" + key); }
        Vec3 nonzero_vec3(const char* key) const { return l.nonzero_vec3(l.require(obj, path, key), path + "/" + key); }
        Vec3 color(const char* key) const { return l.color(l.require(obj, path, key), path + "/" + key); }
        Vec3 color_or(const char* key, Vec3 fallback) const {
            const json* v = l.find(obj, key);
            return v ? l.color(*v, path + "/" + key) : fallback;
        }
        Real non_negative_or(const char* key, Real fallback) const {
            const json* v = l.find(obj, key);
            return v ? l.non_negative(*v, path + "/" + key) : fallback;
        }
    };

    void load_materials(const json& scene, const std::string& sp) {
        const json* ms = find(scene, "Materials");
        const std::string path = sp + "/Materials";
        if (!ms || ms->is_null()) return;
        expect_object(*ms, path);
        check_keys(*ms, path, {"Material"});
        const std::string generic = path + "/Material";
        // The keys every kind shares, then each kind's own (rt/loader/material_desc.h);
        // the _type words, for the message.
        std::vector<const char*> keys = {
            "_id", "_type", "AmbientReflectance", "DiffuseReflectance", "SpecularReflectance", "PhongExponent"};
        std::string words;
        for_each_material_format([&](auto k) {
            using M = decltype(k);
            for (const char* key : M::kKeys)
                if (std::none_of(keys.begin(), keys.end(), [&](const char* x) { return std::strcmp(x, key) == 0; }))
                    keys.push_back(key);
            if (M::kTypeWord) words += std::string(words.empty() ? "" : ", ") + M::kTypeWord;
        });
        if (const size_t last = words.rfind(", "); last != std::string::npos) words.replace(last, 2, " or ");
        for_each_item(*ms, path, "Material", [&](const json& m, const std::string& mp) {
            check_keys(m, generic, keys);
            MaterialDesc d;
            d.type = MaterialType::Plain;
            if (const json* t = find(m, "_type")) {
                const std::string& ty = text(*t, mp + "/_type");
                bool known = false;
                for_each_material_format([&](auto k) {
                    using M = decltype(k);
                    if (M::kTypeWord && ty == M::kTypeWord) {
                        d.type = material_type_of_format<M>;
                        known = true;
                    }
                });
                if (!known) fail(mp + "/_type", "unknown material type '" + ty + "' (expected " + words + ")");
            }
            // Each Blinn-Phong coefficient is 0 0 0 when absent (spec 3: a material "can be
            // defined with" them; a matte wall needs no specular term).
            if (const json* v = find(m, "AmbientReflectance")) d.ambient = color(*v, mp + "/AmbientReflectance");
            if (const json* v = find(m, "DiffuseReflectance")) d.diffuse = color(*v, mp + "/DiffuseReflectance");
            if (const json* v = find(m, "SpecularReflectance")) d.specular = color(*v, mp + "/SpecularReflectance");
            if (const json* v = find(m, "PhongExponent")) d.phong_exponent = non_negative(*v, mp + "/PhongExponent");
            FieldReader r{*this, m, mp};
            visit_material_format<void>(d.type, [&](auto k) { decltype(k)::read(r, d); });
            std::string id = std::to_string(out_.materials.size() + 1);
            if (const json* v = find(m, "_id")) id = std::to_string(integer(*v, mp + "/_id"));
            if (!material_ids_.emplace(id, static_cast<uint32_t>(out_.materials.size())).second)
                fail(mp + "/_id", "duplicate material id " + id);
            d.id = id;
            out_.materials.push_back(d);
        });
    }

    void load_cameras(const json& scene, const std::string& sp) {
        const json& cs = require(scene, sp, "Cameras");
        const std::string path = sp + "/Cameras";
        expect_object(cs, path);
        check_keys(cs, path, {"Camera"});
        const std::string generic = path + "/Camera";
        for_each_item(cs, path, "Camera", [&](const json& c, const std::string& cp) {
            check_keys(
                c, generic,
                {"_id", "_type", "Position", "Gaze", "GazePoint", "Up", "NearPlane", "NearDistance", "FovY",
                 "ImageResolution", "ImageName", "Transformations", "NumSamples", "FocusDistance", "ApertureSize"});
            CameraDesc d;
            bool look_at = false;
            if (const json* t = find(c, "_type")) {
                const std::string& ty = text(*t, cp + "/_type");
                if (ty == "lookAt")
                    look_at = true;
                else if (ty != "simple")
                    fail(cp + "/_type", "unknown camera type '" + ty + "' (expected lookAt)");
            }
            d.position = vec3(require(c, cp, "Position"), cp + "/Position");
            d.near_distance = positive(require(c, cp, "NearDistance"), cp + "/NearDistance");
            const std::vector<double> res = exactly(require(c, cp, "ImageResolution"), cp + "/ImageResolution", 2);
            for (double r : res)
                if (r != std::floor(r) || r < 1)
                    fail(cp + "/ImageResolution", "width and height must be positive integers");
            if (res[0] * res[1] > static_cast<double>(kMaxPixels))
                fail(cp + "/ImageResolution", "image too large (" + format_number(res[0]) + " x " +
                                                  format_number(res[1]) + ", at most " + std::to_string(kMaxPixels) +
                                                  " pixels)");
            d.width = static_cast<int>(res[0]);
            d.height = static_cast<int>(res[1]);
            d.image_name = text(require(c, cp, "ImageName"), cp + "/ImageName");
            if (d.image_name.empty()) fail(cp + "/ImageName", "must not be empty");
            if (look_at) {  // spec 3; the camera math is in src/camera
                const std::string gaze_path = cp + "/GazePoint";
                const Vec3 gaze_point = vec3(require(c, cp, "GazePoint"), gaze_path);
                if (!(length(gaze_point - d.position) > 0)) fail(gaze_path, "GazePoint must differ from Position");
                const Real fovy = real(require(c, cp, "FovY"), cp + "/FovY");
                if (!(fovy > 0 && fovy < 180)) fail(cp + "/FovY", "must be between 0 and 180 degrees");
                set_look_at(d, gaze_point, fovy);
            } else {
                const Vec3 gaze = nonzero_vec3(require(c, cp, "Gaze"), cp + "/Gaze");
                // The course's 2021 spheres.xml writes a fifth number; its parser read four.
                const std::vector<double> np = numbers(require(c, cp, "NearPlane"), cp + "/NearPlane");
                if (np.size() < 4) fail(cp + "/NearPlane", "expected 4 numbers, got " + std::to_string(np.size()));
                if (np.size() > 4)
                    out_.warnings.push_back(file() + ": " + cp + "/NearPlane: " + std::to_string(np.size()) +
                                            " numbers, the first 4 used (left right bottom top)");
                set_near_plane(d, gaze, static_cast<Real>(np[0]), static_cast<Real>(np[1]), static_cast<Real>(np[2]),
                               static_cast<Real>(np[3]));
                if (d.left == d.right || d.bottom == d.top)
                    fail(cp + "/NearPlane", "left/right and bottom/top must differ");
            }
            d.up = nonzero_vec3(require(c, cp, "Up"), cp + "/Up");
            // A camera moves as a rigid body would: its position as a point, its gaze and
            // up as directions (docs/transformations.md).
            if (const std::optional<Affine> m = transform_ref(c, cp)) {
                d.position = m->point(d.position);
                d.gaze = m->vector(d.gaze);
                d.up = m->vector(d.up);
            }
            if (!spans_camera_frame(d.gaze, d.up)) fail(cp + "/Up", "Up is parallel to the gaze direction");
            load_lens(c, cp, d);
            out_.cameras.push_back(d);
        });
        if (out_.cameras.empty()) fail(path, "no camera defined");
    }

    // NumSamples, ApertureSize and FocusDistance (docs/conventions.md, "Assignment 3").
    void load_lens(const json& c, const std::string& cp, CameraDesc& d) {
        if (const json* n = find(c, "NumSamples")) {
            const std::string np = cp + "/NumSamples";
            const double v = exactly(*n, np, 1)[0];
            if (v != std::floor(v) || v < 1 || v > kMaxSamples)
                fail(np,
                     "must be a whole number from 1 to " + std::to_string(kMaxSamples) + ", got " + format_number(v));
            d.num_samples = static_cast<int>(v);
        }
        if (const json* a = find(c, "ApertureSize")) d.aperture_size = non_negative(*a, cp + "/ApertureSize");
        if (const json* f = find(c, "FocusDistance")) d.focus_distance = positive(*f, cp + "/FocusDistance");
        if (d.aperture_size > 0 && !(d.focus_distance > 0))
            fail(cp + "/ApertureSize", "a lens (ApertureSize > 0) needs a FocusDistance");
    }

    void load_lights(const json& scene, const std::string& sp) {
        const json* ls = find(scene, "Lights");
        const std::string path = sp + "/Lights";
        if (!ls || ls->is_null()) return;
        expect_object(*ls, path);
        check_keys(*ls, path, {"AmbientLight", "PointLight", "AreaLight"});
        if (const json* a = find(*ls, "AmbientLight")) out_.ambient_light = color(*a, path + "/AmbientLight");
        const std::string generic = path + "/PointLight";
        for_each_item(*ls, path, "PointLight", [&](const json& l, const std::string& lp) {
            check_keys(l, generic, {"_id", "Position", "Intensity", "Transformations"});
            Vec3 position = vec3(require(l, lp, "Position"), lp + "/Position");
            if (const std::optional<Affine> m = transform_ref(l, lp)) position = m->point(position);
            out_.point_lights.push_back({position, color(require(l, lp, "Intensity"), lp + "/Intensity")});
        });
        for_each_item(*ls, path, "AreaLight", [&](const json& l, const std::string& lp) {
            check_keys(l, path + "/AreaLight", {"_id", "Position", "Normal", "Size", "Radiance"});
            AreaLightDesc a;
            a.position = vec3(require(l, lp, "Position"), lp + "/Position");
            a.normal = nonzero_vec3(require(l, lp, "Normal"), lp + "/Normal");
            a.size = positive(require(l, lp, "Size"), lp + "/Size");
            a.radiance = color(require(l, lp, "Radiance"), lp + "/Radiance");
            out_.area_lights.push_back(a);
        });
    }

    // Copies the VertexData entries a mesh uses into its own vertex list, so that
    // smooth normals are computed per mesh (reference-conventions.md, "Smooth meshes").
    void add_inline_faces(MeshDesc& mesh, const std::vector<double>& ids, const std::string& path) {
        if (ids.size() % 3 != 0)
            fail(path, "expected vertex ids in threes, got " + std::to_string(ids.size()) + " numbers");
        std::unordered_map<uint32_t, uint32_t> local;
        local.reserve(ids.size());
        mesh.indices.reserve(ids.size());
        for (double d : ids) {
            const uint32_t g = vertex_id(d, path);
            auto [it, inserted] = local.emplace(g, static_cast<uint32_t>(mesh.positions.size()));
            if (inserted) mesh.positions.push_back(vertices_[g]);
            mesh.indices.push_back(it->second);
        }
    }

    void load_objects(const json& scene, const std::string& sp) {
        const json* os = find(scene, "Objects");
        const std::string path = sp + "/Objects";
        if (!os || os->is_null()) return;
        expect_object(*os, path);
        std::vector<const char*> kinds = {"Mesh", "Triangle"};
        for_each_shape_desc([&](auto k) { kinds.push_back(decltype(k)::kKey); });
        check_keys(*os, path, kinds);

        size_t meshes = 0, triangles = 0;  // positions among their kind, for object_id
        for_each_item(*os, path, "Mesh", [&](const json& m, const std::string& mp) {
            check_keys(m, path + "/Mesh",
                       {"_id", "_shadingMode", "Material", "Faces", "Transformations", "MotionBlur"});
            MeshDesc mesh;
            mesh.material = material_ref(m, mp);
            mesh.motion = motion_ref(m, mp);
            mesh.id = object_id(m, ++meshes);
            if (const std::optional<Affine> t = transform_ref(m, mp)) mesh.transform = *t;
            add_base(mesh.id, Base{false, static_cast<uint32_t>(out_.meshes.size()), mp});
            if (const json* s = find(m, "_shadingMode")) {
                const std::string& mode = text(*s, mp + "/_shadingMode");
                if (mode == "smooth")
                    mesh.shading = ShadingMode::Smooth;
                else if (mode != "flat")
                    fail(mp + "/_shadingMode", "unknown shading mode '" + mode + "' (expected flat or smooth)");
            }
            const std::string fp = mp + "/Faces";
            const json& faces = require(m, mp, "Faces");
            if (faces.is_string()) {  // XML <Faces>1 2 3</Faces> has no attributes: the text is the data
                add_inline_faces(mesh, numbers(faces, fp), fp);
                mesh.source = fp;
                out_.meshes.push_back(std::move(mesh));
                return;
            }
            expect_object(faces, fp);
            check_keys(faces, path + "/Mesh/Faces", {"_data", "_type", "_plyFile"});
            if (const json* t = find(faces, "_type"); t && text(*t, fp + "/_type") != "triangle")
                fail(fp + "/_type", "unsupported face type '" + t->get<std::string>() + "' (expected triangle)");
            const json* ply = find(faces, "_plyFile");
            const json* data = find(faces, "_data");
            if (ply && data) fail(fp, "has both _data and _plyFile");
            if (ply) {
                // Read once the tree is released (read_mesh_files): the tree and the
                // mesh are never in memory together.
                const std::string& rel = text(*ply, fp + "/_plyFile");
                mesh.source = (!rel.empty() && rel[0] == '/') ? rel : dir_ + rel;
                mesh.ply_pointer = fp + "/_plyFile";
                // Read through the animation's cache: drawn as an instance of itself,
                // so that its BVH comes from the cache too.
                mesh.instanced = meshes_ != nullptr;
            } else if (data) {
                add_inline_faces(mesh, numbers(*data, fp + "/_data"), fp + "/_data");
                mesh.source = fp;
            } else {
                const auto [found, meant] = near_key(faces, {"_data", "_plyFile"});
                fail(fp, "needs _data or _plyFile" +
                             (found.empty() ? "" : " (did you mean " + meant + "? found " + found + ")"));
            }
            out_.meshes.push_back(std::move(mesh));
        });

        for_each_item(*os, path, "Triangle", [&](const json& t, const std::string& tp) {
            check_keys(t, path + "/Triangle", {"_id", "Material", "Indices", "Transformations", "MotionBlur"});
            MeshDesc mesh;
            mesh.material = material_ref(t, tp);
            mesh.motion = motion_ref(t, tp);
            mesh.triangle_object = true;
            mesh.id = object_id(t, ++triangles);
            if (const std::optional<Affine> m = transform_ref(t, tp)) mesh.transform = *m;
            add_inline_faces(mesh, exactly(require(t, tp, "Indices"), tp + "/Indices", 3), tp + "/Indices");
            mesh.source = tp;
            out_.meshes.push_back(std::move(mesh));
        });

        // The other kinds (rt/loader/shape_descs.h), each by its own reader.
        for_each_shape_desc([&](auto k) {
            using D = decltype(k);
            if constexpr (D::kReadAsShape) {
                std::vector<D>& list = out_.all<D>();
                for_each_item(*os, path, D::kKey, [&](const json& e, const std::string& ep) {
                    check_keys(e, path + "/" + D::kKey, D::kKeys);
                    D d;
                    d.material = material_ref(e, ep);
                    if (std::any_of(std::begin(D::kKeys), std::end(D::kKeys),
                                    [](const char* key) { return std::strcmp(key, "MotionBlur") == 0; }))
                        d.motion = motion_ref(e, ep);
                    FieldReader r{*this, e, ep};
                    D::read(r, d);
                    if (const std::optional<Affine> m = transform_ref(e, ep)) D::apply_transform(d, *m);
                    d.id = object_id(e, list.size() + 1);
                    list.push_back(std::move(d));
                });
            }
        });
        load_instances(*os, path);
    }

    // --- mesh instances ---------------------------------------------------------

    // What a _baseMeshId may name: an Objects/Mesh (by its index in SceneDesc::meshes) or
    // an Objects/MeshInstance (by its place among them).
    struct Base {
        bool instance = false;
        uint32_t index = 0;
        std::string path;  // where it is defined; empty when two entries share the id
    };
    std::unordered_map<std::string, Base> bases_;
    void add_base(const std::string& id, Base b) {
        auto [it, inserted] = bases_.emplace(id, b);
        if (!inserted) it->second.path.clear();
    }

    struct PendingInstance {
        const json* entry;
        std::string path;
        int state = 0;  // 0 unread, 1 being resolved (a cycle when met again), 2 done
        InstanceDesc desc;
    };
    std::vector<PendingInstance> instances_;

    // Objects/MeshInstance: _baseMeshId names a Mesh or another MeshInstance (whose
    // mesh, transformation and material it starts from); its Transformations come after
    // the base's, or replace them with _resetTransform "true"; Material, when given,
    // replaces the base's (docs/transformations.md).
    void load_instances(const json& os, const std::string& path) {
        if (const json* list = find(os, InstanceDesc::kKey); list && list->is_array()) instances_.reserve(list->size());
        for_each_item(os, path, InstanceDesc::kKey, [&](const json& e, const std::string& ep) {
            check_keys(e, path + "/" + InstanceDesc::kKey, InstanceDesc::kKeys);
            PendingInstance p{&e, ep, 0, {}};
            p.desc.id = object_id(e, instances_.size() + 1);
            add_base(p.desc.id, Base{true, static_cast<uint32_t>(instances_.size()), ep});
            instances_.push_back(std::move(p));
        });
        std::vector<InstanceDesc>& list = out_.all<InstanceDesc>();
        for (size_t i = 0; i < instances_.size(); ++i) resolve_instance(i);
        // Sized once: growing by doubling would hold two copies of the list at its peak.
        list.reserve(list.size() + out_.meshes.size() + instances_.size());
        // Meshes that instances show, and every mesh or triangle with Transformations,
        // each drawn as an instance of its untransformed self, before the MeshInstances:
        // one rule for all moved triangles (docs/transformations.md).
        for (size_t m = 0; m < out_.meshes.size(); ++m) {
            MeshDesc& mesh = out_.meshes[m];
            if (!mesh.instanced && mesh.transform.is_identity() && is_still(mesh.motion)) continue;
            mesh.instanced = true;
            InstanceDesc self;
            self.mesh = static_cast<uint32_t>(m);
            self.transform = mesh.transform;
            self.motion = mesh.motion;
            self.material = mesh.material;
            self.id = mesh.id;
            self.key = mesh.triangle_object ? "Triangle" : "Mesh";
            list.push_back(self);
        }
        for (PendingInstance& p : instances_) list.push_back(std::move(p.desc));
        instances_.clear();
    }

    const InstanceDesc& resolve_instance(size_t i) {
        PendingInstance& p = instances_[i];  // the recursion below does not grow instances_
        if (p.state == 2) return p.desc;
        const std::string bp = p.path + "/_baseMeshId";
        if (p.state == 1) fail(bp, "instances form a cycle through _baseMeshId");
        p.state = 1;
        const json& e = *p.entry;
        const json& base_id = require(e, p.path, "_baseMeshId");
        const std::string id = base_id.is_number() ? std::to_string(integer(base_id, bp)) : text(base_id, bp);
        auto it = bases_.find(id);
        if (it == bases_.end()) fail(bp, "no Mesh or MeshInstance has _id " + id);
        if (it->second.path.empty()) fail(bp, "more than one Mesh or MeshInstance has _id " + id);
        const Base base = it->second;
        Affine base_transform;
        uint32_t base_material = 0;
        if (base.instance) {
            const InstanceDesc& b = resolve_instance(base.index);
            p.desc.mesh = b.mesh;
            base_transform = b.transform;
            base_material = b.material;
        } else {
            const MeshDesc& m = out_.meshes[base.index];
            p.desc.mesh = base.index;
            base_transform = m.transform;
            base_material = m.material;
        }
        p.desc.material = find(e, "Material") ? material_ref(e, p.path) : base_material;
        p.desc.motion = motion_ref(e, p.path);  // its own: a base's motion is not inherited
        bool reset = false;
        if (const json* r = find(e, "_resetTransform")) {
            const std::string rp = p.path + "/_resetTransform";
            if (r->is_boolean())
                reset = r->get<bool>();
            else if (text(*r, rp) == "true")
                reset = true;
            else if (text(*r, rp) != "false")
                fail(rp, "expected true or false, got '" + r->get<std::string>() + "'");
        }
        const std::optional<Affine> own = transform_ref(e, p.path);
        p.desc.transform = reset ? own.value_or(Affine{}) : own.value_or(Affine{}) * base_transform;
        out_.meshes[p.desc.mesh].instanced = true;
        p.state = 2;
        return p.desc;
    }
};

}  // namespace

SceneDesc describe_scene(const json& root, const std::string& path, PlyCache* meshes) {
    SceneDesc d;
    d.path = path;
    Loader(path, d, meshes).load(root);
    return d;
}

SceneDesc scene_from_json(const json& root, const std::string& path, PlyCache* meshes) {
    SceneDesc d = describe_scene(root, path, meshes);
    read_mesh_files(d, meshes);
    return d;
}

}  // namespace rt
