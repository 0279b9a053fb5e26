// ShapeNames::name: a primitive as the scene file names it (rt/geometry/scene.h).
#include <string>

#include "rt/geometry/scene.h"

namespace rt {

std::string ShapeNames::name(ShapeRef s) const {
    const std::string index = std::to_string(s.index);
    switch (s.kind) {
        case ShapeKind::Triangle: {
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
        case ShapeKind::Sphere:
            return s.index < spheres.size() ? "Sphere " + spheres[s.index] : "sphere #" + index;
        case ShapeKind::Plane:
            return s.index < planes.size() ? "Plane " + planes[s.index] : "plane #" + index;
    }
    return "?";
}

}  // namespace rt
