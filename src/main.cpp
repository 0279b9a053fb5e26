// raytracer: parse, then build, then render, then write — per scene file.
#include <sys/stat.h>

#include <cerrno>
#include <cmath>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "cli/run_stats.h"
#include "rt/error.h"
#include "rt/loader.h"
#include "rt/render.h"
#include "rt/scene.h"

namespace {

const char* kVersion = "raytracer 1.0";
const char* kUsage =
    "usage: raytracer [-o DIR] [-j N] [--cull|--no-cull] [--rounding truncate|nearest] [--stats FILE] [-q] scene.json|scene.xml...";

void print_help() {
    std::printf(
        "%s\n\n"
        "Renders every camera of each scene file (JSON, or the course's older XML format when the\n"
        "name ends in .xml) to the image its ImageName names: PNG (.png) or binary PPM (.ppm).\n\n"
        "options:\n"
        "  -o, --output-dir DIR   write relative image names under DIR (created if needed)\n"
        "  -j, --threads N        render with N threads (default: all hardware threads)\n"
        "      --cull, --no-cull  back-face culling of camera and reflection rays (default: on)\n"
        "      --rounding MODE    truncate (default, as the reference images) or nearest\n"
        "      --stats FILE       write figures per image (times, rays by kind, BVH, memory) to FILE as JSON\n"
        "  -q, --quiet            print errors only (and no progress line, which is shown only on a terminal)\n"
        "  -h, --help             show this help\n"
        "      --version          show the version\n\n"
        "for measurements (the defaults are the scene's values and the tuned BVH):\n"
        "      --max-depth N      override every scene's MaxRecursionDepth (0..10000)\n"
        "      --epsilon-scale F  multiply every scene's ShadowRayEpsilon by F (> 0)\n"
        "      --bvh-leaf N       largest BVH leaf (1..1024, default 8)\n"
        "      --bvh-bins N       SAH bins per axis (2..16, default 16)\n"
        "      --bvh-split MODE   sah (default) or median (object-median splits, no SAH)\n"
        "      --bvh-cost F       SAH cost of a node visit relative to a leaf block test (0.1..100, default 1)\n"
        "      --bvh-block N      primitives a leaf block holds in the SAH cost (1..16, default: as many as one\n"
        "                         leaf test takes, 4 with AVX2)\n\n"
        "exit status: 0 all images written, 1 bad input or an image could not be written, 2 usage error\n",
        kUsage);
}

[[noreturn]] void usage_error(const std::string& msg) {
    std::fprintf(stderr, "raytracer: %s\n%s\n", msg.c_str(), kUsage);
    std::exit(2);
}

struct Options {
    std::string output_dir;
    rt::RenderOptions render;
    bool quiet = false;
    std::vector<std::string> scenes;
    std::string stats_path;   // --stats
    bool progress = false;    // a progress line: stderr is a terminal and not --quiet
    int max_depth = -1;       // --max-depth; -1: the scene's
    double epsilon_scale = 1; // --epsilon-scale
    rt::BvhBuildOptions bvh;  // --bvh-*
};

// Figures of every image written, for --stats.
std::vector<rt::cli::ImageRecord> g_stats;

// A whole number in [lo, hi] for option `name`, or a usage error.
// v as a number, or NaN when the whole of v is not one (callers check their range).
double real_number(const std::string& v) {
    char* end = nullptr;
    const double f = std::strtod(v.c_str(), &end);
    return v.empty() || *end != '\0' ? std::nan("") : f;
}

long whole_number(const std::string& name, const std::string& v, long lo, long hi) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || errno != 0 || n < lo || n > hi)
        usage_error(name + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                    ", got '" + v + "'");
    return n;
}

Options parse_args(int argc, char** argv) {
    Options o;
    bool only_files = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const char* name) -> std::string {
            if (i + 1 >= argc) usage_error(std::string("option ") + name + " needs a value");
            return argv[++i];
        };
        if (only_files || a.empty() || a[0] != '-' || a == "-") {
            o.scenes.push_back(a);
        } else if (a == "--") {
            only_files = true;
        } else if (a == "-h" || a == "--help") {
            print_help();
            std::exit(0);
        } else if (a == "--version") {
            std::printf("%s\n", kVersion);
            std::exit(0);
        } else if (a == "-o" || a == "--output-dir") {
            o.output_dir = value("--output-dir");
        } else if (a.rfind("--output-dir=", 0) == 0) {
            o.output_dir = a.substr(13);
        } else if (a == "-j" || a == "--threads" || a.rfind("--threads=", 0) == 0) {
            const std::string v = a.size() > 10 && a[1] == '-' && a[9] == '=' ? a.substr(10) : value("--threads");
            char* end = nullptr;
            errno = 0;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (v.empty() || *end != '\0' || errno != 0 || n < 1 || n > 1024)
                usage_error("--threads needs a whole number from 1 to 1024, got '" + v + "'");
            o.render.threads = static_cast<int>(n);
        } else if (a == "--cull") {
            o.render.cull = true;
        } else if (a == "--no-cull") {
            o.render.cull = false;
        } else if (a == "--rounding" || a.rfind("--rounding=", 0) == 0) {
            const std::string v = a == "--rounding" ? value("--rounding") : a.substr(11);
            if (v == "truncate") o.render.rounding = rt::Rounding::Truncate;
            else if (v == "nearest") o.render.rounding = rt::Rounding::Nearest;
            else usage_error("--rounding takes truncate or nearest, got '" + v + "'");
        } else if (a == "-q" || a == "--quiet") {
            o.quiet = true;
        } else if (a == "--stats" || a.rfind("--stats=", 0) == 0) {
            o.stats_path = a == "--stats" ? value("--stats") : a.substr(8);
            if (o.stats_path.empty()) usage_error("--stats needs a file name");
        } else if (a == "--max-depth") {
            o.max_depth = static_cast<int>(whole_number(a, value("--max-depth"), 0, 10000));
        } else if (a == "--epsilon-scale") {
            const std::string v = value("--epsilon-scale");
            const double f = real_number(v);
            if (!(f > 0) || !(f < 1e30)) usage_error("--epsilon-scale needs a positive number, got '" + v + "'");
            o.epsilon_scale = f;
        } else if (a == "--bvh-cost") {
            const std::string v = value("--bvh-cost");
            const double f = real_number(v);
            if (!(f >= 0.1) || !(f <= 100)) usage_error("--bvh-cost needs a number from 0.1 to 100, got '" + v + "'");
            o.bvh.traversal_cost = static_cast<float>(f);
        } else if (a == "--bvh-block") {
            o.bvh.block = static_cast<uint32_t>(whole_number(a, value("--bvh-block"), 1, 16));
        } else if (a == "--bvh-leaf") {
            o.bvh.max_leaf = static_cast<uint32_t>(whole_number(a, value("--bvh-leaf"), 1, 1024));
        } else if (a == "--bvh-bins") {
            o.bvh.bins = static_cast<int>(whole_number(a, value("--bvh-bins"), 2, 16));
        } else if (a == "--bvh-split") {
            const std::string v = value("--bvh-split");
            if (v == "sah") o.bvh.sah = true;
            else if (v == "median") o.bvh.sah = false;
            else usage_error("--bvh-split takes sah or median, got '" + v + "'");
        } else {
            usage_error("unknown option '" + a + "'");
        }
    }
    if (o.scenes.empty()) usage_error("no scene file given");
    o.progress = !o.quiet && rt::cli::stderr_is_terminal();
    return o;
}

// Creates every missing parent folder of `path`; throws on failure.
void make_parents(const std::string& path) {
    for (size_t pos = path.find('/', 1); pos != std::string::npos; pos = path.find('/', pos + 1)) {
        const std::string dir = path.substr(0, pos);
        if (::mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST)
            throw rt::InputError(path + ": cannot create folder " + dir + ": " + std::strerror(errno));
    }
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Renders every camera of one scene file; returns false if anything failed.
bool run_scene(const std::string& scene_path, const Options& o) {
    const auto t0 = std::chrono::steady_clock::now();
    rt::Scene scene;
    double load_s = 0;
    rt::cli::SceneTimes times;
    try {
        rt::SceneDesc desc = rt::load_scene(scene_path);
        times.ply = desc.ply_seconds;
        times.parse = seconds_since(t0) - desc.ply_seconds;
        if (!o.quiet)
            for (const std::string& w : desc.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
        // Every image name is checked before anything is rendered: .png or .ppm.
        bool names_ok = true;
        for (size_t c = 0; c < desc.cameras.size(); ++c) {
            if (rt::image_format_of(desc.cameras[c].image_name) != rt::ImageFormat::Unknown) continue;
            std::fprintf(stderr, "%s: camera %zu: ImageName '%s': unknown image format (the name must end in .png or .ppm)\n",
                         scene_path.c_str(), c + 1, desc.cameras[c].image_name.c_str());
            names_ok = false;
        }
        if (!names_ok) return false;
        const auto b0 = std::chrono::steady_clock::now();
        scene = rt::build_scene(std::move(desc), o.bvh);
        times.bvh = double(scene.report.build_seconds);
        times.setup = seconds_since(b0) - times.bvh;
        load_s = seconds_since(t0) - scene.report.build_seconds;
        if (o.max_depth >= 0) scene.setup.max_recursion_depth = o.max_depth;
        scene.setup.shadow_ray_epsilon = static_cast<rt::Real>(scene.setup.shadow_ray_epsilon * o.epsilon_scale);
        if (scene.report.degenerate_triangles > 0 && !o.quiet)
            std::fprintf(stderr, "warning: %s: skipped %zu degenerate triangle%s\n", scene_path.c_str(),
                         scene.report.degenerate_triangles, scene.report.degenerate_triangles > 1 ? "s" : "");
    } catch (const rt::InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
        return false;
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: out of memory while loading\n", scene_path.c_str());
        return false;
    } catch (const std::exception& e) {
        // Not expected (every bad input is an InputError); still one line, no crash.
        std::fprintf(stderr, "%s: cannot load: %s\n", scene_path.c_str(), e.what());
        return false;
    }

    bool ok = true;
    for (size_t c = 0; c < scene.setup.cameras.size(); ++c) {
        const rt::Camera& cam = scene.setup.cameras[c];
        std::string out = cam.image_name;
        if (!o.output_dir.empty() && out[0] != '/') out = o.output_dir + "/" + out;
        try {
            make_parents(out);
            rt::RenderOptions ropt = o.render;
            rt::cli::ProgressLine progress(o.progress);
            if (progress.enabled()) {
                progress.start(out);
                ropt.progress = [&progress](int done, int total) { progress.update(done, total); };
            }
            rt::RenderStats rstats;
            const auto r0 = std::chrono::steady_clock::now();
            const rt::Image img = rt::render(scene, c, ropt, &rstats);
            const double render_s = seconds_since(r0);
            progress.clear();
            const auto w0 = std::chrono::steady_clock::now();
            rt::write_image(img, out);
            const double write_s = seconds_since(w0);
            if (!o.quiet)
                std::fprintf(stderr, "%s: %dx%d, %zu triangles, %zu spheres, load %.3fs, bvh %.3fs, render %.3fs, write %.3fs\n",
                             out.c_str(), cam.width, cam.height, scene.geometry.triangles.size(), scene.geometry.spheres.size(), load_s,
                             double(scene.report.build_seconds), render_s, write_s);
            if (!o.stats_path.empty()) {
                rt::cli::ImageRecord r;
                r.scene = scene_path;
                r.image = out;
                r.camera = c + 1;
                r.width = cam.width;
                r.height = cam.height;
                r.triangles = scene.geometry.triangles.size();
                r.spheres = scene.geometry.spheres.size();
                r.planes = scene.geometry.planes.size();
                r.lights = scene.setup.lights.size();
                r.degenerate = scene.report.degenerate_triangles;
                r.times = times;
                r.render = render_s;
                r.write = write_s;
                r.render_stats = rstats;
                r.cull = o.render.cull;
                r.max_recursion_depth = scene.setup.max_recursion_depth;
                r.shadow_ray_epsilon = double(scene.setup.shadow_ray_epsilon);
                r.bvh_nodes = scene.accel.bvh.nodes.size();
                r.bvh_depth = scene.accel.bvh.depth;
                r.bvh = o.bvh;
                r.peak_rss = rt::cli::peak_rss_bytes();
                g_stats.push_back(std::move(r));
            }
        } catch (const rt::InputError& e) {
            std::fprintf(stderr, "%s: camera %zu: %s\n", scene_path.c_str(), c + 1, e.what());
            ok = false;
        } catch (const std::bad_alloc&) {
            std::fprintf(stderr, "%s: camera %zu: out of memory rendering %s\n", scene_path.c_str(), c + 1,
                         out.c_str());
            ok = false;
        } catch (const std::exception& e) {
            // E.g. std::system_error when no thread can be started.
            std::fprintf(stderr, "%s: camera %zu: cannot render %s: %s\n", scene_path.c_str(), c + 1, out.c_str(),
                         e.what());
            ok = false;
        }
    }
    return ok;
}

}  // namespace

int main(int argc, char** argv) {
    const Options o = parse_args(argc, argv);
    bool ok = true;
    for (const std::string& s : o.scenes) ok = run_scene(s, o) && ok;
    if (!o.stats_path.empty()) {
        try {
            rt::write_file_atomic(o.stats_path, rt::cli::stats_json(g_stats, kVersion));
        } catch (const rt::InputError& e) {
            std::fprintf(stderr, "%s\n", e.what());
            ok = false;
        }
    }
    return ok ? 0 : 1;
}
