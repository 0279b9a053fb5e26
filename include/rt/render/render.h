// Rendering: one camera of a built scene into an Image, on a pool of threads.
#pragma once
#include <functional>

#include "rt/geometry/scene.h"
#include "rt/image/image.h"
#include "rt/shading/shading.h"

namespace rt {

// Images render in square tiles of this many pixels a side, row-major (RenderOptions::part).
inline constexpr int kRenderTile = 16;

struct RenderOptions {
    int threads = 0;   // 0: all hardware threads
    bool cull = true;  // back-face culling of camera and reflection rays (spec 2.9)
    Rounding rounding = Rounding::Truncate;
    double min_weight = kDefaultMinWeight;  // rays of a smaller weight are not traced (rt/shading/shading.h)
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
};

// Deterministic: the image does not depend on the thread count. `stats`, when
// given, receives the figures above.
Image render(const Scene& scene, size_t camera_index, const RenderOptions& options, RenderStats* stats = nullptr);

}  // namespace rt
