// The PLY files a scene names, read after its tree is walked (rt/loader/scene_tree.h).
#include <chrono>
#include <cmath>

#include "json_fields.h"
#include "rt/core/error.h"
#include "rt/loader/ply.h"
#include "rt/loader/ply_cache.h"
#include "rt/loader/scene_tree.h"

namespace rt {

void read_mesh_files(SceneDesc& desc, PlyCache* meshes) {
    const JsonFields scene(desc.path);  // its errors: "<scene>: <pointer>: <what>"
    for (MeshDesc& mesh : desc.meshes) {
        if (mesh.ply_pointer.empty()) continue;
        const auto fail = [&](const std::string& what) { scene.fail(mesh.ply_pointer, what); };
        const auto t0 = std::chrono::steady_clock::now();
        PlyMesh pm;
        try {
            // From the cache, an animation's meshes are parsed once for all frames.
            pm = meshes ? *meshes->ply(mesh.source, mesh.content_key) : read_ply(mesh.source);
        } catch (const InputError& e) {
            fail(e.what());
        }
        for (size_t i = 0; i < pm.positions.size(); ++i)
            for (int a = 0; a < 3; ++a)
                if (!(std::fabs(pm.positions[i][a]) <= kMaxMagnitude))
                    fail(mesh.source + ": vertex " + std::to_string(i) +
                         ": coordinate beyond +-1e30: " + JsonFields::format_number(pm.positions[i][a]));
        mesh.positions = std::move(pm.positions);
        mesh.indices = std::move(pm.indices);
        mesh.ply_pointer.clear();
        desc.ply_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
}

}  // namespace rt
