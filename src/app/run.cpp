// The raytracer command's pipeline: per scene file load -> build -> (per camera)
// render -> write -> record. See rt/run.h.
#include "rt/run.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "progress.h"
#include "rt/atomic_file.h"
#include "rt/cli.h"
#include "rt/error.h"
#include "rt/image.h"
#include "rt/loader.h"
#include "rt/scene.h"
#include "rt/trace.h"

namespace rt {

namespace {

// "1 sphere", "3 spheres".
std::string count_of(size_t n, const char* noun) { return std::to_string(n) + " " + noun + (n == 1 ? "" : "s"); }

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The measurement overrides (--max-depth, --epsilon-scale) applied to a built scene.
void apply_overrides(Scene& scene, const RunOptions& o) {
    if (o.max_depth >= 0) scene.setup.max_recursion_depth = o.max_depth;
    scene.setup.shadow_ray_epsilon = static_cast<Real>(scene.setup.shadow_ray_epsilon * o.epsilon_scale);
}

// A scene ready to render, with what the summary lines and records report of it.
struct LoadedScene {
    Scene scene;
    SceneFigures figures;
    double load_seconds = 0;  // parse + PLY + setup: the summary line's "load"
    size_t warnings = 0;      // warnings its loading raised (the summary line counts them)
};

// Reports the warnings of a scene: on stderr as "warning: ..." unless quiet; under
// --strict as "error: ..." lines, and then the scene is bad input (returns false).
bool report_warnings(const std::vector<std::string>& warnings, const RunOptions& o) {
    for (const std::string& w : warnings) {
        if (o.strict)
            cli::print_error(w + " (--strict)");
        else if (!o.quiet)
            std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    return !(o.strict && !warnings.empty());
}

// Loads and builds one scene file; prints its warnings (unless quiet) and its error
// line, and returns nothing on bad input (under --strict, a warning is bad input). Every
// ImageName is checked before anything is rendered: .png or .ppm.
std::optional<LoadedScene> load(const std::string& scene_path, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        SceneDesc desc = load_scene(scene_path);
        SceneTimes times;
        times.ply = desc.ply_seconds;
        times.parse = seconds_since(t0) - desc.ply_seconds;
        const size_t warnings = desc.warnings.size();
        if (!report_warnings(desc.warnings, o)) return std::nullopt;
        bool names_ok = true;
        for (size_t c = 0; c < desc.cameras.size(); ++c) {
            if (image_format_of(desc.cameras[c].image_name) != ImageFormat::Unknown) continue;
            cli::print_error(scene_path + ": camera " + std::to_string(c + 1) + ": ImageName '" +
                             desc.cameras[c].image_name +
                             "': unknown image format (the name must end in .png or .ppm)");
            names_ok = false;
        }
        if (!names_ok) return std::nullopt;
        const auto b0 = std::chrono::steady_clock::now();
        LoadedScene s{build_scene(std::move(desc), o.bvh), {}, 0, warnings};
        const double build_s = seconds_since(b0);
        const double total_s = seconds_since(t0);
        apply_overrides(s.scene, o);
        s.figures = scene_figures(s.scene, times);
        s.figures.seconds.setup = build_s - s.figures.seconds.bvh;
        s.load_seconds = total_s - s.figures.seconds.bvh;
        if (const size_t n = s.figures.degenerate; n > 0) {
            ++s.warnings;
            if (!report_warnings({scene_path + ": skipped " + count_of(n, "degenerate triangle")}, o))
                return std::nullopt;
        }
        return std::optional<LoadedScene>(std::move(s));  // moved, never copied
    } catch (const InputError& e) {
        cli::print_error(e.what());
    } catch (const std::bad_alloc&) {
        cli::print_error(scene_path + ": out of memory while loading");
    } catch (const std::exception& e) {
        // Not expected (every bad input is an InputError); still one line, no crash.
        cli::print_error(scene_path + ": cannot load: " + e.what());
    }
    return std::nullopt;
}

// Renders and writes camera `c` (0-based) of a loaded scene; returns its record.
// Throws on failure (InputError for an unwritable path).
ImageRecord render_camera(const std::string& scene_path, const LoadedScene& s, size_t c, const std::string& out,
                          const RunOptions& o) {
    const Camera& cam = s.scene.setup.cameras[c];
    make_parent_folders(out);
    RenderOptions ropt = o.render;
    app::ProgressLine progress(o.progress && !o.quiet && app::stderr_is_terminal());
    if (progress.enabled()) {
        progress.start(out);
        ropt.progress = [&progress](int done, int total) { progress.update(done, total); };
    }
    ImageRecord r{scene_path, out, c + 1, cam.width, cam.height, s.figures, 0, 0, {}, o.render.cull, o.bvh, 0};
    const auto r0 = std::chrono::steady_clock::now();
    const Image img = render(s.scene, c, ropt, &r.render_stats);
    r.render = seconds_since(r0);
    progress.clear();
    const auto w0 = std::chrono::steady_clock::now();
    write_image(img, out);
    r.write = seconds_since(w0);
    if (!o.quiet) {
        const std::string warned = s.warnings == 0 ? "" : ", " + count_of(s.warnings, "warning");
        std::fprintf(stderr, "%s: %dx%d, %s, %s, %s, load %.3fs, bvh %.3fs, render %.3fs, write %.3fs%s\n", out.c_str(),
                     cam.width, cam.height, kPrecisionName, count_of(s.figures.triangles, "triangle").c_str(),
                     count_of(s.figures.spheres, "sphere").c_str(), s.load_seconds, s.figures.seconds.bvh, r.render,
                     r.write, warned.c_str());
    }
    r.peak_rss = app::peak_rss_bytes();
    return r;
}

// Renders every camera of one scene file into `records`; returns false if anything failed.
bool run_scene(const std::string& scene_path, const RunOptions& o, std::vector<ImageRecord>& records) {
    const std::optional<LoadedScene> s = load(scene_path, o);
    if (!s) return false;
    bool ok = true;
    for (size_t c = 0; c < s->scene.setup.cameras.size(); ++c) {
        std::string out = s->scene.setup.cameras[c].image_name;
        if (!o.output_dir.empty() && out[0] != '/') out = o.output_dir + "/" + out;
        try {
            records.push_back(render_camera(scene_path, *s, c, out, o));
        } catch (const InputError& e) {
            cli::print_error(scene_path + ": camera " + std::to_string(c + 1) + ": " + e.what());
            ok = false;
        } catch (const std::bad_alloc&) {
            cli::print_error(scene_path + ": camera " + std::to_string(c + 1) + ": out of memory rendering " + out);
            ok = false;
        } catch (const std::exception& e) {
            // Any other failure of this camera (helper threads that cannot start do not
            // fail: their work runs on the calling thread, rt/threads.h).
            cli::print_error(scene_path + ": camera " + std::to_string(c + 1) + ": cannot render " + out + ": " +
                             e.what());
            ok = false;
        }
    }
    return ok;
}

}  // namespace

SceneFigures scene_figures(const Scene& scene, const SceneTimes& seconds) {
    SceneFigures f;
    f.triangles = scene.geometry.triangles.size();
    f.spheres = scene.geometry.spheres.size();
    f.planes = scene.geometry.planes.size();
    f.lights = scene.setup.lights.size();
    f.degenerate = scene.report.degenerate_triangles;
    f.bvh_nodes = scene.accel.bvh.nodes.size();
    f.bvh_depth = scene.accel.bvh.depth;
    f.bvh_block = scene.accel.bvh.block;
    f.max_recursion_depth = scene.setup.max_recursion_depth;
    f.shadow_ray_epsilon = double(scene.setup.shadow_ray_epsilon);
    f.seconds = seconds;
    f.seconds.bvh = double(scene.report.build_seconds);
    return f;
}

RunReport run_scenes(const std::vector<std::string>& scene_paths, const RunOptions& options) {
    RunReport report;
    for (const std::string& path : scene_paths) report.ok = run_scene(path, options, report.images) && report.ok;
    return report;
}

int run_trace(const std::string& scene_path, const RunOptions& o, const PixelTraceRequest& req) {
    const std::optional<LoadedScene> s = load(scene_path, o);
    if (!s) return 1;
    const std::vector<Camera>& cameras = s->scene.setup.cameras;
    if (req.camera < 1 || req.camera > cameras.size())
        throw UsageError("--camera " + std::to_string(req.camera) + ": " + scene_path + " has " +
                         std::to_string(cameras.size()) + " camera" + (cameras.size() == 1 ? "" : "s"));
    const Camera& cam = cameras[req.camera - 1];
    if (req.x < 0 || req.y < 0 || req.x >= cam.width || req.y >= cam.height)
        throw UsageError("--trace " + std::to_string(req.x) + "," + std::to_string(req.y) + ": outside the " +
                         std::to_string(cam.width) + "x" + std::to_string(cam.height) + " image of camera " +
                         std::to_string(req.camera) + " (x 0.." + std::to_string(cam.width - 1) + ", y 0.." +
                         std::to_string(cam.height - 1) + ")");
    PixelTrace t = trace_pixel(s->scene, req.camera - 1, req.x, req.y, TraceOptions{o.render.cull, o.render.min_weight},
                               o.render.rounding);
    t.scene = scene_path;
    std::fputs(trace_text(s->scene, t).c_str(), stdout);
    if (req.json_path.empty()) return 0;
    try {
        write_file_atomic(req.json_path, trace_json(s->scene, t));
    } catch (const InputError& e) {
        cli::print_error(e.what());
        return 1;
    }
    return 0;
}

void make_parent_folders(const std::string& path) {
    // Folder by folder, as mkdir -p: one that exists already (or a file in its place,
    // which the write then reports) is no error.
    for (size_t pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1)) {
        const std::string dir = path.substr(0, pos);
        std::error_code ec;
        std::filesystem::create_directory(dir, ec);
        if (ec && ec != std::errc::file_exists)
            throw InputError(path + ": cannot create folder " + dir + ": " + ec.message());
    }
}

}  // namespace rt
