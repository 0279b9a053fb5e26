// Internal: glTF 2.0 files in and out through tinygltf (Debian libtinygltf-dev, its code
// compiled once, in gltf_io.cpp), and the conversions between tinygltf's extras values and
// nlohmann::json that the importer and exporter use.
//
// Outside namespace rt: nothing in gltf_io.cpp depends on the precision, so one copy (in the
// double library) serves both (FLOAT_CPPFLAGS renames namespace rt, not rtgltf). It reads and
// writes no files itself; its errors are rtgltf::Error, which the callers make
// rt::InputErrors.
#pragma once
#include <nlohmann/json.hpp>

#include <stdexcept>
#include <string>
#include <vector>

#ifndef RT_NO_GLTF  // built without tinygltf (mk/convert.mk): glTF is refused with an error
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop
#else
namespace tinygltf {
class Model;
class Value;
}  // namespace tinygltf
#endif

namespace rtgltf {

struct Error : std::runtime_error {
    using std::runtime_error::runtime_error;
};

// Parses a glTF (JSON, or .glb when `bytes` starts with its magic) read from `path`, its
// external buffers read from `base_dir`. Throws Error, one line naming `path` and, where
// known, the element (/buffers/0). Images are not decoded (a data URI's bytes are kept);
// `warnings` gets tinygltf's warnings.
void parse(const std::string& bytes, const std::string& path, const std::string& base_dir, tinygltf::Model& model,
           std::vector<std::string>& warnings);

// The bytes of `model` as a .glb (`binary`: one file, its buffer inside), or as a .gltf
// whose buffer 0 is the file `bin_name` beside it, with `bin` its bytes.
struct Serialized {
    std::string main, bin;
};
Serialized serialize(tinygltf::Model& model, bool binary, const std::string& bin_name);

nlohmann::json to_json(const tinygltf::Value& v);
tinygltf::Value to_value(const nlohmann::json& j);

}  // namespace rtgltf

namespace rt {

struct SceneDesc;
struct ConvertOptions;
struct ConvertResult;

// The key of the extras the export writes and the import reads (docs/gltf.md).
inline constexpr const char* kGltfExtrasKey = "ceng795";

#ifndef RT_NO_GLTF
// Our extras: `values` as the "ceng795" member of an element's extras (export), and that
// member of an element's extras, or null (import).
inline tinygltf::Value ours_as_extras(const nlohmann::json& values) {
    return rtgltf::to_value(nlohmann::json{{kGltfExtrasKey, values}});
}
inline nlohmann::json ours_in(const tinygltf::Value& extras) {
    const nlohmann::json j = rtgltf::to_json(extras);
    return j.is_object() && j.contains(kGltfExtrasKey) ? j[kGltfExtrasKey] : nlohmann::json();
}
#endif

// A loaded scene as a glTF file at `path` (.gltf + <stem>.bin, or .glb), each file written
// atomically (gltf_export.cpp); the files written, `path` first.
std::vector<std::string> write_gltf(const SceneDesc& scene, const std::string& path, const ConvertOptions& options,
                                    ConvertResult& result);

}  // namespace rt
