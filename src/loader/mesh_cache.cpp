// The meshes of one run's scene files (rt/loader/mesh_cache.h).
#include "rt/loader/mesh_cache.h"

#include <cstdint>
#include <cstdio>
#include <string_view>

#include "file_bytes.h"
#include "rt/geometry/scene.h"

namespace rt {

std::shared_ptr<const PlyMesh> MeshCache::ply(const std::string& path, std::string& key) {
    ply_reader::FileBytes f;
    f.load(path);
    const uint64_t hash =
        std::hash<std::string_view>{}(std::string_view(reinterpret_cast<const char*>(f.data()), f.size()));
    char id[64];
    std::snprintf(id, sizeof id, "|%zu|%016llx", f.size(), static_cast<unsigned long long>(hash));
    key = path + id;
    {
        std::lock_guard<std::mutex> lock(mutex_);
        if (auto it = plys_.find(key); it != plys_.end()) {
            ++counts_.ply_reuses;
            return it->second;
        }
    }
    auto mesh = std::make_shared<const PlyMesh>(parse_ply(reinterpret_cast<const char*>(f.data()), f.size(), path));
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.ply_reads;
    return plys_.emplace(key, std::move(mesh)).first->second;
}

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
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

}  // namespace rt
