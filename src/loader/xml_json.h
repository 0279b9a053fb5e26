// Internal: the course's mapping between its XML scene format and the JSON one,
// both ways, on nlohmann::ordered_json trees (document order is kept).
//
// XML -> JSON (what the course's own conversion produced for its 2025 JSON files):
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
//
// JSON -> XML is the inverse: "_name" keys become attributes, "_data" the element's
// text, arrays repeated elements, null an empty element, numbers and booleans their
// JSON text. JSON -> XML -> JSON gives back the same tree up to that whitespace
// normalisation, one-element arrays (which come back as the element itself) and
// empty strings (which come back as null).
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace rt {

// Throws rt::InputError "<path>: line L, column C: <what>" for malformed XML, and
// "<path>: <what>" for documents with no single root element or nesting too deep.
nlohmann::ordered_json xml_to_json_tree(const std::string& xml_text, const std::string& path);

// Throws rt::InputError "<path>: <json pointer>: <what>" for trees with no XML form
// (a root that is not one object key, arrays of arrays, object-valued attributes,
// keys that are not XML names, ...). The result has no XML declaration, 4-space indents.
std::string json_tree_to_xml(const nlohmann::ordered_json& root, const std::string& path);

// Parses JSON text keeping key order. Throws rt::InputError "<path>: parse error at
// line L, column C: <what>" like the scene loader.
nlohmann::ordered_json parse_json_tree(const std::string& json_text, const std::string& path);

}  // namespace rt
