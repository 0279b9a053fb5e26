// glTF files in and out (gltf_io.h): tinygltf's code is compiled here, once, without
// its image reading and writing (TINYGLTF_NO_STB_IMAGE*, TINYGLTF_NO_EXTERNAL_IMAGE):
// textures are not in the course's format, and an image it cannot read must not stop a
// conversion that does not need it.
#ifndef RT_NO_GLTF  // built without tinygltf (mk/convert.mk): glTF is refused with an error
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE
#define TINYGLTF_NO_INCLUDE_STB_IMAGE_WRITE
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#include <tiny_gltf.h>
#pragma GCC diagnostic pop
#endif

#include <filesystem>
#include <regex>
#include <sstream>

#include "gltf_io.h"
#include "rt/core/error.h"
#include "rt/io/atomic_file.h"
#include "rt/io/files.h"

namespace rt {
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

void load_gltf(const std::string& path, tinygltf::Model& model, std::vector<std::string>& warnings) {
    const std::string bytes = read_text_file(path);
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(skip_image, nullptr);
    std::string err, warn;
    const std::string dir = dirname_of(path);
    const std::string base = dir.empty() ? "." : dir;
    const bool binary = bytes.size() >= 4 && bytes.compare(0, 4, "glTF") == 0;
    const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
    const bool ok = binary ? gltf.LoadBinaryFromMemory(&model, &err, &warn, data, unsigned(bytes.size()), base)
                           : gltf.LoadASCIIFromString(&model, &err, &warn, bytes.data(), unsigned(bytes.size()), base);
    if (!ok || !err.empty())
        throw InputError(path + ": " + (err.empty() ? std::string("not a glTF file") : first_line(err)));
    std::istringstream lines(warn);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) warnings.push_back(path + ": " + first_line(line));
}

std::vector<std::string> save_gltf(tinygltf::Model& model, const std::string& path) {
    const bool binary = lower_extension(path) == ".glb";
    std::vector<std::string> written{path};
    std::string bin_path;
    if (!binary && !model.buffers.empty()) {
        namespace fs = std::filesystem;
        const fs::path p(path);
        model.buffers[0].uri = p.stem().string() + ".bin";
        bin_path = (p.parent_path() / model.buffers[0].uri).string();
        const std::vector<unsigned char>& data = model.buffers[0].data;
        write_file_atomic(bin_path, std::string_view(reinterpret_cast<const char*>(data.data()), data.size()));
        written.push_back(bin_path);
    }
    std::ostringstream out;
    tinygltf::TinyGLTF gltf;
    if (!gltf.WriteGltfSceneToStream(&model, out, /*prettyPrint=*/true, binary))
        throw InputError(path + ": cannot write the glTF");
    write_file_atomic(path, out.str());
    return written;
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

}  // namespace rt
