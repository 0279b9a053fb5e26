// The PLY files of one run's scene files (rt/loader/ply_cache.h).
#include "rt/loader/ply_cache.h"

#include <cstdint>
#include <cstdio>
#include <string_view>

#include "file_bytes.h"

namespace rt {

std::shared_ptr<const PlyMesh> PlyCache::ply(const std::string& path, std::string& key) {
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
            ++counts_.reuses;
            return it->second;
        }
    }
    auto mesh = std::make_shared<const PlyMesh>(parse_ply(reinterpret_cast<const char*>(f.data()), f.size(), path));
    std::lock_guard<std::mutex> lock(mutex_);
    ++counts_.reads;
    return plys_.emplace(key, std::move(mesh)).first->second;
}

PlyCache::Counts PlyCache::ply_counts() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return counts_;
}

}  // namespace rt
