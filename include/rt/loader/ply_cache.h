// PLY files shared by the scene files of one run, as an animation's frames share them:
// each file is parsed once per process, not once per frame. Entries are keyed by the
// file's path and a hash of its bytes, so a file that changed between two frames is read
// again, never served stale. The loader reads PLY files through one when given it
// (rt/loader/load_scene.h); an animation's MeshCache (rt/scene_build/mesh_cache.h) is one,
// which also keeps each mesh's BVH.
#pragma once
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "rt/loader/ply.h"

namespace rt {

class PlyCache {
public:
    // The PLY file at `path` parsed (read_ply), and in `key` what identifies it: its path,
    // size and content hash. Parsed only when no file with that key was parsed before.
    std::shared_ptr<const PlyMesh> ply(const std::string& path, std::string& key);

    struct Counts {
        size_t reads = 0, reuses = 0;  // files parsed; times a parsed file was served again
    };
    Counts ply_counts() const;

private:
    mutable std::mutex mutex_;
    std::map<std::string, std::shared_ptr<const PlyMesh>> plys_;
    Counts counts_;
};

}  // namespace rt
