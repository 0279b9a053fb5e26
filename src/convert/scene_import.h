// Internal: what the importers (OBJ through tinyobjloader, glTF through tinygltf) make of
// a model: a scene tree of our JSON format plus its meshes, which convert.cpp writes out
// (the tree as JSON or XML, each mesh as a binary PLY beside it).
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/convert/convert.h"

namespace rt {

struct ImportedMesh {
    std::string ply_name;           // as the scene tree names it (relative to the scene file)
    std::vector<double> positions;  // x y z per vertex, only the vertices this mesh uses
    std::vector<uint32_t> indices;  // 3 per triangle, 0-based into positions / 3
};

struct SceneImport {
    nlohmann::ordered_json scene;       // {"Scene": {...}}, Faces as {"_plyFile": ply_name}
    std::vector<ImportedMesh> meshes;   // each written as its ply_name
    std::vector<std::string> warnings;  // "<file>: <what>"
    std::vector<std::string> notes;
};

// Meshes are split by material and smoothing (see ObjShading), polygons fan-split,
// negative (relative) indices resolved; mesh k is named `ply_prefix + "_" + k + ".ply"`.
// Materials come from the MTL libraries (Ka, Kd, Ks, Ns; illum 3 or 5, or a
// mirror-like Ks with a dark Kd: mirror; illum 4/6/7/9 or d < 1: dielectric with Ni
// and Tf); a missing MTL or an unknown material gets the default material and a warning.
// A lookAt camera frames the bounding box; the default lights light it (frame_model).
// Throws rt::InputError "<file>: line N: <what>" for unreadable files, faces whose
// indices are out of range, unreadable MTL files and OBJ files without faces.
SceneImport import_obj(const std::string& obj_path, const ConvertOptions& options, const std::string& ply_prefix);

// glTF 2.0 (.gltf with its buffers, or .glb) -> our format; every mapping is in
// docs/gltf.md. Throws rt::InputError "<file>: <element>: <what>", the element a JSON
// pointer into the glTF (/meshes/2/primitives/0), for anything it cannot convert.
SceneImport import_gltf(const std::string& path, const ConvertOptions& options, const std::string& ply_prefix);
// The same of a glTF's bytes, read from `path` (named in messages; external buffers are
// read from its folder).
SceneImport import_gltf_bytes(const std::string& bytes, const std::string& path, const ConvertOptions& options,
                              const std::string& ply_prefix);

// ---- Shared by the importers ---------------------------------------------------------

// The shortest decimal text that reads back as the same double; "0" for -0.
std::string course_number(double d);
// "x y z" of course_number()s.
std::string course_vec(const std::array<double, 3>& v);

// The material a face without one gets: a default grey.
nlohmann::ordered_json default_material(size_t id);

// What a model without its own camera or lights gets, placed by its bounding box
// [lo, hi]: a lookAt camera (40 degrees vertical field of view) in front of it, up and to
// the right, framing its bounding sphere; a point light up and to the left; an ambient
// light. `camera` and `lights` are filled only where asked for.
struct ModelFrame {
    nlohmann::ordered_json camera;  // a Cameras/Camera entry, _id 1
    nlohmann::ordered_json lights;  // a Lights object: AmbientLight and one PointLight
    double radius = 1;              // of the bounding sphere
};
ModelFrame frame_model(const std::array<double, 3>& lo, const std::array<double, 3>& hi, int width, int height,
                       const std::string& image_name);

}  // namespace rt
