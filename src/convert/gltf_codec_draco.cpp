// KHR_draco_mesh_compression through Debian's libdraco (gltf_codecs.h): each primitive with
// the extension has its bufferView decoded (once, however many primitives share it), its
// faces written to its indices accessor as unsigned ints and each attribute the extension
// names to the primitive's accessor of that name as floats (Draco undoes its own
// quantisation). An accessor whose count is not what the stream holds is an Error.
#if !defined(RT_NO_GLTF) && !defined(RT_NO_DRACO)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <draco/compression/decode.h>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <memory>

#include "gltf_codecs.h"

namespace rtgltf {
namespace {

using json = nlohmann::json;

class DracoDecoder {
public:
    DracoDecoder(tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

    void primitive(size_t m, size_t p) {
        tinygltf::Primitive& prim = model_.meshes[m].primitives[p];
        const auto ext = prim.extensions.find("KHR_draco_mesh_compression");
        if (ext == prim.extensions.end()) return;
        where_ = "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p) +
                 "/extensions/KHR_draco_mesh_compression";
        const json e = to_json(ext->second);
        size_t view_index = 0;
        if (!e.is_object() || !whole_number(e.value("bufferView", json()), view_index) ||
            !e.value("attributes", json()).is_object())
            fail("needs a bufferView and an object of attributes");
        const int view = int(std::min<size_t>(view_index, INT32_MAX));
        const draco::Mesh& mesh = decoded(view);
        if (prim.indices < 0) fail("the primitive has no indices accessor, which a Draco primitive needs");
        if (claim(prim.indices, view, -1)) {
            std::vector<unsigned char> bytes(size_t(mesh.num_faces()) * 3 * 4);
            for (draco::FaceIndex f(0); f < mesh.num_faces(); ++f)
                for (int k = 0; k < 3; ++k) {
                    const uint32_t index = mesh.face(f)[k].value();
                    if (index >= mesh.num_points()) fail("the stream's faces name points it does not have");
                    std::memcpy(&bytes[(size_t(f.value()) * 3 + size_t(k)) * 4], &index, 4);
                }
            set(prim.indices, std::move(bytes), size_t(mesh.num_faces()) * 3, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
        }
        for (const auto& [name, id] : e["attributes"].items()) {
            const auto it = prim.attributes.find(name);
            if (it == prim.attributes.end()) continue;  // the primitive does not use it
            size_t number = 0;
            if (!whole_number(id, number)) fail("attributes/" + name + " must be a whole number");
            const int unique = int(std::min<size_t>(number, INT32_MAX));
            if (!claim(it->second, view, unique)) continue;
            const draco::PointAttribute* a = mesh.GetAttributeByUniqueId(uint32_t(unique));
            if (!a) fail("attributes/" + name + ": the stream has no attribute " + std::to_string(unique));
            const int components =
                tinygltf::GetNumComponentsInType(uint32_t(model_.accessors[size_t(it->second)].type));
            if (components != a->num_components())
                fail("attributes/" + name + ": the stream holds " + std::to_string(a->num_components()) +
                     " components a point, the accessor's type " + std::to_string(components));
            if (!a->is_mapping_identity() && a->indices_map_size() < mesh.num_points())
                fail("attributes/" + name + ": the stream maps fewer points than it has");
            std::vector<float> values(size_t(mesh.num_points()) * size_t(components));
            for (draco::PointIndex i(0); i < mesh.num_points(); ++i) {
                const draco::AttributeValueIndex v = a->mapped_index(i);
                if (v.value() >= a->size() ||
                    !a->ConvertValue<float>(v, int8_t(components), &values[size_t(i.value()) * size_t(components)]))
                    fail("attributes/" + name + ": the stream's values do not decode");
            }
            std::vector<unsigned char> bytes(values.size() * 4);
            std::memcpy(bytes.data(), values.data(), bytes.size());
            set(it->second, std::move(bytes), mesh.num_points(), TINYGLTF_COMPONENT_TYPE_FLOAT);
        }
    }

private:
    [[noreturn]] void fail(const std::string& what) const { throw Error(path_ + ": " + where_ + ": " + what); }

    // Bufferview `view`'s mesh, decoded the first time.
    const draco::Mesh& decoded(int view) {
        std::unique_ptr<draco::Mesh>& mesh = meshes_[view];
        if (mesh) return *mesh;
        if (size_t(view) >= model_.bufferViews.size()) fail("bufferView " + std::to_string(view) + " does not exist");
        const tinygltf::BufferView& v = model_.bufferViews[size_t(view)];
        const unsigned char* src =
            bytes_of(model_, v.buffer, v.byteOffset, v.byteLength, "/bufferViews/" + std::to_string(view), path_);
        draco::DecoderBuffer buffer;
        buffer.Init(reinterpret_cast<const char*>(src), v.byteLength);
        draco::Decoder decoder;
        auto result = decoder.DecodeMeshFromBuffer(&buffer);
        if (!result.ok())
            fail("its stream (bufferView " + std::to_string(view) + ", " + std::to_string(v.byteLength) +
                 " bytes) does not decode: truncated or corrupt (Draco: " + result.status().error_msg_string() + ")");
        mesh = std::move(result).value();
        return *mesh;
    }

    // Whether `accessor` is still to be decoded from (view, attribute): false when it was
    // already; an Error when another stream claimed it.
    bool claim(int accessor, int view, int attribute) {
        if (accessor < 0 || size_t(accessor) >= model_.accessors.size())
            fail("accessor " + std::to_string(accessor) + " does not exist");
        const auto [it, fresh] = source_.emplace(accessor, std::make_pair(view, attribute));
        if (!fresh && it->second != std::make_pair(view, attribute))
            fail("accessor " + std::to_string(accessor) + " is decoded from two Draco streams");
        return fresh;
    }

    void set(int accessor, std::vector<unsigned char> bytes, size_t count, int component) {
        tinygltf::Accessor& a = model_.accessors[size_t(accessor)];
        if (a.count != count)
            fail("accessor " + std::to_string(accessor) + " has count " + std::to_string(a.count) +
                 ", the stream holds " + std::to_string(count));
        a.bufferView = append_view(model_, std::move(bytes), 0);
        a.byteOffset = 0;
        a.componentType = component;
        a.normalized = false;
    }

    tinygltf::Model& model_;
    const std::string& path_;
    std::string where_;
    std::map<int, std::unique_ptr<draco::Mesh>> meshes_;  // bufferView -> its mesh
    std::map<int, std::pair<int, int>> source_;           // accessor -> (bufferView, attribute; -1: faces)
};

}  // namespace

void decode_draco(tinygltf::Model& model, const std::string& path) {
    DracoDecoder d(model, path);
    for (size_t m = 0; m < model.meshes.size(); ++m)
        for (size_t p = 0; p < model.meshes[m].primitives.size(); ++p) d.primitive(m, p);
}

}  // namespace rtgltf
#endif
