// The page's renderer session (rt/web/session.h).
#include "rt/web/session.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/camera_desc.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/trace.h"

namespace rt::web {
namespace {

// One part's running sums (refine_part): each pixel's sum of the radiance of its samples
// so far, in the order for_each_pixel visits them.
struct PartSums {
    int samples = 0;
    std::vector<Vec3> sum;
};

struct Session {
    std::optional<Scene> scene;
    std::string path;
    std::vector<std::string> warnings;
    RenderOptions render;
    // The parts refine_part holds, of one camera split into `parts`.
    int refined_camera = -1, refined_parts = 0;
    std::map<int, PartSums> refined;
    TraceCache cache;
};

Session& session() {
    static Session s;
    return s;
}

// A whole number from 0 to `hi`: a JSON integer, or a string of its decimal digits (a
// JavaScript number holds whole numbers exactly only up to 2^53).
std::optional<uint64_t> whole_number(const nlohmann::json& v, uint64_t hi) {
    if (v.is_number_unsigned()) {
        const uint64_t n = v.get<uint64_t>();
        return n <= hi ? std::optional<uint64_t>(n) : std::nullopt;
    }
    if (!v.is_string()) return std::nullopt;
    const std::string& digits = v.get_ref<const std::string&>();
    if (digits.empty() || digits.size() > 19) return std::nullopt;  // 19 digits stay below 2^64
    uint64_t n = 0;
    for (const char c : digits) {
        if (c < '0' || c > '9') return std::nullopt;
        n = n * 10 + static_cast<uint64_t>(c - '0');
    }
    return n <= hi ? std::optional<uint64_t>(n) : std::nullopt;
}

// Calls f(x, y) for each pixel of the tiles of part `part` of `parts` (RenderOptions::part),
// tile after tile, each row-major.
template <class F>
void for_each_pixel(int width, int height, int part, int parts, F f) {
    constexpr int kTile = kRenderTile;
    const int tiles_x = (width + kTile - 1) / kTile, tiles_y = (height + kTile - 1) / kTile;
    for (int t = part; t < tiles_x * tiles_y; t += parts) {
        const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
        for (int y = y0; y < std::min(y0 + kTile, height); ++y)
            for (int x = x0; x < std::min(x0 + kTile, width); ++x) f(x, y);
    }
}

void put_pixel(uint8_t* rgba, int width, int x, int y, const uint8_t* rgb) {
    const size_t i = static_cast<size_t>(y) * width + x;
    std::copy(rgb, rgb + 3, &rgba[4 * i]);
    rgba[4 * i + 3] = 255;
}

// The sampler --sampler names so.
std::optional<SamplerKind> sampler_of(const std::string& name) {
    for (const SamplerKind k : {SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol})
        if (name == sampler_name(k)) return k;
    return std::nullopt;
}

// The command line's options of the same names (rt/app/run.h, docs/web.md); samples 0
// keeps each camera's NumSamples, as without --samples.
void read_options(const std::string& text, RenderOptions& r) {
    if (text.empty()) return;
    const nlohmann::json o = nlohmann::json::parse(text);
    if (!o.is_object()) throw UsageError("options: expected a JSON object");
    for (auto it = o.begin(); it != o.end(); ++it) {
        const std::string& k = it.key();
        const nlohmann::json& v = it.value();
        if (k == "cull" && v.is_boolean()) {
            r.trace.cull = v.get<bool>();
        } else if (k == "max_depth" && v.is_number_integer() && v.get<long long>() >= -1 &&
                   v.get<long long>() <= kMaxRecursionDepth) {
            r.max_depth = v.get<int>();
        } else if (k == "epsilon_scale" && v.is_number() && v.get<double>() > 0) {
            r.epsilon_scale = v.get<double>();
        } else if (k == "min_weight" && v.is_number() && v.get<double>() >= 0 && v.get<double>() <= 1) {
            r.trace.min_weight = v.get<double>();
        } else if (k == "rounding" && v.is_string() && (v == "truncate" || v == "nearest")) {
            r.rounding = v == "nearest" ? Rounding::Nearest : Rounding::Truncate;
        } else if (k == "samples" && v.is_number_unsigned() && v.get<uint64_t>() <= uint64_t(kMaxSamples)) {
            r.samples = v.get<int>();
        } else if (k == "seed" && whole_number(v, kMaxSeed)) {
            r.sampling.seed = *whole_number(v, kMaxSeed);
        } else if (k == "sampler" && v.is_string() && sampler_of(v.get<std::string>())) {
            r.sampling.sampler = *sampler_of(v.get<std::string>());
        } else {
            throw UsageError("options: " + k + ": unknown option or bad value " + v.dump());
        }
    }
}

}  // namespace

std::string load(const std::string& scene_path, const std::string& options_json) {
    Session& s = session();
    s = Session{};
    try {
        read_options(options_json, s.render);
        s.render.threads = 1;  // one worker, one thread: the page runs several workers
        SceneDesc desc = load_scene(scene_path);
        s.warnings = desc.warnings;
        s.scene = build_scene(std::move(desc));
        apply_overrides(*s.scene, s.render);  // as the command line's --max-depth and --epsilon-scale
        s.path = scene_path;
        return "";
    } catch (const std::exception& e) {
        s = Session{};
        return e.what();
    }
}

std::string scene_json() {
    const Session& s = session();
    nlohmann::json out = {{"cameras", nlohmann::json::array()}, {"warnings", s.warnings}};
    if (s.scene)
        for (const Camera& c : s.scene->setup.cameras)
            out["cameras"].push_back(
                {{"name", c.image_name}, {"width", c.width}, {"height", c.height}, {"samples", c.samples}});
    return out.dump();
}

std::string render_part(int camera, int part, int parts, uint8_t* rgba) {
    const Session& s = session();
    try {
        if (!s.scene) return "no scene loaded";
        if (camera < 0 || static_cast<size_t>(camera) >= s.scene->setup.cameras.size()) return "no such camera";
        RenderOptions o = s.render;
        o.part = part;
        o.parts = parts;
        const Image img = render(*s.scene, static_cast<size_t>(camera), o);
        // The part's tiles only (rt/render/render.h), so that parts merge.
        for_each_pixel(img.width, img.height, part, parts, [&](int x, int y) {
            put_pixel(rgba, img.width, x, y, &img.rgb[3 * (static_cast<size_t>(y) * img.width + x)]);
        });
        return "";
    } catch (const std::exception& e) {
        return e.what();
    }
}

std::string refine_part(int camera, int part, int parts, int k0, int k1, uint8_t* rgba) {
    Session& s = session();
    try {
        if (!s.scene) return "no scene loaded";
        if (camera < 0 || static_cast<size_t>(camera) >= s.scene->setup.cameras.size()) return "no such camera";
        if (parts < 1 || part < 0 || part >= parts) return "render: part outside 0..parts-1";
        const Camera& cam = s.scene->setup.cameras[static_cast<size_t>(camera)];
        const int samples = std::max(1, cam.samples);
        if (k0 < 0 || k1 <= k0 || k1 > samples)
            return "samples " + std::to_string(k0) + ".." + std::to_string(k1) + ": camera " +
                   std::to_string(camera + 1) + " takes " + count_of(size_t(samples), "sample") + " per pixel";
        if (camera != s.refined_camera || parts != s.refined_parts) {
            s.refined.clear();
            s.refined_camera = camera;
            s.refined_parts = parts;
        }
        PartSums& held = s.refined[part];
        if (k0 == 0) held = PartSums{};
        if (k0 != held.samples)
            return "samples " + std::to_string(k0) + ".." + std::to_string(k1) + ": part " + std::to_string(part) +
                   " holds " + count_of(size_t(held.samples), "sample");
        const PixelSampling sampling = pixel_sampling(*s.scene, static_cast<size_t>(camera), s.render.sampling);
        // A pixel's mean over samples [0, k1) as the render takes it (sample_pixel), quantized
        // as it does.
        const auto put_mean = [&](int x, int y, const Vec3& sum) {
            const Vec3 mean = sum / Real(k1);
            const uint8_t rgb[3] = {quantize(mean.x, s.render.rounding), quantize(mean.y, s.render.rounding),
                                    quantize(mean.z, s.render.rounding)};
            put_pixel(rgba, cam.width, x, y, rgb);
        };
        if (k1 == 1) {
            // The first sample of each pixel: kPacket neighbouring pixels' rays traced as one
            // packet, as the render traces pixels without samples (a ray's radiance is the
            // same in any packet), not a packet of one ray per pixel.
            held.sum.clear();
            int xs[kPacket], ys[kPacket], n = 0;
            const auto trace_packet = [&] {
                Ray rays[kPacket];
                SampleStream streams[kPacket];
                Vec3 radiance[kPacket];
                for (int j = 0; j < n; ++j) {
                    const CameraSample c = camera_sample(cam, sampling, xs[j], ys[j], 0);
                    rays[j] = c.ray;
                    streams[j] = c.stream;
                }
                trace_primaries(*s.scene, rays, n, s.render.trace, &s.cache, streams, radiance);
                for (int j = 0; j < n; ++j) {
                    held.sum.emplace_back();
                    held.sum.back() += radiance[j];  // as add_samples adds to a sum from zero
                    put_mean(xs[j], ys[j], held.sum.back());
                }
                n = 0;
            };
            for_each_pixel(cam.width, cam.height, part, parts, [&](int x, int y) {
                xs[n] = x;
                ys[n] = y;
                if (++n == kPacket) trace_packet();
            });
            if (n) trace_packet();
        } else {
            size_t i = 0;
            for_each_pixel(cam.width, cam.height, part, parts, [&](int x, int y) {
                if (i == held.sum.size()) held.sum.emplace_back();  // k0 0: from zero
                PixelSum acc;
                acc.sum = held.sum[i];
                acc.n = k0;
                add_samples(*s.scene, cam, sampling, x, y, k0, k1, s.render.trace, &s.cache, acc);
                held.sum[i++] = acc.sum;
                put_mean(x, y, acc.sum);
            });
        }
        held.samples = k1;
        return "";
    } catch (const std::exception& e) {
        s.refined.clear();
        return e.what();
    }
}

std::string trace(int camera, int x, int y, int sample) {
    const Session& s = session();
    try {
        if (!s.scene) return nlohmann::json{{"error", "no scene loaded"}}.dump();
        const std::vector<Camera>& cams = s.scene->setup.cameras;
        if (camera < 0 || static_cast<size_t>(camera) >= cams.size())
            return nlohmann::json{{"error", "no camera " + std::to_string(camera + 1)}}.dump();
        const Camera& c = cams[static_cast<size_t>(camera)];
        if (x < 0 || y < 0 || x >= c.width || y >= c.height)
            return nlohmann::json{{"error", "pixel " + std::to_string(x) + "," + std::to_string(y) +
                                                " is outside the " + std::to_string(c.width) + "x" +
                                                std::to_string(c.height) + " image"}}
                .dump();
        const int samples = std::max(1, c.samples);
        if (sample < 0 || sample >= samples)
            return nlohmann::json{{"error", "sample " + std::to_string(sample) + ": camera " +
                                                std::to_string(camera + 1) + " takes " +
                                                count_of(size_t(samples), "sample") + " per pixel (0.." +
                                                std::to_string(samples - 1) + ")"}}
                .dump();
        PixelTrace t = trace_pixel(*s.scene, static_cast<size_t>(camera), x, y, s.render.trace, s.render.rounding,
                                   s.render.sampling, sample);
        t.scene = s.path;
        return trace_json(*s.scene, t);
    } catch (const std::exception& e) {
        return nlohmann::json{{"error", e.what()}}.dump();
    }
}

}  // namespace rt::web
