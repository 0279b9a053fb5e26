// The raytracer command's pipeline: per scene file load -> build -> (per camera)
// render -> write -> record. See rt/app/run.h.
#include "rt/app/run.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <string>
#include <system_error>
#include <utility>

#include "progress.h"
#include "rt/cli/parser.h"
#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/image/image.h"
#include "rt/io/atomic_file.h"
#include "rt/io/memory.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/trace.h"

namespace rt {

namespace {

// The summary line's counts: what the BVH holds, every bounded kind ("5 triangles, 3 spheres").
std::string bvh_counts(const SceneFigures& f) {
    std::string s = count_of(f.shapes[size_t(ShapeKind::Triangle)], "triangle");
    for_each_shape([&](auto k) {
        using S = decltype(k);
        if constexpr (S::kBounded) s += ", " + count_of(f.shapes[size_t(kind_of<S>)], S::Desc::kNoun, S::Desc::kNouns);
    });
    return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// A scene ready to render, with what the summary lines and records report of it.
struct LoadedScene {
    Scene scene;
    SceneFigures figures;
    Timing load;          // parse + PLY + setup: the summary line's "load"
    size_t warnings = 0;  // warnings its loading raised (the summary line counts them)
};

// A warning as the error --strict makes of it: what is wrong, without what the renderer
// would have done instead (the loader's and load_once's wordings), and why it is an error.
std::string strict_error(std::string w) {
    static const std::pair<const char*, const char*> kInstead[] = {
        {": unknown key ignored", ": unknown key"},
        {", the first 4 used (left right bottom top)", " (expected 4: left right bottom top)"},
        {": skipped ", ": "},  // "skipped 2 degenerate triangles"
    };
    for (const auto& [instead, fact] : kInstead)
        if (const size_t at = w.find(instead); at != std::string::npos) {
            w.replace(at, std::char_traits<char>::length(instead), fact);
            break;
        }
    return w + "; --strict makes it an error";
}

// Reports the warnings of a scene: on stderr as "warning: ..." unless quiet; under
// --strict as "error: ..." lines, and then the scene is bad input (returns false).
bool report_warnings(const std::vector<std::string>& warnings, const RunOptions& o) {
    for (const std::string& w : warnings) {
        if (o.strict)
            cli::print_error(strict_error(w));
        else if (!o.quiet)
            std::fprintf(stderr, "warning: %s\n", w.c_str());
    }
    return !(o.strict && !warnings.empty());
}

// Loads and builds one scene file once; prints its warnings (unless quiet) and its error
// line, and returns nothing on bad input (under --strict, a warning is bad input). Every
// ImageName is checked before anything is rendered: .png or .ppm. The times are one sample.
std::optional<LoadedScene> load_once(const std::string& scene_path, const RunOptions& o) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
        SceneDesc desc = load_scene(scene_path, o.meshes);
        const double ply_s = desc.ply_seconds;
        const double parse_s = seconds_since(t0) - ply_s;
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
        LoadedScene s{build_scene(std::move(desc), o.bvh, o.meshes), {}, {}, warnings};
        const double build_s = seconds_since(b0);
        release_free_memory();  // the scene's descs, freed: back to the system
        const double total_s = seconds_since(t0);
        apply_overrides(s.scene, o.render);
        SceneTimes times;
        times.parse = timing_of({parse_s});
        times.ply = timing_of({ply_s});
        s.figures = scene_figures(s.scene, times);
        s.figures.seconds.setup = timing_of({build_s - s.figures.seconds.bvh.median});
        s.load = timing_of({total_s - s.figures.seconds.bvh.median});
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

// Loads and builds a scene --repeat times (the warnings printed once); the times are over
// all runs, the scene is the last run's (the one in memory: runs are not kept side by side).
std::optional<LoadedScene> load(const std::string& scene_path, const RunOptions& o) {
    std::optional<LoadedScene> s = load_once(scene_path, o);
    if (!s || o.repeat <= 1) return s;
    std::vector<double> parse, ply, setup, bvh, total;
    const auto add = [&](const LoadedScene& l) {
        parse.push_back(l.figures.seconds.parse.median);
        ply.push_back(l.figures.seconds.ply.median);
        setup.push_back(l.figures.seconds.setup.median);
        bvh.push_back(l.figures.seconds.bvh.median);
        total.push_back(l.load.median);
    };
    add(*s);
    RunOptions again = o;  // the first run reported the warnings
    again.quiet = true;
    again.strict = false;
    for (int run = 1; run < o.repeat; ++run) {
        s.reset();
        s = load_once(scene_path, again);
        if (!s) return s;
        add(*s);
    }
    s->figures.seconds = SceneTimes{timing_of(parse), timing_of(ply), timing_of(setup), timing_of(bvh)};
    s->load = timing_of(total);
    return s;
}

// "0.123s", or with --repeat "0.123s (0.120..0.131)": the median (fastest..slowest).
std::string seconds_text(const Timing& t, int repeat) {
    char buf[96];
    if (repeat <= 1)
        std::snprintf(buf, sizeof buf, "%.3fs", t.median);
    else
        std::snprintf(buf, sizeof buf, "%.3fs (%.3f..%.3f)", t.median, t.min, t.max);
    return buf;
}

// The summary line's rays: how many the render traced and how fast (of the median run),
// and the samples per pixel of a camera that takes several.
std::string rays_text(const Camera& cam, const ImageRecord& r) {
    const auto metric = [](double v) {
        char buf[32];
        if (v >= 1e9)
            std::snprintf(buf, sizeof buf, "%.2fG", v / 1e9);
        else if (v >= 1e6)
            std::snprintf(buf, sizeof buf, "%.2fM", v / 1e6);
        else if (v >= 1e3)
            std::snprintf(buf, sizeof buf, "%.1fk", v / 1e3);
        else
            std::snprintf(buf, sizeof buf, "%.0f", v);
        return std::string(buf);
    };
    const double rays = double(r.render_stats.rays.total());
    std::string samples;
    if (r.adaptive) {
        char buf[96];
        std::snprintf(buf, sizeof buf, "adaptive: %.1f samples per pixel on average, at most %d, ",
                      double(r.render_stats.samples) / (double(cam.width) * cam.height), r.adaptive);
        samples = buf;
    } else if (cam.samples > 0) {
        samples = count_of(size_t(cam.samples), "sample") + " per pixel, ";
    }
    return samples + metric(rays) + " rays, " + metric(r.render.median > 0 ? rays / r.render.median : 0) + " rays/s";
}

// --sample-map's file for image `image`: the path given, or with several images the
// path's stem, "_", the image's own stem and the path's extension.
std::string sample_map_path(const std::string& map, const std::string& image, bool several) {
    if (!several) return map;
    const std::filesystem::path m(map), i(image);
    return (m.parent_path() / (m.stem().string() + "_" + i.stem().string() + m.extension().string())).string();
}

// The grey map of `counts` (a pixel's samples, row-major): 255 at `cap` samples, 0 at none.
Image sample_map(const std::vector<uint32_t>& counts, int width, int height, int cap) {
    Image map;
    map.width = width;
    map.height = height;
    map.rgb.assign(static_cast<size_t>(width) * height * 3, 0);
    for (size_t i = 0; i < counts.size() && i * 3 < map.rgb.size(); ++i) {
        const double level = std::min(255.0, std::round(255.0 * counts[i] / cap));
        map.rgb[3 * i] = map.rgb[3 * i + 1] = map.rgb[3 * i + 2] = static_cast<uint8_t>(level);
    }
    return map;
}

// Renders camera `c` (0-based) of a loaded scene --repeat times and writes it once;
// returns its record. Throws on failure (InputError for an unwritable path).
ImageRecord render_camera(const std::string& scene_path, const LoadedScene& s, size_t c, const std::string& out,
                          const RunOptions& o) {
    const Camera& cam = s.scene.setup.cameras[c];
    make_parent_folders(out);
    RenderOptions ropt = o.render;
    ropt.count_samples = !o.sample_map.empty();
    app::ProgressLine progress(o.progress && !o.quiet && app::stderr_is_terminal());
    if (progress.enabled()) ropt.progress = [&progress](int done, int total) { progress.update(done, total); };
    ImageRecord r;
    r.scene = scene_path;
    r.image = out;
    r.camera = c + 1;
    r.width = cam.width;
    r.height = cam.height;
    r.figures = s.figures;
    r.repeat = o.repeat;
    r.cull = o.render.trace.cull;
    r.min_weight = o.render.trace.min_weight;
    r.bvh = o.bvh;
    std::vector<double> renders;
    Image img;
    for (int run = 0; run < o.repeat; ++run) {
        progress.start(o.repeat > 1 ? out + " (run " + std::to_string(run + 1) + " of " + std::to_string(o.repeat) + ")"
                                    : out);
        const auto r0 = std::chrono::steady_clock::now();
        img = render(s.scene, c, ropt, &r.render_stats);
        renders.push_back(seconds_since(r0));
        progress.clear();
    }
    r.render = timing_of(renders);
    r.render_rss = app::resident_bytes();
    const PixelSampling sampling = pixel_sampling(s.scene, c, ropt.sampling);
    if (sampling.noise_target > 0) r.adaptive = sampling.max_samples;
    r.sampler = sampler_name(sampling.sampler);
    const auto w0 = std::chrono::steady_clock::now();
    write_image(img, out);
    r.write = timing_of({seconds_since(w0)});
    if (!o.sample_map.empty()) {
        const std::string map = sample_map_path(o.sample_map, out, o.several_files || s.scene.setup.cameras.size() > 1);
        make_parent_folders(map);
        write_image(sample_map(r.render_stats.pixel_samples, cam.width, cam.height, std::max(1, sampling.pattern())),
                    map);
    }
    if (!o.quiet) {
        const std::string warned = s.warnings == 0 ? "" : ", " + count_of(s.warnings, "warning");
        const std::string runs =
            o.repeat <= 1 ? "" : "median (fastest..slowest) of " + std::to_string(o.repeat) + " runs: ";
        std::fprintf(stderr, "%s: %dx%d, %s, %s, %sload %s, bvh %s, render %s (%s), write %.3fs%s%s\n", out.c_str(),
                     cam.width, cam.height, kPrecisionName, bvh_counts(s.figures).c_str(), runs.c_str(),
                     seconds_text(s.load, o.repeat).c_str(), seconds_text(s.figures.seconds.bvh, o.repeat).c_str(),
                     seconds_text(r.render, o.repeat).c_str(), rays_text(cam, r).c_str(), r.write.median,
                     o.repeat <= 1 ? "" : " (written once)", warned.c_str());
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
            // fail: their work runs on the calling thread, rt/core/threads.h).
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
    for (ShapeKind k : kShapeKinds) f.shapes[size_t(k)] = scene.geometry.count(k);
    // Triangles stored: those of the meshes instances draw too, each mesh once.
    for (const auto& m : scene.geometry.mesh_scenes)
        f.shapes[size_t(ShapeKind::Triangle)] += m->geometry.triangles.size();
    f.lights = scene.setup.lights.size();
    f.degenerate = scene.report.degenerate_triangles;
    f.bvh_nodes = scene.accel.bvh.nodes.size();
    f.bvh_depth = scene.accel.bvh.depth;
    f.bvh_block = scene.accel.bvh.block;
    f.max_recursion_depth = scene.setup.max_recursion_depth;
    f.shadow_ray_epsilon = double(scene.setup.shadow_ray_epsilon);
    f.seconds = seconds;
    f.seconds.bvh = timing_of({double(scene.report.build_seconds)});
    return f;
}

Timing timing_of(std::vector<double> samples) {
    if (samples.empty()) return {};
    std::sort(samples.begin(), samples.end());
    const size_t n = samples.size();
    const double median = n % 2 == 1 ? samples[n / 2] : (samples[n / 2 - 1] + samples[n / 2]) / 2;
    return {median, samples.front(), samples.back()};
}

std::vector<std::string> select_frames(const std::vector<std::string>& files, const FrameSelection& s) {
    std::vector<std::string> out;
    for (size_t i = s.first, k = 0; i < files.size() && i <= s.last; ++i, ++k)
        if (k % s.shards == s.shard) out.push_back(files[i]);
    return out;
}

RunReport run_scenes(const std::vector<std::string>& scene_paths, const RunOptions& options) {
    RunReport report;
    MeshCache meshes;
    RunOptions o = options;
    if (scene_paths.size() > 1 || o.frames) {
        o.meshes = &meshes;
        o.several_files = true;
    }
    for (const std::string& path : scene_paths) report.ok = run_scene(path, o, report.images) && report.ok;
    const MeshCache::Counts n = meshes.counts();
    if (o.meshes && !o.quiet && n.ply_reads > 0)
        std::fprintf(stderr, "%s: %s read once, then served %zu times; %s built once, then reused %zu times\n",
                     count_of(scene_paths.size(), "scene file").c_str(), count_of(n.ply_reads, "PLY file").c_str(),
                     n.ply_reuses, count_of(n.builds, "mesh BVH").c_str(), n.build_reuses);
    return report;
}

int run_trace(const std::string& scene_path, const RunOptions& o, const PixelTraceRequest& req) {
    const std::optional<LoadedScene> s = load_once(scene_path, o);
    if (!s) return 1;
    const std::vector<Camera>& cameras = s->scene.setup.cameras;
    if (req.camera < 1 || req.camera > cameras.size())
        throw UsageError("--camera " + std::to_string(req.camera) + ": " + scene_path + " has " +
                         count_of(cameras.size(), "camera"));
    const Camera& cam = cameras[req.camera - 1];
    if (req.x < 0 || req.y < 0 || req.x >= cam.width || req.y >= cam.height)
        throw UsageError("--trace " + std::to_string(req.x) + "," + std::to_string(req.y) + ": outside the " +
                         std::to_string(cam.width) + "x" + std::to_string(cam.height) + " image of camera " +
                         std::to_string(req.camera) + " (x 0.." + std::to_string(cam.width - 1) + ", y 0.." +
                         std::to_string(cam.height - 1) + ")");
    const int samples = std::max(1, pixel_sampling(s->scene, req.camera - 1, o.render.sampling).pattern());
    if (req.sample >= samples)
        throw UsageError("--sample " + std::to_string(req.sample) + ": camera " + std::to_string(req.camera) +
                         " takes " + count_of(size_t(samples), "sample") + " per pixel (0.." +
                         std::to_string(samples - 1) + ")");
    PixelTrace t = trace_pixel(s->scene, req.camera - 1, req.x, req.y, o.render.trace, o.render.rounding,
                               o.render.sampling, req.sample);
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
