// Tile pool: workers pull 16x16 tiles from an atomic counter. Each pixel is a
// pure function of the scene, so the image does not depend on the thread count.
#include <algorithm>
#include <atomic>
#include <thread>
#include <vector>

#include "rt/render.h"
#include "rt/shading.h"

namespace rt {

Image render(const Scene& scene, size_t camera_index, const RenderOptions& options) {
    const Camera& cam = scene.cameras.at(camera_index);
    Image img;
    img.width = cam.width;
    img.height = cam.height;
    img.rgb.assign(static_cast<size_t>(cam.width) * cam.height * 3, 0);

    constexpr int kTile = 16;
    const int tiles_x = (cam.width + kTile - 1) / kTile;
    const int tiles_y = (cam.height + kTile - 1) / kTile;
    const int tiles = tiles_x * tiles_y;
    std::atomic<int> next{0};
    const TraceOptions topt{options.cull};

    auto work = [&]() {
        TraceCache cache;  // per thread
        for (int tile; (tile = next.fetch_add(1, std::memory_order_relaxed)) < tiles;) {
            const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
            const int x1 = std::min(x0 + kTile, cam.width), y1 = std::min(y0 + kTile, cam.height);
            for (int y = y0; y < y1; ++y) {
                for (int x = x0; x < x1; ++x) {
                    const Vec3 c = trace_primary(scene, cam.primary_ray(x, y), topt, &cache);
                    uint8_t* px = &img.rgb[(static_cast<size_t>(y) * cam.width + x) * 3];
                    px[0] = quantize(c.x, options.rounding);
                    px[1] = quantize(c.y, options.rounding);
                    px[2] = quantize(c.z, options.rounding);
                }
            }
        }
    };

    int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::max(1, std::min(threads, tiles));
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
    return img;
}

}  // namespace rt
