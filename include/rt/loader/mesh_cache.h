// Meshes shared by the scene files of one run, as an animation's frames share them: each
// PLY file is parsed once and each mesh's BVH built once per process, not once per
// frame. Entries are keyed by the file's path and a hash of its bytes, so a file that
// changed between two frames is read again, never served stale.
#pragma once
#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "rt/loader/ply.h"

namespace rt {

struct Scene;  // rt/geometry/scene.h

class MeshCache {
public:
    // The PLY file at `path` parsed (read_ply), and in `key` what identifies it: its path,
    // size and content hash. Parsed only when no file with that key was parsed before.
    std::shared_ptr<const PlyMesh> ply(const std::string& path, std::string& key);

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
    std::map<std::string, std::shared_ptr<const PlyMesh>> plys_;
    std::map<std::string, std::shared_ptr<const Scene>> scenes_;
    Counts counts_;
};

}  // namespace rt
