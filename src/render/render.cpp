// Tile pool: workers pull 16x16 tiles from an atomic counter. Each pixel is a
// pure function of the scene, so the image does not depend on the thread count.
// Each worker counts its rays in its own TraceCache; the counts are summed at the end.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include "rt/core/threads.h"
#include "rt/geometry/traverse.h"
#include "rt/render/render.h"
#include "rt/shading/shading.h"

namespace rt {

void apply_overrides(Scene& scene, const RenderOptions& options) {
    if (options.max_depth >= 0) scene.setup.max_recursion_depth = options.max_depth;
    scene.setup.shadow_ray_epsilon = static_cast<Real>(scene.setup.shadow_ray_epsilon * options.epsilon_scale);
    if (options.samples > 0)
        for (Camera& c : scene.setup.cameras) c.samples = options.samples;
}

Image render(const Scene& scene, size_t camera_index, const RenderOptions& options, RenderStats* stats) {
    const Camera& cam = scene.setup.cameras.at(camera_index);
    Image img;
    img.width = cam.width;
    img.height = cam.height;
    img.rgb.assign(static_cast<size_t>(cam.width) * cam.height * 3, 0);

    constexpr int kTile = kRenderTile;
    constexpr int kPacketW = 4, kPacketH = 4;  // pixels of a packet (kPacketW * kPacketH <= kPacket)
    static_assert(kPacketW * kPacketH <= kPacket && kTile % kPacketW == 0 && kTile % kPacketH == 0);
    const int tiles_x = (cam.width + kTile - 1) / kTile;
    const int tiles_y = (cam.height + kTile - 1) / kTile;
    const int all_tiles = tiles_x * tiles_y;
    const int parts = std::max(1, options.parts), part = options.part;
    if (part < 0 || part >= parts) throw std::invalid_argument("render: part outside 0..parts-1");
    // This part's tiles: part, part + parts, ...
    const int tiles = all_tiles > part ? (all_tiles - part + parts - 1) / parts : 0;
    std::atomic<int> next{0};
    const TraceOptions& topt = options.trace;
    const PixelSampling sampling = pixel_sampling(scene, camera_index, options.sampling);
    const bool watch = static_cast<bool>(options.progress);

    int threads = options.threads > 0 ? options.threads : static_cast<int>(std::thread::hardware_concurrency());
    threads = std::max(1, std::min(threads, tiles));

    // Progress: tiles finished (one relaxed increment per tile), and workers finished.
    std::atomic<int> done{0};
    std::mutex finished_mutex;
    std::condition_variable finished_cv;
    int finished = 0;
    std::vector<RayCounts> rays(static_cast<size_t>(threads));
    std::vector<uint64_t> samples_taken(static_cast<size_t>(threads), 0);
    // Each pixel's sample count, when asked for: every pixel written by one worker.
    std::vector<uint32_t> pixel_samples;
    if (stats && options.count_samples) pixel_samples.assign(static_cast<size_t>(cam.width) * cam.height, 0);
    uint32_t* const counts = pixel_samples.empty() ? nullptr : pixel_samples.data();

    auto work = [&](int worker) {
        TraceCache cache;  // per thread
        uint64_t taken = 0;
        for (int k; (k = next.fetch_add(1, std::memory_order_relaxed)) < tiles;) {
            const int tile = part + k * parts;
            const int x0 = (tile % tiles_x) * kTile, y0 = (tile / tiles_x) * kTile;
            const int x1 = std::min(x0 + kTile, cam.width), y1 = std::min(y0 + kTile, cam.height);
            // Neighbouring pixels' camera rays traverse the tree as one packet of
            // kPacketW x kPacketH pixels.
            uint8_t pixels[kTile][kTile * 3];
            const auto put = [&](int px, int py, Vec3 c) {
                uint8_t* rgb = &pixels[py - y0][(px - x0) * 3];
                rgb[0] = quantize(c.x, options.rounding);
                rgb[1] = quantize(c.y, options.rounding);
                rgb[2] = quantize(c.z, options.rounding);
            };
            // A pixel with samples: its bytes, its count.
            const auto keep = [&](int px, int py, const PixelValue& v) {
                put(px, py, v.radiance);
                taken += uint64_t(v.samples);
                if (counts) counts[static_cast<size_t>(py) * cam.width + px] = uint32_t(v.samples);
            };
            if (sampling.noise_target > 0) {
                // Adaptive sampling: the tile's regions, each on its own (pixel_samples.h).
                static_assert(kTile % kAdaptiveRegion == 0);
                PixelValue v[kAdaptiveRegion * kAdaptiveRegion];
                for (int ry = y0; ry < y1; ry += kAdaptiveRegion)
                    for (int rx = x0; rx < x1; rx += kAdaptiveRegion) {
                        const int rx1 = std::min(rx + kAdaptiveRegion, x1), ry1 = std::min(ry + kAdaptiveRegion, y1);
                        sample_region(scene, cam, sampling, rx, ry, rx1, ry1, topt, &cache, v);
                        for (int y = ry; y < ry1; ++y)
                            for (int x = rx; x < rx1; ++x) keep(x, y, v[(y - ry) * (rx1 - rx) + (x - rx)]);
                    }
            } else if (sampling.samples > 1) {
                // Distribution ray tracing: each pixel's samples (pixel_samples.h).
                for (int y = y0; y < y1; ++y)
                    for (int x = x0; x < x1; ++x) keep(x, y, sample_pixel(scene, cam, sampling, x, y, topt, &cache));
            } else
                for (int y = y0; y < y1; y += kPacketH)
                    for (int x = x0; x < x1; x += kPacketW) {
                        Ray rays_in[kPacket];
                        SampleStream streams[kPacket];
                        int n = 0;
                        for (int py = y; py < std::min(y + kPacketH, y1); ++py)
                            for (int px = x; px < std::min(x + kPacketW, x1); ++px, ++n) {
                                if (!sampling.random) {  // assignments 1 and 2: no number drawn
                                    rays_in[n] = cam.primary_ray(px, py);
                                    continue;
                                }
                                const CameraSample cs = camera_sample(cam, sampling, px, py, 0);
                                rays_in[n] = cs.ray;
                                streams[n] = cs.stream;
                            }
                        Vec3 c[kPacket];
                        trace_primaries(scene, rays_in, n, topt, &cache, streams, c);
                        n = 0;
                        for (int py = y; py < std::min(y + kPacketH, y1); ++py)
                            for (int px = x; px < std::min(x + kPacketW, x1); ++px, ++n) put(px, py, c[n]);
                    }
            // The tile goes to the image a row at a time: a tile row (48 bytes) shares
            // cache lines with its neighbours', which the other workers render at the
            // same time.
            for (int y = y0; y < y1; ++y)
                std::copy(pixels[y - y0], pixels[y - y0] + (x1 - x0) * 3,
                          &img.rgb[(static_cast<size_t>(y) * cam.width + x0) * 3]);
            if (watch) done.fetch_add(1, std::memory_order_relaxed);
        }
        rays[static_cast<size_t>(worker)] = cache.rays;
        samples_taken[static_cast<size_t>(worker)] = taken;
        if (watch) {
            {
                std::lock_guard<std::mutex> lock(finished_mutex);
                ++finished;
            }
            finished_cv.notify_one();
        }
    };

    // Workers run on threads of their own; the calling thread watches (progress) or
    // waits, and renders only as the one worker of a single-threaded render. A worker
    // on the calling thread would keep its per-ray state (TraceCache, spilled locals)
    // on the stack right below this frame, whose variables the other workers read for
    // every ray: a cache line shared that way, depending on where the stack starts,
    // made renders up to 1.4x slower (docs/performance.md). A worker whose thread cannot
    // start renders on this thread as it starts (HelperThread); the others find fewer
    // tiles left.
    const bool caller_renders = !watch && threads == 1;
    std::vector<HelperThread> pool;
    pool.reserve(static_cast<size_t>(threads));
    try {
        for (int i = caller_renders ? 1 : 0; i < threads; ++i) pool.emplace_back([&work, i] { work(i); });
    } catch (...) {
        // Out of memory starting a thread: stop the ones that started (they find no
        // tile left; the pool's destructor joins them), then report.
        next.store(tiles);
        throw;
    }
    if (watch) {
        const auto interval = std::chrono::duration<double>(std::max(0.001, options.progress_interval));
        std::unique_lock<std::mutex> lock(finished_mutex);
        while (!finished_cv.wait_for(lock, interval, [&] { return finished == threads; })) {
            lock.unlock();
            try {
                options.progress(done.load(std::memory_order_relaxed), tiles);
            } catch (...) {
                // A failing progress display never stops the render.
            }
            lock.lock();
        }
    } else if (caller_renders) {
        work(0);
    }
    for (HelperThread& t : pool) t.join();

    if (stats) {
        *stats = RenderStats{};
        stats->pixel_samples = std::move(pixel_samples);
        for (const RayCounts& r : rays) stats->rays += r;
        for (const uint64_t n : samples_taken) stats->samples += n;
        stats->threads = threads;
        stats->tiles = tiles;
    }
    return img;
}

}  // namespace rt
