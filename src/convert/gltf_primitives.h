// Internal: glTF triangle primitives as the course's meshes (docs/gltf.md): accessors read
// with every range checked, flat shading recognised by the normals, vertices other writers
// split joined again, and the export's exact positions used while they still agree.
#pragma once
#include <nlohmann/json.hpp>

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "gltf_io.h"
#include "rt/core/affine.h"

namespace rt {

// The length of v, a - b, and p moved by m (a point, or a direction without the
// translation): the import keeps glTF's coordinates in double, whatever Real is.
inline double norm(const std::array<double, 3>& v) { return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]); }
inline std::array<double, 3> sub(const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
inline std::array<double, 3> apply(const Affine& m, const std::array<double, 3>& p, bool point) {
    std::array<double, 3> out;
    for (int r = 0; r < 3; ++r)
        out[size_t(r)] = m.m[r][0] * p[0] + m.m[r][1] * p[1] + m.m[r][2] * p[2] + (point ? m.m[r][3] : 0.0);
    return out;
}

// A triangle list from one POSITION accessor and one indices accessor.
struct GltfTriangles {
    std::vector<double> positions;  // x y z per vertex
    std::vector<uint32_t> indices;  // 3 per triangle, into positions / 3
    bool smooth = false;            // _shadingMode smooth
    std::array<double, 3> lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};  // the box
};

// The parts of `g` that share no vertex, each with its own vertices (in the order of their
// first use) and box: several where a pipeline joined meshes of one material into one.
std::vector<GltfTriangles> connected_parts(const GltfTriangles& g);
// Which of those parts each triangle is in (numbered in the order of first use); `parts`
// gets their count.
std::vector<uint32_t> part_of_triangles(const GltfTriangles& g, size_t& parts);
// The triangles of `g` in `groups` lists, triangle t in list group[t], each with its own
// vertices (in the order of their first use) and box.
std::vector<GltfTriangles> split_triangles(const GltfTriangles& g, const std::vector<uint32_t>& group, size_t groups);

class GltfPrimitives {
public:
    // `path` names the file in errors and warnings (appended to `warnings`).
    GltfPrimitives(const tinygltf::Model& model, const std::string& path, std::vector<std::string>& warnings)
        : model_(model), path_(path), warnings_(warnings) {}

    // Primitive p of mesh m, read once per accessor pair: every primitive showing the same
    // accessors gets the same pointer. nullptr for a primitive that is skipped, with a
    // warning (not a triangle list, no POSITION). Throws rt::InputError naming the element
    // for anything malformed.
    const GltfTriangles* get(int m, int p);

    // Accessor `index` as numbers, the components of `type` (TINYGLTF_TYPE_VEC3, ...) per
    // element: floats, or KHR_mesh_quantization's integers (normalised or not) dequantised.
    // `where` names its user. Throws rt::InputError naming the accessor.
    std::vector<double> numbers(int index, int type, const std::string& where) const;

    // The vertices of primitive p's corners as the file numbers them (its indices, or 0, 1, 2,
    // ... without), whole triangles: triangle t of get(m, p) is corners 3t to 3t + 2.
    std::vector<uint32_t> corners(int m, int p) const;

private:
    [[noreturn]] void fail(const std::string& element, const std::string& what) const;
    void warn(const std::string& what) { warnings_.push_back(path_ + ": " + what); }

    struct View {
        const unsigned char* data = nullptr;  // null: all zeros (no bufferView)
        size_t stride = 0, count = 0;
    };
    View view(int index, int component, int type, const std::string& where) const;
    std::vector<uint32_t> indices(int index, size_t vertices, const std::string& where) const;

    const tinygltf::Model& model_;
    const std::string& path_;
    std::vector<std::string>& warnings_;
    std::map<std::pair<int, int>, GltfTriangles> read_;  // (POSITION, indices) -> triangles
    std::set<std::string> skipped_;
};

}  // namespace rt
