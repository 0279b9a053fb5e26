// Meshes shared by the scene files of one run, as an animation's frames share them: each
// PLY file is parsed once (PlyCache, which the loader reads them through) and each mesh's
// BVH built once per process (build_scene), not once per frame. Entries are keyed by the
// file's path and a hash of its bytes, so a file that changed between two frames is read
// again, never served stale.
#pragma once
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "rt/loader/ply_cache.h"

namespace rt {

struct Scene;  // rt/geometry/scene.h

class MeshCache : public PlyCache {
public:
    // The object-space scene (triangles and BVH) stored under `key`, made by `make` the
    // first time it is asked for.
    std::shared_ptr<const Scene> mesh_scene(const std::string& key, const std::function<Scene()>& make);

    struct Counts {
        size_t ply_reads = 0, ply_reuses = 0;  // files parsed; times a parsed file was served again
        size_t builds = 0, build_reuses = 0;   // mesh BVHs built; times one was served again
    };
    Counts counts() const;

private:
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const Scene>> scenes_;
    Counts counts_;
};

}  // namespace rt
