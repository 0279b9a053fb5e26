// Wavefront OBJ (+MTL) import through tinyobjloader (Debian libtinyobjloader-dev,
// double-precision build): faces are grouped into meshes by material and smoothing,
// materials are mapped onto ours, and a camera and lights are made to frame the model.
#ifndef RT_NO_OBJ  // built without tinyobjloader (mk/convert.mk): OBJ input is refused with an error
#define TINYOBJLOADER_USE_DOUBLE
#include <tiny_obj_loader.h>
#endif

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <sstream>
#include <unordered_map>
#include <utility>

#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/io/files.h"
#include "scene_import.h"

namespace rt {
#ifndef RT_NO_OBJ
namespace {

using ojson = nlohmann::ordered_json;
using V3 = std::array<double, 3>;

// 15 significant digits: tinyobjloader's number parser can be an ulp off ("0.3" reads
// as 0.30000000000000004), which this rounds away again.
std::string num(double d) {
    if (d == 0) return "0";  // also -0
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.15g", d);
    return buf;
}

std::string vec(const V3& v) { return num(v[0]) + " " + num(v[1]) + " " + num(v[2]); }

// Reads mtllib files relative to the OBJ file. A library that does not exist is a
// warning (the default material is used); one that exists but cannot be read is an error.
class MtlReader : public tinyobj::MaterialReader {
public:
    MtlReader(std::string obj_path) : obj_path_(std::move(obj_path)), dir_(dirname_of(obj_path_)) {}

    bool operator()(const std::string& name, std::vector<tinyobj::material_t>* materials,
                    std::map<std::string, int>* matMap, std::string* warn, std::string* err) override {
        const std::string path = (!name.empty() && name[0] == '/') ? name : dir_ + name;
        struct stat st;
        if (::stat(path.c_str(), &st) != 0 && errno == ENOENT) {
            warnings.push_back(obj_path_ + ": material library " + path + " not found: default material used");
            return false;
        }
        try {
            if (::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode))
                throw InputError(path + ": cannot read: not a regular file");
            const std::string text = read_text_file(path);
            std::istringstream in(text);
            std::string w, e;
            tinyobj::LoadMtl(matMap, materials, &in, &w, &e);
            if (warn) *warn += w;
            if (err) *err += e;
            return true;
        } catch (const InputError& e) {
            if (error.empty()) error = e.what();
            return false;
        }
    }

    std::vector<std::string> warnings;
    std::string error;

private:
    std::string obj_path_, dir_;
};

// Line number (1-based) and text of the n-th face line (1-based) with 3 or more
// vertices, the faces tinyobjloader keeps, in file order.
std::pair<size_t, std::string> face_line(const std::string& text, size_t n) {
    size_t line_no = 0, count = 0, start = 0;
    while (start <= text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        ++line_no;
        std::string line = text.substr(start, end - start);
        if (!line.empty() && line.back() == '\r') line.pop_back();
        const size_t b = line.find_first_not_of(" \t");
        if (b != std::string::npos && line[b] == 'f' && b + 1 < line.size() &&
            (line[b + 1] == ' ' || line[b + 1] == '\t')) {
            std::istringstream tokens(line.substr(b + 1));
            std::string t;
            int vertices = 0;
            while (tokens >> t) ++vertices;
            if (vertices >= 3 && ++count == n) return {line_no, line.substr(b)};
        }
        if (end == text.size()) break;
        start = end + 1;
    }
    return {0, ""};
}

// One line of tinyobjloader's error text, as "line N: what" when it names a line.
std::string tinyobj_error(const std::string& err) {
    std::string first = err.substr(0, err.find('\n'));
    const size_t at = first.find("line ");
    std::string line;
    if (at != std::string::npos) {
        size_t e = at + 5;
        while (e < first.size() && std::isdigit(static_cast<unsigned char>(first[e]))) ++e;
        if (e > at + 5) line = first.substr(at, e - at);
    }
    if (first.find("`f' line") != std::string::npos)
        return (line.empty() ? "" : line + ": ") + "bad face: a vertex index is 0 or not a number";
    while (!first.empty() && (first.back() == ' ' || first.back() == '\r')) first.pop_back();
    return (line.empty() ? "" : line + ": ") + first;
}

V3 clamp_color(const double* c, const std::string& what, std::vector<std::string>& warnings) {
    V3 out{c[0], c[1], c[2]};
    for (double& x : out) {
        if (!std::isfinite(x) || x < 0) {
            warnings.push_back(what + ": negative or non-finite value set to 0");
            x = 0;
        }
    }
    return out;
}

// One of our materials from an MTL material (nullptr: the default grey).
ojson make_material(const tinyobj::material_t* m, size_t id, const std::string& mtl_what,
                    std::vector<std::string>& warnings, std::string& kind) {
    ojson j = ojson::object();
    j["_id"] = std::to_string(id);
    if (!m) {
        kind = "default grey";
        return default_material(id);
    }
    const V3 ka = clamp_color(m->ambient, mtl_what + " Ka", warnings);
    const V3 kd = clamp_color(m->diffuse, mtl_what + " Kd", warnings);
    const V3 ks = clamp_color(m->specular, mtl_what + " Ks", warnings);
    const double ns = (std::isfinite(m->shininess) && m->shininess > 0) ? m->shininess : 1.0;
    const int illum = m->illum;
    const bool dielectric = illum == 4 || illum == 6 || illum == 7 || illum == 9 || m->dissolve < 1;
    const bool mirror_like = std::min({ks[0], ks[1], ks[2]}) >= 0.9 && std::max({kd[0], kd[1], kd[2]}) <= 0.1;
    const bool mirror = !dielectric && (illum == 3 || illum == 5 || mirror_like);
    if (dielectric) {
        kind = "dielectric";
        j["_type"] = "dielectric";
        // Glass shows through its refraction; a diffuse term would make it milky.
        j["AmbientReflectance"] = "0 0 0";
        j["DiffuseReflectance"] = "0 0 0";
        j["SpecularReflectance"] = vec(ks);
        j["PhongExponent"] = num(ns);
        j["MirrorReflectance"] = "1 1 1";
        const double ior = (std::isfinite(m->ior) && m->ior > 0 && m->ior != 1) ? m->ior : 1.5;
        j["RefractionIndex"] = num(ior);
        // Tf is the fraction transmitted per unit distance: Beer's law c = -ln(Tf).
        const double* tf = m->transmittance;
        if ((tf[0] > 0 || tf[1] > 0 || tf[2] > 0) && (tf[0] < 1 || tf[1] < 1 || tf[2] < 1)) {
            V3 c;
            for (int i = 0; i < 3; ++i) c[i] = tf[i] >= 1 ? 0.0 : -std::log(std::max(tf[i], 1e-3));
            j["AbsorptionCoefficient"] = vec(c);
        }
        return j;
    }
    if (mirror) {
        kind = "mirror";
        j["_type"] = "mirror";
    } else {
        kind = "plain";
    }
    j["AmbientReflectance"] = vec(ka);
    j["DiffuseReflectance"] = vec(kd);
    j["SpecularReflectance"] = vec(ks);
    j["PhongExponent"] = num(ns);
    if (mirror) {
        V3 r = ks;
        for (double& x : r) x = std::min(x, 1.0);
        j["MirrorReflectance"] = vec(r);
    }
    return j;
}

}  // namespace

SceneImport import_obj(const std::string& obj_path, const ConvertOptions& options, const std::string& ply_prefix) {
    SceneImport out;
    const std::string text = read_text_file(obj_path);

    tinyobj::attrib_t attrib;
    std::vector<tinyobj::shape_t> shapes;
    std::vector<tinyobj::material_t> materials;
    std::string warn, err;
    std::istringstream in(text);
    MtlReader reader(obj_path);
    const bool ok = tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &reader,
                                     /*triangulate=*/false, /*default_vcols_fallback=*/false);
    if (!reader.error.empty()) throw InputError(reader.error);
    if (!ok) throw InputError(obj_path + ": " + tinyobj_error(err));
    out.warnings = reader.warnings;

    // tinyobjloader's own warnings, less those we report better ourselves.
    size_t degenerate = 0;
    {
        std::istringstream lines(warn);
        std::string line;
        while (std::getline(lines, line)) {
            while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
            if (line.empty() || line == ".") continue;
            if (line.rfind("Degenerated face found", 0) == 0) {
                ++degenerate;
                continue;
            }
            if (line.find("indices out of bounds") != std::string::npos) continue;  // checked below
            if (line.rfind("Failed to load material file", 0) == 0) continue;       // MtlReader said why
            if (line.rfind("material [", 0) == 0) {  // material [ 'name' ] not found in .mtl
                out.warnings.push_back(obj_path + ": " + line.substr(0, line.find(" not found")) +
                                       " not found in the material libraries: default material used");
                continue;
            }
            out.warnings.push_back(obj_path + ": " + line);
        }
    }
    if (degenerate)
        out.warnings.push_back(obj_path + ": skipped " + count_of(degenerate, "face") + " with fewer than 3 vertices");

    const size_t nv = attrib.vertices.size() / 3, nn = attrib.normals.size() / 3;
    for (size_t i = 0; i < attrib.vertices.size(); ++i)
        if (!std::isfinite(attrib.vertices[i]))
            throw InputError(obj_path + ": vertex " + std::to_string(i / 3 + 1) + " is not a finite number");

    // Meshes keyed by (material id, smoothing key): 0 flat, a smoothing group id, or
    // kNormals for faces outside any group that carry vertex normals.
    constexpr uint64_t kNormals = 0xffffffffull + 1;
    std::map<std::pair<int, uint64_t>, size_t> mesh_of;
    std::vector<std::pair<int, bool>> mesh_info;  // material id, smooth
    std::vector<std::unordered_map<int, uint32_t>> local;
    std::vector<int> used_materials;      // tinyobj ids (-1: default), in order of first use
    std::map<int, size_t> material_slot;  // tinyobj id -> our 1-based id
    size_t face_no = 0, polygons = 0;
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};

    auto fail_face = [&](size_t face, const std::string& what, const std::string& detail) {
        const auto [line, line_text] = face_line(text, face);
        throw InputError(obj_path + ": " + (line ? "line " + std::to_string(line) + ": " : "") + what +
                         (line ? " in '" + line_text + "'" : "") + " (" + detail + ")");
    };

    for (const tinyobj::shape_t& shape : shapes) {
        const tinyobj::mesh_t& m = shape.mesh;
        size_t offset = 0;
        for (size_t f = 0; f < m.num_face_vertices.size(); ++f) {
            const size_t n = m.num_face_vertices[f];
            ++face_no;
            bool normals = true;
            for (size_t k = 0; k < n; ++k) {
                const tinyobj::index_t& ix = m.indices[offset + k];
                if (ix.vertex_index < 0 || static_cast<size_t>(ix.vertex_index) >= nv)
                    fail_face(face_no, "vertex index out of range", "the file has " + std::to_string(nv) + " vertices");
                if (ix.normal_index < -1 || (ix.normal_index >= 0 && static_cast<size_t>(ix.normal_index) >= nn))
                    fail_face(face_no, "normal index out of range", "the file has " + std::to_string(nn) + " normals");
                normals = normals && ix.normal_index >= 0;
            }
            int material = f < m.material_ids.size() ? m.material_ids[f] : -1;
            if (material >= static_cast<int>(materials.size())) material = -1;
            const unsigned group = f < m.smoothing_group_ids.size() ? m.smoothing_group_ids[f] : 0;
            uint64_t key = 0;
            if (options.shading == ObjShading::Smooth)
                key = 1;
            else if (options.shading == ObjShading::Auto)
                key = group != 0 ? group : normals ? kNormals : 0;

            if (!material_slot.count(material)) {
                material_slot[material] = used_materials.size() + 1;
                used_materials.push_back(material);
            }
            auto [it, inserted] = mesh_of.emplace(std::make_pair(material, key), out.meshes.size());
            if (inserted) {
                out.meshes.emplace_back();
                out.meshes.back().ply_name = ply_prefix + "_" + std::to_string(out.meshes.size()) + ".ply";
                mesh_info.emplace_back(material, key != 0);
                local.emplace_back();
            }
            ImportedMesh& mesh = out.meshes[it->second];
            std::unordered_map<int, uint32_t>& ids = local[it->second];
            uint32_t corner[3];
            for (size_t k = 0; k < n; ++k) {
                const int v = m.indices[offset + k].vertex_index;
                auto [vi, fresh] = ids.emplace(v, static_cast<uint32_t>(mesh.positions.size() / 3));
                if (fresh) {
                    for (int a = 0; a < 3; ++a) {
                        const double x = attrib.vertices[3 * size_t(v) + a];
                        mesh.positions.push_back(x);
                        lo[a] = std::min(lo[a], x);
                        hi[a] = std::max(hi[a], x);
                    }
                }
                // Fan split: (0, k-1, k) for k >= 2.
                if (k == 0)
                    corner[0] = vi->second;
                else if (k == 1)
                    corner[1] = vi->second;
                else {
                    corner[2] = vi->second;
                    mesh.indices.insert(mesh.indices.end(), {corner[0], corner[1], corner[2]});
                    corner[1] = corner[2];
                }
            }
            if (n > 3) ++polygons;
            offset += n;
        }
    }
    if (out.meshes.empty()) throw InputError(obj_path + ": no faces");

    // Materials, in order of first use.
    ojson mats = ojson::array();
    for (size_t i = 0; i < used_materials.size(); ++i) {
        const int id = used_materials[i];
        const tinyobj::material_t* m = id >= 0 ? &materials[size_t(id)] : nullptr;
        std::string kind;
        mats.push_back(
            make_material(m, i + 1, obj_path + ": material '" + (m ? m->name : "") + "'", out.warnings, kind));
        out.notes.push_back("material " + std::to_string(i + 1) + ": " + (m ? "'" + m->name + "' " : "") + "(" + kind +
                            ")");
    }

    const ModelFrame frame =
        frame_model({lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}, options.width, options.height, options.image_name);
    ojson scene = ojson::object();
    scene["BackgroundColor"] = "40 44 56";
    scene["ShadowRayEpsilon"] = num(1e-4 * frame.radius);
    scene["MaxRecursionDepth"] = "6";
    scene["Cameras"] = {{"Camera", frame.camera}};
    scene["Lights"] = frame.lights;
    scene["Materials"] = {{"Material", mats}};
    ojson meshes = ojson::array();
    size_t triangles = 0;
    for (size_t i = 0; i < out.meshes.size(); ++i) {
        ojson mesh = ojson::object();
        mesh["_id"] = std::to_string(i + 1);
        mesh["_shadingMode"] = mesh_info[i].second ? "smooth" : "flat";
        mesh["Material"] = std::to_string(material_slot[mesh_info[i].first]);
        mesh["Faces"] = {{"_plyFile", out.meshes[i].ply_name}};
        meshes.push_back(mesh);
        triangles += out.meshes[i].indices.size() / 3;
        out.notes.push_back("mesh " + std::to_string(i + 1) + ": " +
                            count_of(out.meshes[i].indices.size() / 3, "triangle") + ", " +
                            (mesh_info[i].second ? "smooth" : "flat") + ", material " +
                            std::to_string(material_slot[mesh_info[i].first]) + " -> " + out.meshes[i].ply_name);
    }
    scene["Objects"] = {{"Mesh", meshes}};
    out.scene = {{"Scene", scene}};
    out.notes.push_back(count_of(face_no, "face") + " (" + count_of(polygons, "polygon") + " fan-split) -> " +
                        count_of(triangles, "triangle") + " in " + count_of(out.meshes.size(), "mesh", "meshes"));
    return out;
}
#else
SceneImport import_obj(const std::string& obj_path, const ConvertOptions&, const std::string&) {
    throw InputError(obj_path +
                     ": OBJ import is not supported by this build (it was made without tinyobjloader, "
                     "libtinyobjloader-dev)");
}
#endif  // RT_NO_OBJ

}  // namespace rt
