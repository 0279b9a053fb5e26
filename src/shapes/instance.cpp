// Mesh instances (rt/shapes/instance.h): the render form built from the desc, and the
// polygons of the export. The ray test, a traversal of the mesh's own scene, is in
// src/geometry/instance.cpp.
#include "rt/shapes/instance.h"

#include "rt/loader/scene_desc.h"

namespace rt {

Instance Instance::build(const Desc& d, const BuildInputs& in) {
    return {in.mesh_scenes.at(d.mesh).get(), d.transform.inverse(), d.material, d.motion, !is_still(d.motion)};
}

const std::vector<Vec3>& Instance::mesh_positions(const Desc& d, const std::vector<MeshDesc>& meshes) {
    return meshes.at(d.mesh).positions;
}

Polygons mesh_polygons(const MeshDesc& m, const Affine& to_world) {
    Polygons out;
    out.smooth = m.shading == ShadingMode::Smooth;
    out.vertices = m.positions;
    out.faces.reserve(m.indices.size() / 3);
    for (size_t i = 0; i + 2 < m.indices.size(); i += 3)
        out.faces.push_back({m.indices[i], m.indices[i + 1], m.indices[i + 2]});
    out.move(to_world);
    return out;
}

Polygons Instance::polygons(const Desc& d, const ExportFrame& f) {
    return mesh_polygons(f.meshes->at(d.mesh), d.transform);
}

}  // namespace rt
