// Rendering: one camera of a built scene into an Image, on a pool of threads.
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "rt/geometry/scene.h"
#include "rt/image/image.h"
#include "rt/shading/pixel_samples.h"
#include "rt/shading/shading.h"

namespace rt {

// Images render in square tiles of this many pixels a side, row-major (RenderOptions::part).
inline constexpr int kRenderTile = 16;

// How a run renders, as the command line's options and the page's load options both set
// it (rt/app/run.h, rt/web/session.h, docs/web.md): tracing, rounding, the overrides of
// the scene's own values, and the threads and parts of the work.
struct RenderOptions {
    int threads = 0;     // 0: all hardware threads
    TraceOptions trace;  // back-face culling (spec 2.9) and the minimum ray weight (rt/shading/shading.h)
    Rounding rounding = Rounding::Truncate;
    int max_depth = -1;          // >= 0 (at most kMaxRecursionDepth): overrides the scene's MaxRecursionDepth
    double epsilon_scale = 1;    // multiplies the scene's ShadowRayEpsilon
    int samples = 0;             // > 0: overrides every camera's NumSamples (--samples)
    SamplingOptions sampling;    // seed, sampler, adaptive sampling (rt/shading/pixel_samples.h)
    bool count_samples = false;  // RenderStats::pixel_samples wanted (--sample-map)
    // When set, called on the calling thread about every `progress_interval` seconds
    // while the image renders, with the tiles finished so far and the tile count (never
    // after the last tile: a render shorter than one interval makes no call). The
    // calling thread then only watches; the `threads` workers render.
    std::function<void(int tiles_done, int tiles_total)> progress;
    double progress_interval = 0.05;
    // Renders only the tiles t (kRenderTile, row-major) with t % parts == part; the others stay
    // black. A page splits one image over workers, or over calls between which it shows
    // progress, and merges the parts: each pixel is the same whichever part renders it.
    int part = 0, parts = 1;
};

// What a render did. The ray counts depend only on the scene, the camera and the
// options, never on the thread count.
struct RenderStats {
    RayCounts rays;
    int threads = 0;  // threads that rendered
    int tiles = 0;    // 16x16 tiles
    // Samples taken in all (0 for images without NumSamples or adaptive sampling), and,
    // with RenderOptions::count_samples, each pixel's, row-major (0 where not rendered).
    uint64_t samples = 0;
    std::vector<uint32_t> pixel_samples;
};

// The overrides of `options` (max_depth, epsilon_scale, samples) applied to a built scene; the
// command line and the page call it once per scene, before rendering or tracing it.
void apply_overrides(Scene& scene, const RenderOptions& options);

// Deterministic: the image does not depend on the thread count. `stats`, when
// given, receives the figures above.
Image render(const Scene& scene, size_t camera_index, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace rt
