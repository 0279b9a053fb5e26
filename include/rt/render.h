// Rendering: one camera of a built scene into an Image, on a pool of threads.
#pragma once
#include "rt/image.h"
#include "rt/scene.h"

namespace rt {

struct RenderOptions {
    int threads = 0;        // 0: all hardware threads
    bool cull = true;       // back-face culling of camera and reflection rays (spec 2.9)
    Rounding rounding = Rounding::Truncate;
};

// Deterministic: the image does not depend on the thread count.
Image render(const Scene& scene, size_t camera_index, const RenderOptions& options);

}  // namespace rt
