// Scene converters (the rtconvert command): the course's XML format <-> our JSON
// format, Wavefront OBJ (+MTL) -> JSON + binary PLY, and any scene -> OBJ + MTL.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/loader/scene_desc.h"

namespace rt {

// A file's format by its extension, case-insensitive: .json, .xml, .obj.
enum class SceneFormat { Json, Xml, Obj, Unknown };
SceneFormat scene_format_of(const std::string& path);

// How OBJ faces are shaded: Auto makes smooth meshes of faces that carry vertex
// normals or sit in a smoothing group ("s 1"), flat meshes of the rest.
enum class ObjShading { Auto, Flat, Smooth };

struct ConvertOptions {
    // OBJ import
    ObjShading shading = ObjShading::Auto;
    int width = 800, height = 600;  // the camera's ImageResolution
    std::string image_name;         // the camera's ImageName; default: the output's stem + ".png"
    // scene -> OBJ export: a sphere becomes a UV sphere of this many segments around
    // and half as many rings
    int sphere_segments = 48;
};

struct ConvertResult {
    std::vector<std::string> written;   // files written, the main output first
    std::vector<std::string> warnings;  // one line each, "<file>: <place>: <what>"
    std::vector<std::string> notes;     // what was made of what (materials, meshes), one line each
};

// Converts `input` to `output`, the direction chosen by their extensions:
//   .xml  -> .json   the course's conversion (rt/loader/scene_tree.h); .json -> .xml its inverse;
//                    .json -> .json and .xml -> .xml rewrite (relative PLY paths are
//                    adjusted whenever the output lands in another folder)
//   .obj  -> .json/.xml  scene file + one binary PLY per mesh beside it (<stem>_<n>.ply)
//   .json/.xml -> .obj   OBJ + MTL (<stem>.mtl) beside it
// Every file is written atomically. Throws rt::InputError, one line naming the file
// and the place, for unreadable or malformed input and unwritable output.
ConvertResult convert_file(const std::string& input, const std::string& output, const ConvertOptions& options = {});

// In-memory versions of the XML <-> JSON conversions; `path` names the input in errors.
std::string xml_to_json_text(const std::string& xml_text, const std::string& path);  // 2-space JSON
std::string json_to_xml_text(const std::string& json_text, const std::string& path);

// A loaded scene as OBJ + MTL text: meshes as they are, spheres tessellated, planes as
// large quads (10x the scene's extent), one MTL material per scene material.
struct ObjText {
    std::string obj, mtl;
};
ObjText scene_to_obj(const SceneDesc& scene, const std::string& mtl_file_name, int sphere_segments = 48);

// Binary little-endian PLY of float positions (x y z per vertex) and triangles.
// Throws rt::InputError naming `path` when it cannot be written.
void write_ply(const std::string& path, const std::vector<double>& positions, const std::vector<uint32_t>& indices);

}  // namespace rt
