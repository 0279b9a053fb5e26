// What the raytracer command does, as a library function: each scene file is loaded,
// built, rendered camera by camera and written, with the command's stderr messages, and
// every image written gives one record (the figures --stats reports).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/render/render.h"
#include "rt/shapes/shapes.h"

namespace rt {

struct Scene;
class MeshCache;

struct RunOptions {
    std::string output_dir;  // relative ImageNames go under it (created); "": the current folder
    RenderOptions render;    // threads, tracing, rounding, overrides (the progress callback is set per image)
    BvhBuildOptions bvh;     // BVH build knobs, for measurements
    bool quiet = false;      // stderr: errors only
    bool strict = false;     // every warning is an error: the scene is bad input, no image
    bool progress = true;    // a progress line while each image renders, when stderr is a terminal
    int repeat = 1;          // --repeat: each scene loaded, built and each image rendered this
                             // many times, for timing; every image is written once
    bool frames = false;     // --frames or --shard picked the files: an animation's frames
    // --sample-map: each image's samples per pixel as a grey PNG at this path (with several
    // images, sample_map_path names each).
    std::string sample_map;
    bool several_files = false;  // set by run_scenes: more than one scene file, or frames
    // Set by run_scenes for several files or for frames: the meshes they share, each PLY
    // file parsed and each mesh's BVH built once (rt/scene_build/mesh_cache.h).
    MeshCache* meshes = nullptr;
};

// The seconds a phase took over the --repeat runs.
struct Timing {
    double median = 0, min = 0, max = 0;
};

// The median (of an even count: the mean of the middle two), fastest and slowest of
// `samples`; all zero when there are none.
Timing timing_of(std::vector<double> samples);

// Seconds spent on a scene before its images render; shared by all its images.
struct SceneTimes {
    Timing parse;  // reading and parsing the scene file, PLY files excluded
    Timing ply;    // reading PLY files
    Timing setup;  // render data: vertices copied, normals (build_scene without the BVH)
    Timing bvh;    // BVH build
};

// What a built scene holds, as the per-image summary line and --stats report it.
struct SceneFigures {
    size_t shapes[kShapeKindCount] = {};  // by ShapeKind (rt/shapes/shapes.h); triangles: those stored,
                                          // an instanced mesh's once
    size_t lights = 0;
    size_t degenerate = 0;  // triangles skipped at build time
    size_t bvh_nodes = 0;
    int bvh_depth = 0;
    uint32_t bvh_block = 0;         // the leaf block the SAH priced leaves in (Bvh::block)
    int max_recursion_depth = 0;    // after --max-depth
    double shadow_ray_epsilon = 0;  // after --epsilon-scale
    SceneTimes seconds;
};

// The figures of one scene's settings and build; the one reader of rt::Scene's counts.
// The BVH's build time is the scene's own (one sample).
SceneFigures scene_figures(const Scene& scene, const SceneTimes& seconds);

// One image written.
struct ImageRecord {
    std::string scene, image;  // the scene file and the image written
    size_t camera = 0;         // 1-based
    int width = 0, height = 0;
    SceneFigures figures;
    int repeat = 1;            // the runs the times are over (--repeat)
    Timing render, write;      // seconds; written once, so write is one sample
    RenderStats render_stats;  // of the last run (every run traces the same rays)
    bool cull = true;
    double min_weight = 0;  // --min-weight
    BvhBuildOptions bvh;
    uint64_t peak_rss = 0;    // bytes, of the whole process so far
    uint64_t render_rss = 0;  // bytes resident when the render ended: the scene's render data
                              // (what loading freed is returned to the system first)
    int adaptive = 0;         // adaptive sampling: its cap of samples per pixel; 0: not adaptive
    std::string sampler;      // --sampler's name
};

struct RunReport {
    bool ok = true;  // every scene loaded and every image written
    std::vector<ImageRecord> images;
};

// Renders every camera of each scene file, in order; a failure stops only that scene
// (bad input) or that image (an unwritable path). On stderr: warnings and one summary
// line per image unless `quiet`, one line per error. Several files (or options.frames)
// are taken as an animation's frames: the meshes they read from the same PLY files are
// parsed and built once, and a last line says how often each was reused.
RunReport run_scenes(const std::vector<std::string>& scene_paths, const RunOptions& options);

// --frames A:B and --shard K/N: which of the scene files given (an animation's frames, in
// the order given: a shell glob's) one process renders. Frames A to B, 0-based positions,
// both included (A defaults to the first, B to the last); of those, every N-th from the
// K-th (0 <= K < N), so that N processes with K = 0 .. N-1 render each frame once.
struct FrameSelection {
    size_t first = 0, last = SIZE_MAX;
    size_t shard = 0, shards = 1;
};
std::vector<std::string> select_frames(const std::vector<std::string>& files, const FrameSelection& s);

// raytracer --trace X,Y [--camera N] [--trace-json FILE]: one pixel's ray tree instead of images.
struct PixelTraceRequest {
    int x = 0, y = 0;       // column from the left, row from the top (>= 0)
    size_t camera = 1;      // 1-based
    int sample = 0;         // with samples: which one to trace (0-based)
    std::string json_path;  // "": no JSON
};

// Loads and builds `scene_path` as run_scenes does (the same options and overrides),
// traces the pixel (rt/shading/trace.h), prints the tree on stdout and writes the JSON file.
// Returns 0, or 1 for bad input or an unwritable JSON file (its line printed); throws
// UsageError when the camera or the pixel is not in the scene.
int run_trace(const std::string& scene_path, const RunOptions& options, const PixelTraceRequest& request);

// The --stats document: {"raytracer": version, "precision", "machine": {...}, "images": [...]}.
std::string stats_json(const std::vector<ImageRecord>& images, const std::string& version);

// Creates the missing folders above the file `path` (mkdir -p of its parent); an
// existing one, folder or not, is left for the write to report. Throws InputError
// "<path>: cannot create folder <folder>: <reason>".
void make_parent_folders(const std::string& path);

}  // namespace rt
