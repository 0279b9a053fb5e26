// Internal: glTF 2.0 files in and out through tinygltf (Debian libtinygltf-dev, its code
// compiled once, in gltf_io.cpp), and the conversions between tinygltf's extras values
// and nlohmann::json that the importer and exporter read and write them with.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace tinygltf {
class Model;
class Value;
}  // namespace tinygltf

namespace rt {

struct SceneDesc;
struct ConvertOptions;
struct ConvertResult;

// The key of the extras the export writes and the import reads (docs/gltf.md).
inline constexpr const char* kGltfExtrasKey = "ceng795";

// Reads `path` (.gltf with its buffers beside it, or .glb). Throws rt::InputError, one
// line naming the file and, where tinygltf says, the element (/buffers/0). Images are
// not read (the format has no textures); `warnings` gets tinygltf's warnings.
void load_gltf(const std::string& path, tinygltf::Model& model, std::vector<std::string>& warnings);

// Writes `model` to `path` atomically: a .glb with its buffer inside, or a .gltf with
// buffer 0 written beside it as <stem>.bin. Returns the files written, `path` first.
std::vector<std::string> save_gltf(tinygltf::Model& model, const std::string& path);

// A loaded scene as glTF (gltf_export.cpp), written by save_gltf; the files written.
std::vector<std::string> write_gltf(const SceneDesc& scene, const std::string& path, const ConvertOptions& options,
                                    ConvertResult& result);

nlohmann::json to_json(const tinygltf::Value& v);
tinygltf::Value to_value(const nlohmann::json& j);

}  // namespace rt
