// The raytracer program in this copy's precision (rt/app/program.h): reads the command
// line, renders every camera of each scene file (run_scenes) and writes --stats; or
// traces one pixel (--trace, run_trace).
#include <unistd.h>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <type_traits>
#include <vector>

#include "rt/app/program.h"
#include "rt/app/run.h"
#include "rt/cli/parser.h"
#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/image/image.h"
#include "rt/io/atomic_file.h"
#include "rt/loader/scene_desc.h"

// The instruction-set level this copy was compiled for (Makefile, ISAS); a build outside
// the Makefile's copies (the sanitized ones, say) is for the machine it was built on.
#ifndef RT_ISA_NAME
#define RT_ISA_NAME "native"
#endif

namespace rt {
namespace {

// A function's static, not a namespace-scope object: nothing of this copy runs before
// main() has chosen it (rt/cli/parser.h).
const cli::Program& program() {
    static const cli::Program p{
        "raytracer", "raytracer 1.0 (" RT_ISA_NAME " kernels)",
        "usage: raytracer [-o DIR] [-j N] [--precision double|float] [--isa LEVEL] [--cull|--no-cull]\n"
        "                 [--rounding truncate|nearest] [--min-weight W] [--stats FILE] [-q] [--strict]\n"
        "                 [--samples N] [--seed S] [--sampler MODE] [--noise-target E [--max-samples N]]\n"
        "                 [--sample-map FILE] [--repeat N] [--max-depth N] [--epsilon-scale F]\n"
        "                 [--bvh-... (measurements)] [--frames A:B] [--shard K/N] scene.json|scene.xml...\n"
        "       raytracer --trace X,Y [--camera N] [--sample K] [--trace-json FILE] [options] scene.json|scene.xml",
        "Renders every camera of each scene file (JSON, or the course's older XML format when the\n"
        "name ends in .xml) to the image its ImageName names: PNG (.png) or binary PPM (.ppm).\n",
        "exit status: 0 all images written, 1 bad input or an image could not be written, 2 usage error"};
    return p;
}

// Whether `path` holds a scene: JSON whose first key is "Scene", or XML with a <Scene>
// element near its start. Outputs (--stats, --trace-json) never overwrite one: the usual
// slip is `--stats scene.json more.json`, where the first scene is taken for the file name.
bool is_scene_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    std::string head(4096, '\0');
    in.read(head.data(), static_cast<std::streamsize>(head.size()));
    head.resize(static_cast<size_t>(in.gcount()));
    size_t i = 0;
    const auto skip_space = [&] {
        while (i < head.size() && std::isspace(static_cast<unsigned char>(head[i]))) ++i;
    };
    skip_space();
    if (i < head.size() && head[i] == '<') return head.find("<Scene") != std::string::npos;
    if (i >= head.size() || head[i++] != '{') return false;
    skip_space();
    return head.compare(i, 7, "\"Scene\"") == 0;
}

// Why the scene file `path` cannot be read, or "" when it can: not opened, not parsed. A name
// with a wildcard that names no file is a pattern the shell matched to nothing and passed
// on as written (quoted for GNU parallel or not, the shell that runs the command expands
// it): the message says so, and where relative paths start from.
std::string unreadable_scene(const std::string& path) {
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) return "cannot open: " + std::string(std::strerror(EISDIR));
    // access(), not open(): opening a FIFO (a <(...) of the shell) would wait for its writer.
    if (::access(path.c_str(), R_OK) == 0) return "";
    const int e = errno;
    std::string why = "cannot open: " + std::string(std::strerror(e));
    if (e == ENOENT && path.find_first_of("*?[") != std::string::npos) {
        const std::filesystem::path here = std::filesystem::current_path(ec);
        why += " (no file matches this pattern, so the shell passed it on unexpanded; relative paths start from " +
               (ec ? std::string("the current folder") : here.string()) + ")";
    }
    return why;
}

}  // namespace

int raytracer_cli(int argc, char** argv) {
    RunOptions o;
    std::vector<std::string> scenes;
    std::string stats_path;
    PixelTraceRequest request;
    bool trace = false, camera_given = false, sample_given = false;
    FrameSelection frames;
    cli::Parser app(program());
    cli::add_value(app, "-o,--output-dir", "DIR", "write relative image names under DIR (created if needed)",
                   [&o](const std::string& v) { o.output_dir = v; });
    cli::add_whole(app, "-j,--threads", "N", "render with N threads (default: all hardware threads)", o.render.threads,
                   1, 1024);
    bool float_precision = std::is_same_v<Real, float>;
    cli::add_choice(app, "--precision",
                    "double (default) or float (single precision; what it changes: docs/precision.md)", float_precision,
                    {{"double", false}, {"float", true}});
    cli::add_value(app, "--isa", "LEVEL",
                   "the copy of the kernels to run: auto (default: the best this CPU executes; the environment's "
                   "RT_ISA when set), x86-64, avx2 or avx512 (--version names the one running)",
                   [](const std::string&) {});
    app.add_flag("--cull,!--no-cull", o.render.trace.cull,
                 "back-face culling of camera and reflection rays (default: on)");
    cli::add_choice(app, "--rounding", "truncate (default, as the reference images) or nearest", o.render.rounding,
                    {{"truncate", Rounding::Truncate}, {"nearest", Rounding::Nearest}});
    cli::add_number(app, "--min-weight", "W",
                    "do not trace a reflected or refracted ray whose weight in the pixel is below W (0..1, default "
                    "1e-4; 0 traces every ray to MaxRecursionDepth, as the assignment does)",
                    o.render.trace.min_weight, "a number from 0 to 1", [](double w) { return w >= 0 && w <= 1; });
    cli::add_text(app, "--stats", "FILE", "write figures per image (times, rays by kind, BVH, memory) to FILE as JSON",
                  stats_path, "a file name");
    cli::add_value(app, "--trace", "X,Y",
                   "print the ray tree of pixel X,Y (column, row from the top left); render nothing",
                   [&trace, &request](const std::string& v) {
                       const size_t comma = v.find(',');
                       if (comma == std::string::npos) cli::usage_error("--trace needs X,Y, got '" + v + "'");
                       request.x = int(cli::whole_number("--trace X", v.substr(0, comma), 0, 1 << 30));
                       request.y = int(cli::whole_number("--trace Y", v.substr(comma + 1), 0, 1 << 30));
                       trace = true;
                   });
    cli::add_value(app, "--camera", "N", "--trace: the camera (1-based, default 1)",
                   [&request, &camera_given](const std::string& v) {
                       request.camera = size_t(cli::whole_number("--camera", v, 1, 1 << 30));
                       camera_given = true;
                   });
    cli::add_value(app, "--sample", "K",
                   "--trace: with samples per pixel (NumSamples), the sample to trace (0-based, default 0)",
                   [&request, &sample_given](const std::string& v) {
                       request.sample = int(cli::whole_number("--sample", v, 0, kMaxSamples - 1));
                       sample_given = true;
                   });
    cli::add_text(app, "--trace-json", "FILE", "--trace: also write the ray tree to FILE as JSON", request.json_path,
                  "a file name");
    app.group("samples (distribution ray tracing: docs/conventions.md, \"Assignment 3\")");
    cli::add_whole(app, "--samples", "N",
                   "take N samples per pixel in every camera, in place of its NumSamples (1.." +
                       std::to_string(kMaxSamples) + "; a quick preview at 4)",
                   o.render.samples, 1, kMaxSamples);
    cli::add_value(app, "--seed", "S",
                   "the random numbers' seed (0..2^62, default 0): the same seed gives the same image on any "
                   "machine and thread count, another seed independent noise",
                   [&o](const std::string& v) {
                       o.render.sampling.seed = uint64_t(cli::whole_number("--seed", v, 0, long(kMaxSeed)));
                   });
    cli::add_choice(
        app, "--sampler",
        "sobol (default: scrambled Sobol points), stratified (jittered, every pair of dimensions) or "
        "random (independent numbers, as the course's references were made): docs/sampling.md",
        o.render.sampling.sampler,
        {{"sobol", SamplerKind::Sobol}, {"stratified", SamplerKind::Stratified}, {"random", SamplerKind::Random}});
    cli::add_number(app, "--noise-target", "E",
                    "adaptive sampling: each pixel takes samples until the estimated standard error of its mean "
                    "is at most E output levels (0..255 after clamping) in every channel, or --max-samples",
                    o.render.sampling.noise_target, "a positive number of levels up to 255",
                    [](double e) { return e > 0 && e <= 255; });
    cli::add_whole(app, "--max-samples", "N",
                   "--noise-target: the most samples a pixel takes (1.." + std::to_string(kMaxSamples) + ", default " +
                       std::to_string(kAdaptiveCapFactor) + " times the camera's NumSamples)",
                   o.render.sampling.max_samples, 1, kMaxSamples);
    cli::add_text(app, "--sample-map", "FILE",
                  "write a grey PNG of the samples each pixel took (white: --max-samples, or NumSamples) to FILE; "
                  "with several images, FILE_<image name>.png each",
                  o.sample_map, "a file name");
    app.add_flag("-q,--quiet", o.quiet, "print errors only (and no progress line, which is shown only on a terminal)");
    app.add_flag(
        "--strict", o.strict,
        "treat every warning (unknown key, skipped triangle, ...) as an error: exit 1, no image of that scene");
    app.group("animations (several scene files, one per frame: docs/animations.md)");
    cli::add_value(app, "--frames", "A:B",
                   "render only frames A to B of the scene files given (0-based positions, both included; "
                   "A or B may be left out)",
                   [&frames, &o](const std::string& v) {
                       const size_t colon = v.find(':');
                       if (colon == std::string::npos) cli::usage_error("--frames needs A:B, got '" + v + "'");
                       const std::string a = v.substr(0, colon), b = v.substr(colon + 1);
                       if (!a.empty()) frames.first = size_t(cli::whole_number("--frames A", a, 0, 1 << 30));
                       if (!b.empty()) frames.last = size_t(cli::whole_number("--frames B", b, 0, 1 << 30));
                       if (frames.first > frames.last) cli::usage_error("--frames " + v + ": A is after B");
                       o.frames = true;
                   });
    cli::add_value(app, "--shard", "K/N",
                   "render every N-th of those frames from the K-th (0 <= K < N): N processes (GNU parallel, a "
                   "Slurm array) with K = 0..N-1 share an animation",
                   [&frames, &o](const std::string& v) {
                       const size_t slash = v.find('/');
                       if (slash == std::string::npos) cli::usage_error("--shard needs K/N, got '" + v + "'");
                       frames.shards = size_t(cli::whole_number("--shard N", v.substr(slash + 1), 1, 1 << 30));
                       frames.shard =
                           size_t(cli::whole_number("--shard K", v.substr(0, slash), 0, int(frames.shards) - 1));
                       o.frames = true;
                   });
    app.group("for measurements (the defaults are the scene's values and the tuned BVH)");
    cli::add_whole(app, "--repeat", "N",
                   "load, build and render each scene N times (1..1000); the summary line and --stats give the "
                   "median, fastest and slowest run of each phase; every image is written once",
                   o.repeat, 1, 1000);
    cli::add_whole(app, "--max-depth", "N",
                   "override every scene's MaxRecursionDepth (0.." + std::to_string(kMaxRecursionDepth) + ")",
                   o.render.max_depth, 0, kMaxRecursionDepth);
    cli::add_number(app, "--epsilon-scale", "F", "multiply every scene's ShadowRayEpsilon by F (> 0)",
                    o.render.epsilon_scale, "a positive number", [](double f) { return f > 0 && f < 1e30; });
    cli::add_whole(app, "--bvh-leaf", "N", "largest BVH leaf (1..1024, default 8 in double, 16 in float)",
                   o.bvh.max_leaf, 1, 1024);
    cli::add_whole(app, "--bvh-bins", "N", "SAH bins per axis (2..16, default 16)", o.bvh.bins, 2, 16);
    cli::add_choice(app, "--bvh-split", "sah (default) or median (object-median splits, no SAH)", o.bvh.sah,
                    {{"sah", true}, {"median", false}});
    cli::add_choice(app, "--bvh-collapse", "yes (default) or no (keep the top-down tree's sparse bottom nodes)",
                    o.bvh.collapse, {{"yes", true}, {"no", false}});
    cli::add_number(app, "--bvh-cost", "F",
                    "SAH cost of a node visit relative to a leaf block test (0.1..100, default 1)",
                    o.bvh.traversal_cost, "a number from 0.1 to 100", [](double f) { return f >= 0.1 && f <= 100; });
    cli::add_whole(app, "--bvh-block", "N",
                   "primitives a leaf block holds in the SAH cost (1..16, default: as many as one leaf test takes, "
                   "at most 4 in double for scenes of up to 2^17 primitives; --stats names it)",
                   o.bvh.block, 1, 16);
    app.add_operands("scenes", scenes);
    app.final_check([&] {
        if (scenes.empty()) cli::usage_error("no scene file given");
        if (trace && scenes.size() > 1) cli::usage_error("--trace takes one scene file");
        if (trace && o.frames)
            cli::usage_error("--frames and --shard pick scene files to render; --trace renders nothing");
        if (!trace && (camera_given || sample_given || !request.json_path.empty()))
            cli::usage_error("--camera, --sample and --trace-json need --trace");
        if (trace && o.repeat != 1) cli::usage_error("--repeat times renders; --trace renders nothing");
        if (o.render.sampling.max_samples > 0 && !(o.render.sampling.noise_target > 0))
            cli::usage_error("--max-samples caps adaptive sampling: it needs --noise-target");
        if (trace && !o.sample_map.empty()) cli::usage_error("--sample-map maps a render; --trace renders nothing");
        for (const auto& [flag, out] :
             {std::pair{"--stats", &stats_path}, {"--trace-json", &request.json_path}, {"--sample-map", &o.sample_map}})
            if (!out->empty() && is_scene_file(*out))
                cli::usage_error(std::string(flag) + " " + *out + ": that is a scene file; it is not overwritten");
    });
    if (const auto status = app.parse(argc, argv)) return *status;
    // main() (src/main.cpp) picked this copy of the program from the same arguments.
    if (float_precision != std::is_same_v<Real, float>) {
        cli::print_error(std::string("internal error: --precision ") + (float_precision ? "float" : "double") +
                         " reached the " + kPrecisionName + " renderer");
        return 1;
    }

    if (trace) {
        try {
            return run_trace(scenes[0], o, request);
        } catch (const UsageError& e) {
            return cli::report_usage_error(program(), e.what());
        }
    }

    if (o.frames) {
        // Every shard checks every file given, not only its own frames, before rendering
        // anything: a wrong path fails all shards alike (each job of a Slurm array reports it).
        bool all_readable = true;
        for (const std::string& s : scenes)
            if (const std::string why = unreadable_scene(s); !why.empty()) {
                cli::print_error(s + ": " + why);
                all_readable = false;
            }
        if (!all_readable) return 1;
        const size_t given = scenes.size();
        scenes = select_frames(scenes, frames);
        if (scenes.empty()) {
            // More shards than frames leaves some shards idle: a warning (an error under --strict).
            const std::string what = "no frame to render: " + count_of(given, "scene file") +
                                     " given, none in this selection (frames " + std::to_string(frames.first) + ":" +
                                     (frames.last == SIZE_MAX ? std::string() : std::to_string(frames.last)) +
                                     ", shard " + std::to_string(frames.shard) + "/" + std::to_string(frames.shards) +
                                     ")";
            if (o.strict) {
                cli::print_error(what + "; --strict makes it an error");
                return 1;
            }
            if (!o.quiet) std::fprintf(stderr, "warning: %s\n", what.c_str());
            return 0;
        }
    }
    const RunReport report = run_scenes(scenes, o);
    bool ok = report.ok;
    if (!stats_path.empty()) {
        try {
            write_file_atomic(stats_path, stats_json(report.images, program().version));
        } catch (const InputError& e) {
            cli::print_error(e.what());
            ok = false;
        }
    }
    return ok ? 0 : 1;
}

}  // namespace rt
