// The JSON tree every scene file is read into, and the one step from that tree to a
// SceneDesc. The scene loader (rt/loader/load_scene.h) picks the reader by the file's name; rtconvert
// (rt/convert/convert.h) reads and writes the trees themselves.
//
// A JSON file is parsed as it is. An XML file (the course's previous format) becomes
// the tree the course's own conversion produced for its 2025 JSON files:
//   <Scene>...</Scene>            {"Scene": {...}}
//   attribute id="1"              "_id": "1"
//   text beside attributes or     "_data": "text"
//     child elements
//   element with text only        "Name": "text"
//   empty element                 "Name": null
//   repeated element              "Name": [ ... ]   (in document order)
// Every value is a string. Text and attribute values have their whitespace collapsed:
// leading and trailing whitespace dropped, every inner run (newlines, tabs) made one
// space, as in the course's JSON files. Comments, processing instructions and the XML
// declaration are ignored.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "rt/loader/ply_cache.h"
#include "rt/loader/scene_desc.h"

namespace rt {

// XML documents nested deeper are refused, read or written (scenes nest 5 deep).
constexpr int kMaxXmlDepth = 256;

// Parses JSON text into Tree: nlohmann::json for loading, nlohmann::ordered_json where
// the key order is kept (rtconvert); only these two are provided. Throws rt::InputError
// "<path>: parse error at line L, column C: <what>" for malformed JSON and
// "<path>: line L, column C: number overflow parsing '<literal>' (not a finite number)"
// for a number beyond the double range, the renderer and rtconvert alike.
template <class Tree>
Tree parse_json_tree(const std::string& json_text, const std::string& path);

// Throws rt::InputError "<path>: line L, column C: <what>" for malformed XML, and
// "<path>: <what>" for documents with no single root element or nesting too deep.
nlohmann::ordered_json xml_to_json_tree(const std::string& xml_text, const std::string& path);

// Walks a scene tree ({"Scene": {...}}) into a SceneDesc. `path` names the file in
// messages and anchors relative PLY paths. Throws rt::InputError
// "<path>: <json pointer>: <what>". `meshes`: see load_scene.
SceneDesc scene_from_json(const nlohmann::json& root, const std::string& path, PlyCache* meshes = nullptr);

// scene_from_json in two steps, so that the tree can be released between them (the
// peak of a large scene's load): describe_scene walks the tree and leaves each PLY mesh
// unread (MeshDesc::ply_pointer set, no positions); read_mesh_files reads them, through
// `meshes` when given, and checks their coordinates. The same errors as scene_from_json.
SceneDesc describe_scene(const nlohmann::json& root, const std::string& path, PlyCache* meshes = nullptr);
void read_mesh_files(SceneDesc& desc, PlyCache* meshes = nullptr);

}  // namespace rt
