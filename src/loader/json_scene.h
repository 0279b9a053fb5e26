// Internal to the loaders: the step from a parsed JSON tree to a SceneDesc, shared by
// the JSON front end (json_loader.cpp) and the XML one (xml_loader.cpp), which first
// turns the XML into the same tree. Keeps nlohmann out of include/rt/loader.h.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "rt/scene_desc.h"

namespace rt {

// Walks a scene tree ({"Scene": {...}}) into a SceneDesc. `path` names the file in
// messages and anchors relative PLY paths. Throws rt::InputError
// "<path>: <json pointer>: <what>".
SceneDesc scene_from_json(const nlohmann::json& root, const std::string& path);

}  // namespace rt
