// The page's renderer session (rt/web/session.h).
#include "rt/web/session.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/loader/camera_desc.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/trace.h"

namespace rt::web {
namespace {

struct Session {
    std::optional<Scene> scene;
    std::string path;
    std::vector<std::string> warnings;
    RenderOptions render;
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
        constexpr int kTile = kRenderTile;
        const int tiles_x = (img.width + kTile - 1) / kTile, tiles_y = (img.height + kTile - 1) / kTile;
        for (int t = part; t < tiles_x * tiles_y; t += parts) {
            const int x0 = (t % tiles_x) * kTile, y0 = (t / tiles_x) * kTile;
            for (int y = y0; y < std::min(y0 + kTile, img.height); ++y)
                for (int x = x0; x < std::min(x0 + kTile, img.width); ++x) {
                    const size_t i = static_cast<size_t>(y) * img.width + x;
                    std::copy(&img.rgb[3 * i], &img.rgb[3 * i] + 3, &rgba[4 * i]);
                    rgba[4 * i + 3] = 255;
                }
        }
        return "";
    } catch (const std::exception& e) {
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
