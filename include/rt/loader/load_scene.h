// Scene loading: JSON (or the course's older XML) text -> SceneDesc (plain structs,
// all ids resolved and checked). Both formats are read into the same JSON tree and
// walked by one function (rt/loader/scene_tree.h).
#pragma once
#include <string>

#include "rt/loader/ply_cache.h"
#include "rt/loader/scene_desc.h"

namespace rt {

// Reads and parses a scene file; PLY files are resolved relative to its folder.
// A name ending in ".xml" (any case) is read as the course's previous XML format,
// anything else as JSON. Throws rt::InputError "<path>: <json pointer>: <what>" for
// any bad input (XML syntax errors: "<path>: line L, column C: <what>").
// With `meshes` (the frames of an animation), PLY files come from that cache, and every
// mesh read from one is drawn as an instance of itself (MeshDesc::instanced), so that
// build_scene takes its BVH from the cache too (an animation passes its MeshCache,
// rt/scene_build/mesh_cache.h).
SceneDesc load_scene(const std::string& path, PlyCache* meshes = nullptr);

// Parses scene JSON held in memory; `path` names it in messages and anchors PLY paths.
SceneDesc parse_scene(const std::string& json_text, const std::string& path, PlyCache* meshes = nullptr);

// Parses a scene in the course's XML format held in memory: the XML is turned into the
// JSON tree the course's conversion produces (rt/loader/scene_tree.h) and loaded like a JSON scene,
// so error places are JSON pointers of that tree (/Scene/Objects/Sphere/2/Radius).
SceneDesc parse_scene_xml(const std::string& xml_text, const std::string& path, PlyCache* meshes = nullptr);

// True when `path` ends in ".xml", in any case.
bool is_xml_path(const std::string& path);

}  // namespace rt
