// Internal: materials whose textures are palettes (docs/gltf.md, "Files that pipelines
// wrote"). glTF Transform's palette step merges materials that differ only in their base
// colour (or metallic and roughness) into one, whose texture holds one texel per merged
// material, every corner of a triangle at its material's texel. The course's format has no
// textures, but such a texture is a material per triangle: here each triangle's texel, read
// from the decoded image (stb_image, PNG or JPEG), and the course's materials are made of them
// by import_materials (gltf_import.h).
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "gltf_io.h"
#include "gltf_primitives.h"

namespace rt {

#ifndef RT_NO_GLTF
// What a triangle's texels say of its material: the 8-bit values of the base colour texel
// (sRGB-encoded, as glTF stores base colour) and of the metallic-roughness texel (its G is
// roughness, its B metalness, linear); -1 where the material has no such texture.
struct PaletteTexel {
    int material = -1;  // the glTF material
    std::array<int, 3> base{-1, -1, -1};
    int roughness = -1, metallic = -1;
    // The exported material (texel_matches' `listed`) of its triangles where several tie and
    // their places told them apart; -1: the first that matches.
    int listed = -1;
    bool operator<(const PaletteTexel& o) const {
        return std::tie(material, base, roughness, metallic, listed) <
               std::tie(o.material, o.base, o.roughness, o.metallic, o.listed);
    }
};

class GltfPalettes {
public:
    // `path`: the glTF file's, whose folder holds the images a .gltf names by uri; a
    // warning for an image that cannot be read goes to `warnings`.
    GltfPalettes(const tinygltf::Model& model, const GltfPrimitives& primitives, const std::string& path,
                 std::vector<std::string>& warnings)
        : model_(model), primitives_(primitives), path_(path), warnings_(warnings) {}

    // The texels of each triangle of primitive p of mesh m, when its material's base colour
    // or metallic-roughness texture is a palette for it: every triangle's corners in one
    // texel of each (nearest sampling, repeat), no KHR_texture_transform. Empty otherwise
    // (no such texture, an image that cannot be read or does not decode, corners that
    // span texels: a texture, whose factors the import uses, with a warning). Throws
    // rt::InputError naming the accessor for a malformed TEXCOORD.
    std::vector<PaletteTexel> triangle_texels(int m, int p);

private:
    struct Decoded {
        int width = 0, height = 0;
        std::vector<unsigned char> rgba;  // empty: not decoded
    };
    const Decoded& image_of(int texture);

    const tinygltf::Model& model_;
    const GltfPrimitives& primitives_;
    const std::string& path_;
    std::vector<std::string>& warnings_;
    std::map<int, Decoded> decoded_;  // texture index -> its image, decoded once
};

// glTF's sRGB transfer function, an 8-bit value to linear and linear to [0, 1] encoded.
double srgb_to_linear(int value8);
double linear_to_srgb(double linear);
#endif

}  // namespace rt
