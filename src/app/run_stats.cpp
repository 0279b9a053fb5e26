// The --stats document, the progress line and the process figures.
#include "progress.h"

#include <sys/resource.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <thread>

#include "rt/app/run.h"
#include "rt/core/real.h"

namespace rt {
namespace app {

uint64_t peak_rss_bytes() {
    struct rusage u {};
    if (::getrusage(RUSAGE_SELF, &u) != 0) return 0;
    return static_cast<uint64_t>(u.ru_maxrss) * 1024;  // Linux: KiB
}

uint64_t resident_bytes() {
    std::ifstream f("/proc/self/statm");
    uint64_t size = 0, resident = 0;
    if (!(f >> size >> resident)) return 0;
    return resident * static_cast<uint64_t>(::sysconf(_SC_PAGESIZE));
}

std::string cpu_model() {
    std::ifstream f("/proc/cpuinfo");
    for (std::string line; std::getline(f, line);) {
        if (line.rfind("model name", 0) != 0) continue;
        const size_t colon = line.find(':');
        if (colon == std::string::npos) break;
        const size_t start = line.find_first_not_of(" \t", colon + 1);
        return start == std::string::npos ? "unknown" : line.substr(start);
    }
    return "unknown";
}

bool stderr_is_terminal() { return ::isatty(STDERR_FILENO) == 1; }

void ProgressLine::start(const std::string& label) {
    label_ = label;
    t0_ = std::chrono::steady_clock::now();
}

void ProgressLine::update(int done, int total) {
    if (!enabled_ || total <= 0) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
    char buf[512];
    int n;
    if (done > 0) {
        const double left = elapsed * double(total - done) / double(done);
        n = std::snprintf(buf, sizeof buf, "%s: %3d%%  %.1f s elapsed, ~%.1f s left", label_.c_str(),
                          int(100.0 * done / total), elapsed, left);
    } else {
        n = std::snprintf(buf, sizeof buf, "%s:   0%%  %.1f s elapsed", label_.c_str(), elapsed);
    }
    if (n < 0) return;
    const size_t len = std::min(static_cast<size_t>(n), sizeof buf - 1);
    // Pad with spaces over a longer previous line, then return to the line's start.
    std::fprintf(stderr, "\r%s%*s", buf, shown_ > len ? int(shown_ - len) : 0, "");
    std::fflush(stderr);
    shown_ = std::max(shown_, len);
}

void ProgressLine::clear() {
    if (!enabled_ || shown_ == 0) return;
    std::fprintf(stderr, "\r%*s\r", int(shown_), "");
    std::fflush(stderr);
    shown_ = 0;
}

}  // namespace app

std::string stats_json(const std::vector<ImageRecord>& images, const std::string& version) {
    using nlohmann::ordered_json;
    ordered_json doc;
    doc["raytracer"] = version;
    doc["precision"] = kPrecisionName;
    doc["machine"] = {{"cpu", app::cpu_model()}, {"hardware_threads", std::thread::hardware_concurrency()}};
    ordered_json list = ordered_json::array();
    for (const ImageRecord& r : images) {
        const RayCounts& rays = r.render_stats.rays;
        ordered_json j;
        j["scene"] = r.scene;
        j["image"] = r.image;
        j["camera"] = r.camera;
        j["width"] = r.width;
        j["height"] = r.height;
        const SceneFigures& f = r.figures;
        ordered_json prims;
        prims["triangles"] = f.shapes[size_t(ShapeKind::Triangle)];
        for_each_shape([&](auto k) { prims[decltype(k)::Desc::kNouns] = f.shapes[size_t(kind_of<decltype(k)>)]; });
        prims["lights"] = f.lights;
        prims["degenerate_skipped"] = f.degenerate;
        j["primitives"] = prims;
        j["threads"] = r.render_stats.threads;
        j["cull"] = r.cull;
        j["min_weight"] = r.min_weight;
        j["max_recursion_depth"] = f.max_recursion_depth;
        j["shadow_ray_epsilon"] = f.shadow_ray_epsilon;
        // The medians over the --repeat runs, then the fastest and the slowest run.
        j["repeat"] = r.repeat;
        const auto seconds = [&](double Timing::*which) {
            return ordered_json{{"parse", f.seconds.parse.*which}, {"ply", f.seconds.ply.*which},
                                {"setup", f.seconds.setup.*which}, {"bvh", f.seconds.bvh.*which},
                                {"render", r.render.*which},       {"write", r.write.*which}};
        };
        j["seconds"] = seconds(&Timing::median);
        j["seconds_min"] = seconds(&Timing::min);
        j["seconds_max"] = seconds(&Timing::max);
        j["rays"] = {{"camera", rays.camera},
                     {"shadow", rays.shadow},
                     {"reflection", rays.reflection},
                     {"refraction", rays.refraction},
                     {"total", rays.total()}};
        j["rays_per_second"] = r.render.median > 0 ? double(rays.total()) / r.render.median : 0.0;
        // Samples: what each pixel averaged (adaptive sampling: a mean over the pixels).
        const double pixels = double(r.width) * r.height;
        j["samples"] = {{"sampler", r.sampler},
                        {"per_pixel", r.render_stats.samples > 0 ? double(r.render_stats.samples) / pixels : 1.0},
                        {"total", r.render_stats.samples},
                        {"adaptive_cap", r.adaptive}};
        j["bvh"] = {{"nodes", f.bvh_nodes},
                    {"depth", f.bvh_depth},
                    {"max_leaf", r.bvh.max_leaf},
                    {"bins", r.bvh.bins},
                    {"traversal_cost", r.bvh.traversal_cost},
                    {"block", f.bvh_block},
                    {"split", r.bvh.sah ? "sah" : "median"},
                    {"collapse", r.bvh.collapse}};
        j["peak_rss_bytes"] = r.peak_rss;
        j["render_rss_bytes"] = r.render_rss;
        list.push_back(std::move(j));
    }
    doc["images"] = std::move(list);
    return doc.dump(2) + "\n";
}

}  // namespace rt
