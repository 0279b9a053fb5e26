// Internal: Wavefront OBJ (+MTL) -> a scene tree of our JSON format plus its meshes,
// through tinyobjloader (Debian libtinyobjloader-dev); convert.cpp writes the result.
#pragma once
#include <nlohmann/json.hpp>

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

struct ObjImport {
    nlohmann::ordered_json scene;       // {"Scene": {...}}, Faces as {"_plyFile": ply_name}
    std::vector<ImportedMesh> meshes;   // in the order of the tree's Mesh array
    std::vector<std::string> warnings;  // "<file>: <what>"
    std::vector<std::string> notes;
};

// Meshes are split by material and smoothing (see ObjShading), polygons fan-split,
// negative (relative) indices resolved; mesh k is named `ply_prefix + "_" + k + ".ply"`.
// Materials come from the MTL libraries (Ka, Kd, Ks, Ns; illum 3 or 5, or a
// mirror-like Ks with a dark Kd: mirror; illum 4/6/7/9 or d < 1: dielectric with Ni
// and Tf); a missing MTL or an unknown material gets a default grey and a warning.
// A lookAt camera frames the bounding box; an ambient light and a point light light it.
// Throws rt::InputError "<file>: line N: <what>" for unreadable files, faces whose
// indices are out of range, unreadable MTL files and OBJ files without faces.
ObjImport import_obj(const std::string& obj_path, const ConvertOptions& options, const std::string& ply_prefix);

}  // namespace rt
