// EXT_meshopt_compression through Debian's libmeshoptimizer (gltf_codecs.h): each bufferView
// with the extension decoded (vertex, index or index-sequence codec, then its filter) into a
// buffer of its own. Every parameter the library asserts on is checked first, so a file
// that lies is an Error naming the bufferView, never an abort.
#if !defined(RT_NO_GLTF) && !defined(RT_NO_MESHOPT)
#include <meshoptimizer.h>

#include <algorithm>
#include <cstdint>

#include "gltf_codecs.h"

namespace rtgltf {
namespace {

using json = nlohmann::json;

// No stream of the three codecs decodes to more than 64 times its size (the vertex codec
// spends at least 2 bits on each group of 16 bytes): a larger count is a lie, refused before
// anything is allocated for it.
constexpr size_t kMaxRatio = 64;

}  // namespace

void decode_meshopt(tinygltf::Model& model, const std::string& path) {
    for (size_t i = 0; i < model.bufferViews.size(); ++i) {
        const auto ext = model.bufferViews[i].extensions.find("EXT_meshopt_compression");
        if (ext == model.bufferViews[i].extensions.end()) continue;
        const std::string where = "/bufferViews/" + std::to_string(i) + "/extensions/EXT_meshopt_compression";
        auto fail = [&](const std::string& what) { throw Error(path + ": " + where + ": " + what); };
        const json e = to_json(ext->second);
        if (!e.is_object()) fail("must be an object");
        auto whole = [&](const char* key, bool required, size_t otherwise = 0) -> size_t {
            if (!e.contains(key)) {
                if (required) fail("has no " + std::string(key));
                return otherwise;
            }
            size_t n = 0;
            if (!whole_number(e[key], n)) fail(std::string(key) + " must be a whole number >= 0");
            return n;
        };
        const size_t buffer = whole("buffer", true), offset = whole("byteOffset", false),
                     length = whole("byteLength", true), stride = whole("byteStride", true),
                     count = whole("count", true);
        const std::string mode = e.value("mode", json()).is_string() ? e["mode"].get<std::string>() : "";
        const std::string filter = e.value("filter", json("NONE")).is_string() ? e.value("filter", "NONE") : "?";
        if (mode == "ATTRIBUTES") {
            if (stride == 0 || stride > 256 || stride % 4) fail("ATTRIBUTES needs a byteStride of 4 to 256, by 4");
        } else if (mode == "TRIANGLES" || mode == "INDICES") {
            if (stride != 2 && stride != 4) fail(mode + " needs a byteStride of 2 or 4");
            if (mode == "TRIANGLES" && count % 3) fail("TRIANGLES needs a count divisible by 3");
        } else {
            fail("mode must be ATTRIBUTES, TRIANGLES or INDICES");
        }
        if (filter != "NONE" && mode != "ATTRIBUTES") fail("filter " + filter + " is only for ATTRIBUTES");
        if ((filter == "OCTAHEDRAL" && stride != 4 && stride != 8) || (filter == "QUATERNION" && stride != 8))
            fail("filter " + filter + " does not take a byteStride of " + std::to_string(stride));
        if (filter != "NONE" && filter != "OCTAHEDRAL" && filter != "QUATERNION" && filter != "EXPONENTIAL")
            fail("filter must be NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL");
        if (count > SIZE_MAX / stride || count * stride != model.bufferViews[i].byteLength)
            fail("count x byteStride must be the bufferView's byteLength (" +
                 std::to_string(model.bufferViews[i].byteLength) + ")");
        const unsigned char* src =
            bytes_of(model, int(std::min<size_t>(buffer, INT32_MAX)), offset, length, where, path);
        if (count * stride > kMaxRatio * length)
            fail("a stream of " + std::to_string(length) + " bytes cannot hold " + std::to_string(count) +
                 " elements of " + std::to_string(stride) + " bytes: it is corrupt");
        std::vector<unsigned char> out(count * stride);
        const int rc = mode == "ATTRIBUTES"  ? meshopt_decodeVertexBuffer(out.data(), count, stride, src, length)
                       : mode == "TRIANGLES" ? meshopt_decodeIndexBuffer(out.data(), count, stride, src, length)
                                             : meshopt_decodeIndexSequence(out.data(), count, stride, src, length);
        if (rc != 0)
            fail("its " + mode + " stream (" + std::to_string(length) +
                 " bytes) does not decode: truncated or corrupt " + "(meshopt error " + std::to_string(rc) + ")");
        if (filter == "OCTAHEDRAL") meshopt_decodeFilterOct(out.data(), count, stride);
        if (filter == "QUATERNION") meshopt_decodeFilterQuat(out.data(), count, stride);
        if (filter == "EXPONENTIAL") meshopt_decodeFilterExp(out.data(), count, stride);
        tinygltf::BufferView& v = model.bufferViews[i];
        v.buffer = int(model.buffers.size());
        v.byteOffset = 0;
        v.extensions.erase(ext);
        model.buffers.emplace_back();
        model.buffers.back().data = std::move(out);
    }
}

}  // namespace rtgltf
#endif
