// What the raytracer command reports about its own run: the --stats JSON file
// (figures per image) and the live progress line on a terminal.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/bvh.h"
#include "rt/render.h"

namespace rt {
namespace cli {

// Seconds spent on a scene before its images render; shared by all its images.
struct SceneTimes {
    double parse = 0;  // reading and parsing the scene file, PLY files excluded
    double ply = 0;    // reading PLY files
    double setup = 0;  // render data: vertices copied, normals (build_scene without the BVH)
    double bvh = 0;    // BVH build
};

struct ImageRecord {
    std::string scene, image;  // the scene file and the image written
    size_t camera = 0;         // 1-based
    int width = 0, height = 0;
    size_t triangles = 0, spheres = 0, planes = 0, lights = 0, degenerate = 0;
    SceneTimes times;
    double render = 0, write = 0;
    RenderStats render_stats;
    bool cull = true;
    int max_recursion_depth = 0;
    double shadow_ray_epsilon = 0;
    size_t bvh_nodes = 0;
    int bvh_depth = 0;
    BvhBuildOptions bvh;
    uint64_t peak_rss = 0;  // bytes, of the whole process so far
};

// The --stats document: {"raytracer", "precision", "machine": {...}, "images": [...]}.
std::string stats_json(const std::vector<ImageRecord>& images, const std::string& version);

// Peak resident memory of this process so far, in bytes (getrusage).
uint64_t peak_rss_bytes();

// "model name" of the first CPU in /proc/cpuinfo, or "unknown".
std::string cpu_model();

// True when stderr is a terminal.
bool stderr_is_terminal();

// One carriage-return line on stderr: "label: 42% 1.2 s elapsed, ~1.7 s left".
// Does nothing unless enabled; clear() erases it (before the per-image summary line).
class ProgressLine {
public:
    explicit ProgressLine(bool enabled) : enabled_(enabled) {}
    ~ProgressLine() { clear(); }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    bool enabled() const { return enabled_; }
    void start(const std::string& label);
    void update(int done, int total);
    void clear();

private:
    bool enabled_;
    std::string label_;
    std::chrono::steady_clock::time_point t0_;
    size_t shown_ = 0;  // characters on the line now
};

}  // namespace cli
}  // namespace rt
