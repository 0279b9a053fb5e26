// glTF files in and out (gltf_io.h): tinygltf's code is compiled here, once, without
// its image reading and writing (TINYGLTF_NO_STB_IMAGE*, TINYGLTF_NO_EXTERNAL_IMAGE):
// textures are not in the course's format (but for palettes, which the import decodes
// itself), and an image it cannot read must not stop a conversion that does not need it. Nothing here depends on the
// precision: one copy, in the double library, serves both (namespace rtgltf, which the float copy's -Drt=rt_float
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
#include "gltf_codecs.h"

#include <cstring>
#include <regex>
#include <sstream>

namespace rtgltf {
#ifndef RT_NO_GLTF
namespace {

// Images are not decoded here: the import reads the palettes it can use (gltf_palette.h)
// from their bufferViews, checking their ranges, and warns about other textures. A data
// URI's bytes, which are nowhere else, are kept as they are.
bool keep_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                int size, void*) {
    if (image->bufferView < 0 && bytes && size > 0) {
        image->image.assign(bytes, bytes + size);
        image->as_is = true;
    }
    return true;
}

// tinygltf's first error line, with its "buffer[2]"-style names made JSON pointers.
std::string first_line(const std::string& text) {
    std::string line = text.substr(0, text.find('\n'));
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '.')) line.pop_back();
    static const std::regex kIndexed(R"(\b(buffer|bufferView|accessor|mesh|node|image|material|camera)s?\[(\d+)\])");
    return std::regex_replace(line, kIndexed, "/$1s/$2");
}

// tinygltf writes zfar 0 for a perspective camera without one (its "infinite"); glTF has
// no zfar 0: an infinite projection leaves it out.
void drop_zero_zfar(nlohmann::ordered_json& j) {
    if (!j.contains("cameras")) return;
    for (auto& c : j["cameras"])
        if (c.contains("perspective") && c["perspective"].value("zfar", 1.0) == 0.0) c["perspective"].erase("zfar");
}

void append_u32(std::string& out, uint32_t v) {
    char b[4];
    std::memcpy(b, &v, 4);  // GLB is little-endian, as every target here
    out.append(b, 4);
}

// A GLB container: the 12-byte header, the JSON chunk (padded with spaces) and, when `bin`
// is not empty, the BIN chunk (padded with zeros), each 4-byte aligned.
std::string glb(std::string json, const std::string& bin) {
    json.append((4 - json.size() % 4) % 4, ' ');
    const size_t bin_padded = bin.size() + (4 - bin.size() % 4) % 4;
    const size_t total = 12 + 8 + json.size() + (bin.empty() ? 0 : 8 + bin_padded);
    if (total > UINT32_MAX) throw Error("the model is too large for a GLB file (over 4 GiB)");
    std::string out = "glTF";
    append_u32(out, 2);
    append_u32(out, uint32_t(total));
    append_u32(out, uint32_t(json.size()));
    out += "JSON";
    out += json;
    if (!bin.empty()) {
        append_u32(out, uint32_t(bin_padded));
        out.append("BIN\0", 4);
        out += bin;
        out.append(bin_padded - bin.size(), '\0');
    }
    return out;
}

// The JSON and BIN chunks of a GLB container; false when it is not one (tinygltf names what
// is wrong).
bool split_glb(const std::string& bytes, std::string& json, std::string& bin) {
    auto u32 = [&](size_t at) {
        uint32_t v;
        std::memcpy(&v, bytes.data() + at, 4);
        return size_t(v);
    };
    if (bytes.size() < 20 || bytes.compare(16, 4, "JSON") != 0 || u32(12) > bytes.size() - 20) return false;
    json = bytes.substr(20, u32(12));
    const size_t next = 20 + u32(12);
    bin.clear();
    if (bytes.size() >= next + 8 && bytes.compare(next + 4, 4, std::string("BIN\0", 4)) == 0 &&
        u32(next) <= bytes.size() - next - 8)
        bin = bytes.substr(next + 8, u32(next));
    return true;
}

}  // namespace

void parse(const std::string& file_bytes, const std::string& path, const std::string& base_dir, tinygltf::Model& model,
           std::vector<std::string>& warnings) {
    tinygltf::TinyGLTF gltf;
    gltf.SetImageLoader(keep_image, nullptr);
    std::string err, warn;
    const bool binary = file_bytes.size() >= 4 && file_bytes.compare(0, 4, "glTF") == 0;
    if (binary && file_bytes.size() >= 12) {  // the GLB header: magic, version, total length
        uint32_t length;
        std::memcpy(&length, file_bytes.data() + 8, 4);
        if (length > file_bytes.size())
            throw Error(path + ": truncated: its GLB header says " + std::to_string(length) + " bytes, the file has " +
                        std::to_string(file_bytes.size()));
    }
    // The extensions it requires checked, and a compressed file's JSON made one tinygltf
    // reads (gltf_codecs.h); JSON that does not parse is left to tinygltf's error.
    Compressed compressed;
    std::string rewritten;
    std::string json_text, bin;
    if (binary ? split_glb(file_bytes, json_text, bin) : (json_text = file_bytes, true)) {
        nlohmann::json j = nlohmann::json::parse(json_text, nullptr, false);
        if (!j.is_discarded() && prepare(j, path, compressed, warnings))
            rewritten = binary ? glb(j.dump(), bin) : j.dump();
    }
    const std::string& bytes = rewritten.empty() ? file_bytes : rewritten;
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
    decode(model, compressed, path);
    std::istringstream lines(warn);
    for (std::string line; std::getline(lines, line);)
        if (!line.empty()) warnings.push_back(path + ": " + first_line(line));
}

Serialized serialize(tinygltf::Model& model, bool binary, const std::string& bin_name) {
    // tinygltf writes the JSON, buffer 0's bytes set aside (it would embed them as a data
    // URI); then the fix above, and buffer 0 named: the .bin beside a .gltf, or the BIN
    // chunk of a .glb.
    std::vector<unsigned char> bin;
    if (!model.buffers.empty()) std::swap(bin, model.buffers[0].data);
    std::ostringstream text;
    const bool ok = tinygltf::TinyGLTF().WriteGltfSceneToStream(&model, text, /*prettyPrint=*/true, false);
    if (!model.buffers.empty()) std::swap(bin, model.buffers[0].data);
    if (!ok) throw Error("tinygltf could not write the model");
    nlohmann::ordered_json j = nlohmann::ordered_json::parse(text.str());
    drop_zero_zfar(j);
    Serialized out;
    if (!model.buffers.empty()) {
        const std::vector<unsigned char>& bytes = model.buffers[0].data;
        out.bin.assign(reinterpret_cast<const char*>(bytes.data()), bytes.size());
        if (binary)
            j["buffers"][0].erase("uri");
        else
            j["buffers"][0]["uri"] = bin_name;
        j["buffers"][0]["byteLength"] = bytes.size();
    }
    if (!binary) {
        out.main = j.dump(2) + "\n";
        return out;
    }
    out.main = glb(j.dump(), out.bin);
    out.bin.clear();
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
