// Scene loading: JSON text -> SceneDesc (plain structs, all ids resolved and checked).
#pragma once
#include <string>

#include "rt/scene_desc.h"

namespace rt {

// Reads and parses a scene file; PLY files are resolved relative to its folder.
// Throws rt::InputError "<path>: <json pointer>: <what>" for any bad input.
SceneDesc load_scene(const std::string& path);

// Parses scene JSON held in memory; `path` names it in messages and anchors PLY paths.
SceneDesc parse_scene(const std::string& json_text, const std::string& path);

}  // namespace rt
