// rtconvert's JSON -> XML writer: the inverse of the XML reading of rt/loader/scene_tree.h.
// "_name" keys become attributes, "_data" the element's text, arrays repeated
// elements, null an empty element, numbers and booleans their JSON text.
// JSON -> XML -> JSON gives back the same tree up to the reader's whitespace
// normalisation, one-element arrays (which come back as the element itself) and
// empty strings (which come back as null).
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace rt {

// Throws rt::InputError "<path>: <json pointer>: <what>" for trees with no XML form
// (a root that is not one object key, arrays of arrays, object-valued attributes,
// keys that are not XML names, ...). The result has no XML declaration, 4-space indents.
std::string json_tree_to_xml(const nlohmann::ordered_json& root, const std::string& path);

}  // namespace rt
