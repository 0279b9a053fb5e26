// ShapeNames::name: a primitive as the scene file names it (rt/geometry/shape_names.h).
#include <string>

#include "rt/geometry/shape_names.h"

namespace rt {

std::string ShapeNames::name(ShapeRef s) const {
    const std::string index = std::to_string(s.index);
    if (s.kind == ShapeKind::Triangle) {
        // The last mesh starting at or before the triangle (meshes left empty by
        // skipped faces share their first_triangle with the next one).
        const Mesh* found = last_starting_at(meshes, s.index, &Mesh::first_triangle);
        if (!found) return "triangle #" + index;
        const Mesh& m = *found;
        if (m.triangle_object) return "Triangle " + m.id;
        uint32_t face = s.index - m.first_triangle;
        for (uint32_t skipped_face : m.skipped) {
            if (skipped_face > face) break;
            ++face;
        }
        return "Mesh " + m.id + ", face " + std::to_string(face);
    }
    const std::vector<std::string>& named = ids[size_t(s.kind)];
    return visit_shape<std::string>(s.kind, [&](auto k) {
        using S = decltype(k);
        if (s.index >= named.size()) return S::kNoun + (" #" + index);
        const char* key = keys[size_t(s.kind)][s.index];
        return std::string(key ? key : S::kKey) + " " + named[s.index];
    });
}

}  // namespace rt
