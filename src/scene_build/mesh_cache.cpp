// The meshes of one run's scene files (rt/scene_build/mesh_cache.h).
#include "rt/scene_build/mesh_cache.h"

#include "rt/geometry/scene.h"

namespace rt {

std::shared_ptr<const Scene> MeshCache::mesh_scene(const std::string& key, const std::function<Scene()>& make) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (auto it = scenes_.find(key); it != scenes_.end()) {
            ++counts_.build_reuses;
            return it->second;
        }
    }
    auto scene = std::make_shared<const Scene>(make());
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.builds;
    return scenes_.emplace(key, std::move(scene)).first->second;
}

MeshCache::Counts MeshCache::counts() const {
    const PlyCache::Counts p = ply_counts();
    std::lock_guard<std::mutex> lock(mutex_);
    Counts c = counts_;
    c.ply_reads = p.reads;
    c.ply_reuses = p.reuses;
    return c;
}

}  // namespace rt
