// Internal: the glTF extensions rtconvert reads, and the compressed files glTF pipelines
// write (docs/gltf.md, "Compressed and quantised files"): EXT_meshopt_compression through
// Debian's libmeshoptimizer (gltf_codec_meshopt.cpp), KHR_draco_mesh_compression through
// libdraco (gltf_codec_draco.cpp). Both are optional (mk/convert.mk: RT_NO_MESHOPT,
// RT_NO_DRACO); a build without one refuses the files that require it, naming the extension.
//
// tinygltf does not read such files as they are (a meshopt fallback buffer holds no bytes; a
// Draco primitive's indices accessor has no bufferView), so rtgltf::parse runs three steps:
// prepare() on the JSON, tinygltf on the result, then the decoders, which leave the model as
// an uncompressed file would have been. Namespace rtgltf, as gltf_io.h: compiled once.
#pragma once
#include <nlohmann/json.hpp>

#include <cstddef>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gltf_io.h"

namespace rtgltf {

// Whether this build reads `extension` (or may leave it aside without changing what a
// scene shows).
bool understood(const std::string& extension);

// What prepare() set aside for the decoders.
struct Compressed {
    std::map<int, size_t> fallbacks;                   // meshopt fallback buffer -> its byteLength
    std::map<std::pair<int, int>, int> draco_indices;  // (mesh, primitive) -> its indices accessor
    bool empty() const { return fallbacks.empty() && draco_indices.empty(); }
};

// Before tinygltf: throws Error (one line naming `path` and /extensionsRequired/i) for a
// file that requires an extension this build does not read; appends a warning per extension
// used and not read; and makes the JSON of a compressed file one tinygltf reads: each
// meshopt fallback buffer without a uri gets a one-byte stand-in, each Draco primitive's
// indices are set aside in `out`. Returns whether `j` changed.
bool prepare(nlohmann::json& j, const std::string& path, Compressed& out, std::vector<std::string>& warnings);

// After tinygltf: every compressed bufferView (meshopt) and primitive (Draco) decoded into a
// buffer of its own, the accessors and bufferViews pointed at it, the fallback buffers
// emptied. Throws Error naming `path` and the element (/bufferViews/3/extensions/...) for a
// stream that does not decode or does not fit what the file says of it.
void decode(tinygltf::Model& model, const Compressed& set_aside, const std::string& path);

// The decoders decode() runs, each where this build has its library (each throws Error as
// decode does): meshopt on every bufferView with the extension, Draco on every primitive.
void decode_meshopt(tinygltf::Model& model, const std::string& path);
void decode_draco(tinygltf::Model& model, const std::string& path);

// Shared by the decoders: whether `j` is a whole number >= 0 (tinygltf keeps a number of
// the file as an int, or a double past int's range), and then `out` is it.
bool whole_number(const nlohmann::json& j, size_t& out);
// A new buffer holding `bytes` and a bufferView of all of it (with
// `stride`, 0 for none); the view's index.
int append_view(tinygltf::Model& model, std::vector<unsigned char> bytes, size_t stride);
// The bytes [offset, offset + length) of buffer `buffer`; an Error at `where` when they are
// not all there.
const unsigned char* bytes_of(const tinygltf::Model& model, int buffer, size_t offset, size_t length,
                              const std::string& where, const std::string& path);

}  // namespace rtgltf
