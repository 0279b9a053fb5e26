// Scene converters (the rtconvert command): the course's XML format <-> our JSON
// format, Wavefront OBJ (+MTL) -> JSON + binary PLY, any scene -> OBJ + MTL, and
// glTF 2.0 (.gltf, .glb) <-> JSON + binary PLY (docs/gltf.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/loader/scene_desc.h"
#include "rt/shapes/shape.h"

namespace rt {

// A file's format by its extension, case-insensitive: .json, .xml, .obj, .gltf, .glb.
enum class SceneFormat { Json, Xml, Obj, Gltf, Unknown };
SceneFormat scene_format_of(const std::string& path);

// How OBJ faces are shaded: Auto makes smooth meshes of faces that carry vertex
// normals or sit in a smoothing group ("s 1"), flat meshes of the rest.
enum class ObjShading { Auto, Flat, Smooth };

struct ConvertOptions {
    // OBJ import
    ObjShading shading = ObjShading::Auto;
    int width = 800, height = 600;  // the camera's ImageResolution
    bool size_given = false;        // --size: glTF cameras take it instead of their aspect ratio
    std::string image_name;         // the camera's ImageName; default: the output's stem + ".png"
    // glTF import
    int camera = 1;                // the glTF camera to keep, 1-based; 0: all of them
    bool bake_transforms = false;  // node matrices applied to the vertices, not kept as Transformations
    // course Intensity = candela x light_scale (docs/gltf.md): the pixel value, 0..255, a
    // glTF point light gives a white diffuse surface where Blender renders it 0..1
    double light_scale = 255 / (683 * 3.141592653589793);
    // scene -> OBJ or glTF export: a sphere becomes a UV sphere of this many segments
    // around and half as many rings (128: within 0.5% of the exact sphere's pixels in the
    // official scenes, docs/gltf.md)
    int sphere_segments = 128;
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
//   .gltf/.glb -> .json/.xml  scene file + one binary PLY per mesh beside it
//   .json/.xml -> .gltf  glTF + its buffer (<stem>.bin) beside it; -> .glb: one file
// Every file is written atomically. Throws rt::InputError, one line naming the file
// and the place, for unreadable or malformed input and unwritable output.
ConvertResult convert_file(const std::string& input, const std::string& output, const ConvertOptions& options = {});

// In-memory versions of the XML <-> JSON conversions; `path` names the input in errors.
std::string xml_to_json_text(const std::string& xml_text, const std::string& path);  // 2-space JSON
std::string json_to_xml_text(const std::string& json_text, const std::string& path);
// glTF (the bytes of a .gltf or .glb, external buffers beside `path`) -> the scene's JSON
// text; its meshes are named (mesh_1.ply, ...), not written.
std::string gltf_to_json_text(const std::string& gltf_bytes, const std::string& path,
                              const ConvertOptions& options = {});

// A loaded scene as OBJ + MTL text: meshes as they are, spheres tessellated, planes as
// large quads (10x the scene's extent), one MTL material per scene material.
struct ObjText {
    std::string obj, mtl;
};
ObjText scene_to_obj(const SceneDesc& scene, const std::string& mtl_file_name, int sphere_segments = 128);

// What the exports make polygons with (rt/shapes/shape.h): the scene's centre and extent
// (planes become squares 10x its extent) and the segments of a tessellated sphere.
ExportFrame export_frame(const SceneDesc& scene, int sphere_segments);

// Binary little-endian PLY of positions (x y z per vertex) and triangles: float
// positions, or double where some coordinate is not a float.
// Throws rt::InputError naming `path` when it cannot be written.
void write_ply(const std::string& path, const std::vector<double>& positions, const std::vector<uint32_t>& indices);

}  // namespace rt
