// Palette textures as a material per triangle (gltf_palette.h, docs/gltf.md).
#include "gltf_palette.h"

#include <cctype>
#include <cmath>
#include <limits>
#include <string>

#include <stb/stb_image.h>

#include "rt/core/error.h"
#include "rt/io/files.h"

namespace rt {
#ifndef RT_NO_GLTF

double srgb_to_linear(int value8) {
    const double c = value8 / 255.0;
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double linear) {
    const double c = std::fmin(std::fmax(linear, 0.0), 1.0);
    return c <= 0.0031308 ? c * 12.92 : 1.055 * std::pow(c, 1 / 2.4) - 0.055;
}

namespace {

// Larger images are not palettes; the bound keeps a hostile file from making the decoder
// allocate gigabytes.
constexpr int kMaxPalettePixels = 1 << 22;

// A URI's %XX escapes decoded (glTF writers escape spaces and the like in file names).
std::string percent_decoded(const std::string& uri) {
    std::string out;
    for (size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
            out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += uri[i];
        }
    }
    return out;
}

}  // namespace

const GltfPalettes::Decoded& GltfPalettes::image_of(int texture) {
    if (const auto it = decoded_.find(texture); it != decoded_.end()) return it->second;
    Decoded& d = decoded_[texture];
    if (texture < 0 || size_t(texture) >= model_.textures.size()) return d;
    const int source = model_.textures[size_t(texture)].source;
    if (source < 0 || size_t(source) >= model_.images.size()) return d;
    const tinygltf::Image& image = model_.images[size_t(source)];
    const unsigned char* bytes = nullptr;
    size_t size = 0;
    std::string file;
    if (image.bufferView >= 0) {  // in a buffer: every range checked
        if (size_t(image.bufferView) >= model_.bufferViews.size()) return d;
        const tinygltf::BufferView& bv = model_.bufferViews[size_t(image.bufferView)];
        if (bv.buffer < 0 || size_t(bv.buffer) >= model_.buffers.size()) return d;
        const std::vector<unsigned char>& buf = model_.buffers[size_t(bv.buffer)].data;
        if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset) return d;
        bytes = buf.data() + bv.byteOffset;
        size = bv.byteLength;
    } else if (!image.image.empty()) {  // a data URI, its bytes kept by the parse (gltf_io.cpp)
        bytes = image.image.data();
        size = image.image.size();
    } else if (!image.uri.empty()) {  // a file beside a .gltf, named relative to it
        try {
            file = read_text_file(dirname_of(path_) + percent_decoded(image.uri));
        } catch (const InputError& e) {
            warnings_.push_back(path_ + ": /images/" + std::to_string(source) + ": " + e.what());
            return d;
        }
        bytes = reinterpret_cast<const unsigned char*>(file.data());
        size = file.size();
    }
    if (size == 0 || size > size_t(std::numeric_limits<int>::max())) return d;
    int w = 0, h = 0, channels = 0;
    if (!stbi_info_from_memory(bytes, int(size), &w, &h, &channels) || w <= 0 || h <= 0 || w > kMaxPalettePixels / h)
        return d;
    unsigned char* pixels = stbi_load_from_memory(bytes, int(size), &w, &h, &channels, 4);
    if (!pixels) return d;
    d.width = w;
    d.height = h;
    d.rgba.assign(pixels, pixels + size_t(w) * size_t(h) * 4);
    stbi_image_free(pixels);
    return d;
}

std::vector<PaletteTexel> GltfPalettes::triangle_texels(int m, int p) {
    const tinygltf::Primitive& prim = model_.meshes[size_t(m)].primitives[size_t(p)];
    if (prim.material < 0 || size_t(prim.material) >= model_.materials.size()) return {};
    const tinygltf::PbrMetallicRoughness& pbr = model_.materials[size_t(prim.material)].pbrMetallicRoughness;
    const std::string where = "/meshes/" + std::to_string(m) + "/primitives/" + std::to_string(p);
    const std::vector<uint32_t> corners = primitives_.corners(m, p);
    std::vector<PaletteTexel> out(corners.size() / 3);
    for (PaletteTexel& t : out) t.material = prim.material;
    bool any = false;
    // Each texture's texel per triangle, into `set`; false when it is not a palette here.
    auto read = [&](const tinygltf::TextureInfo& info, auto&& set) {
        if (info.index < 0) return true;
        if (info.extensions.count("KHR_texture_transform")) return false;
        const auto uv = prim.attributes.find("TEXCOORD_" + std::to_string(info.texCoord));
        if (uv == prim.attributes.end()) return false;
        const Decoded& image = image_of(info.index);
        if (image.rgba.empty()) return false;
        const std::vector<double> st =
            primitives_.numbers(uv->second, TINYGLTF_TYPE_VEC2, where + "/attributes/" + uv->first);
        auto texel = [&](uint32_t v) -> long {
            if (2 * size_t(v) + 1 >= st.size()) return -1;
            const double s = st[2 * v], t = st[2 * v + 1];
            const double x = std::floor((s - std::floor(s)) * image.width),
                         y = std::floor((t - std::floor(t)) * image.height);
            if (!(x >= 0 && y >= 0)) return -1;
            return long(std::fmin(y, image.height - 1)) * image.width + long(std::fmin(x, image.width - 1));
        };
        for (size_t i = 0; i < out.size(); ++i) {
            const long a = texel(corners[3 * i]);
            if (a < 0 || texel(corners[3 * i + 1]) != a || texel(corners[3 * i + 2]) != a) return false;
            set(out[i], &image.rgba[4 * size_t(a)]);
        }
        any = true;
        return true;
    };
    const bool palette = read(pbr.baseColorTexture,
                              [](PaletteTexel& t, const unsigned char* px) {
                                  t.base = {px[0], px[1], px[2]};
                              }) &&
                         read(pbr.metallicRoughnessTexture, [](PaletteTexel& t, const unsigned char* px) {
                             t.roughness = px[1];
                             t.metallic = px[2];
                         });
    if (!palette || !any) return {};
    return out;
}

#endif  // RT_NO_GLTF
}  // namespace rt
