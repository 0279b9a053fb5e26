// glTF files in and out (gltf_io.h): tinygltf's code is compiled here, once, without
// its image reading and writing (TINYGLTF_NO_STB_IMAGE*, TINYGLTF_NO_EXTERNAL_IMAGE):
// textures are not in the course's format, and an image it cannot read must not stop a
// conversion that does not need it. Nothing here depends on the precision: one copy, in
// the double library, serves both (namespace rtgltf, which the float copy's -Drt=rt_float
// leaves alone; see rt/cli/options.h).
#ifndef RT_NO_GLTF  // built without tinygltf (mk/convert.mk): glTF is refused with an error
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#endif
#include "gltf_io.h"  // includes tiny_gltf.h, here with its implementation

#include <cstring>
#include <regex>
#include <sstream>

namespace rtgltf {
#ifndef RT_NO_GLTF
namespace {

// Images are skipped, not decoded: the importer warns about the textures that use them.
bool skip_image(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
    return true;
}

// tinygltf's first error line, with its "buffer[2]"-style names made JSON pointers.
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '.')) line.pop_back();
    static const std::regex kIndexed(R"(\b(buffer|bufferView|accessor|mesh|node|image|material|camera)s?\[(\d+)\])");
    return std::regex_replace(line, kIndexed, "/$1s/$2");
}

}  // namespace

void parse(const std::string& bytes, const std::string& path, const std::string& base_dir, tinygltf::Model& model,
           std::vector<std::string>& warnings) {
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skip_image, nullptr);
    std::string err, warn;
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    if (binary && bytes.size() >= 12) {  // the GLB header: magic, version, total length
        uint32_t length;
        std::memcpy(&length, bytes.data() + 8, 4);
        if (length > bytes.size())
            throw Error(path + ": truncated: its GLB header says " + std::to_string(length) + " bytes, the file has " +
                        std::to_string(bytes.size()));
    }
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok = binary
                        ? gltf.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(bytes.size()), base_dir)
                        : gltf.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base_dir);
    if (!ok || !err.empty()) {
        std::string what = err.empty() ? std::string("not a glTF file") : first_line(err);
        // "File not found : x.bin": which buffer or image names it.
        static const std::string kNotFound = "File not found : ";
        if (!binary && what.rfind(kNotFound, 0) == 0) {
            const std::string file = what.substr(kNotFound.size());
            const nlohmann::json j = nlohmann::json::parse(bytes, nullptr, false);
            for (const char* kind : {"buffers", "images"})
                if (j.is_object() && j.contains(kind) && j[kind].is_array())
                    for (size_t i = 0; i < j[kind].size(); ++i)
                        if (j[kind][i].is_object() && j[kind][i].value("uri", "") == file)
                            what = std::string("/") + kind + "/" + std::to_string(i) + ": its file " + file +
                                   " is missing (looked in " + base_dir + ")";
        }
        throw Error(path + ": " + what);
    }
    std::istringstream lines(warn);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) warnings.push_back(path + ": " + first_line(line));
}

Serialized serialize(tinygltf::Model& model, bool binary, const std::string& bin_name) {
    Serialized out;
    std::ostringstream text;
    tinygltf::TinyGLTF gltf;
    if (binary || model.buffers.empty()) {
        if (!gltf.WriteGltfSceneToStream(&model, text, /*prettyPrint=*/true, binary))
            throw Error("tinygltf could not write the model");
        out.main = text.str();
        return out;
    }
    // .gltf: tinygltf's stream writer embeds buffers as data URIs; buffer 0 goes beside
    // the file instead, and the JSON names it.
    std::vector<unsigned char> data = std::move(model.buffers[0].data);
    model.buffers[0].data.clear();
    const bool ok = gltf.WriteGltfSceneToStream(&model, text, /*prettyPrint=*/true, false);
    model.buffers[0].data = std::move(data);
    if (!ok) throw Error("tinygltf could not write the model");
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(text.str());
    j["buffers"][0]["uri"] = bin_name;
    j["buffers"][0]["byteLength"] = model.buffers[0].data.size();
    out.main = j.dump(2) + "\n";
    out.bin.assign(reinterpret_cast<const char*>(model.buffers[0].data.data()), model.buffers[0].data.size());
    return out;
}

nlohmann::json to_json(const tinygltf::Value& v) {
    switch (v.Type()) {
        case tinygltf::BOOL_TYPE:
            return v.Get<bool>();
        case tinygltf::INT_TYPE:
            return v.Get<int>();
        case tinygltf::REAL_TYPE:
            return v.Get<double>();
        case tinygltf::STRING_TYPE:
            return v.Get<std::string>();
        case tinygltf::ARRAY_TYPE: {
            nlohmann::json a = nlohmann::json::array();
            for (size_t i = 0; i < v.ArrayLen(); ++i) a.push_back(to_json(v.Get(int(i))));
            return a;
        }
        case tinygltf::OBJECT_TYPE: {
            nlohmann::json o = nlohmann::json::object();
            for (const std::string& k : v.Keys()) o[k] = to_json(v.Get(k));
            return o;
        }
        default:
            return nullptr;
    }
}

tinygltf::Value to_value(const nlohmann::json& j) {
    if (j.is_boolean()) return tinygltf::Value(j.get<bool>());
    if (j.is_number_integer()) return tinygltf::Value(j.get<int>());
    if (j.is_number()) return tinygltf::Value(j.get<double>());
    if (j.is_string()) return tinygltf::Value(j.get<std::string>());
    if (j.is_array()) {
        tinygltf::Value::Array a;
        for (const auto& e : j) a.push_back(to_value(e));
        return tinygltf::Value(std::move(a));
    }
    if (j.is_object()) {
        tinygltf::Value::Object o;
        for (auto it = j.begin(); it != j.end(); ++it) o[it.key()] = to_value(it.value());
        return tinygltf::Value(std::move(o));
    }
    return tinygltf::Value();
}
#endif  // RT_NO_GLTF

}  // namespace rtgltf
