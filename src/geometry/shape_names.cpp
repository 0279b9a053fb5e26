// ShapeNames::name: a primitive as the scene file names it (rt/geometry/shape_names.h).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "rt/geometry/shape_names.h"

namespace rt {

void NameList::push_back(std::string_view id, const char* key) {
    if (chars_.size() + id.size() > UINT32_MAX) throw std::length_error("NameList: more than 4 GiB of names");
    if (key) keys_.emplace_back(static_cast<uint32_t>(ends_.size()), key);
    chars_ += id;
    ends_.push_back(static_cast<uint32_t>(chars_.size()));
}

const char* NameList::key(size_t i) const {
    auto it = std::lower_bound(keys_.begin(), keys_.end(), i, [](const auto& e, size_t j) { return e.first < j; });
    return it != keys_.end() && it->first == i ? it->second : nullptr;
}

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
    const NameList& named = ids[size_t(s.kind)];
    return visit_shape<std::string>(s.kind, [&](auto k) {
        using S = decltype(k);
        if (s.index >= named.size()) return S::Desc::kNoun + (" #" + index);
        const char* key = named.key(s.index);
        return std::string(key ? key : S::Desc::kKey) + " " + std::string(named.id(s.index));
    });
}

}  // namespace rt
