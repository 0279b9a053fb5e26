// --stats, the ray counters, the progress line and the measurement switches
// (--max-depth, --epsilon-scale, --bvh-*): the JSON has the documented fields with
// plausible values, ray counts do not depend on the thread count and equal what
// rt::render reports, the progress line appears on a terminal only, and the switches
// change what they should and nothing else.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <thread>
#include <type_traits>
#include <vector>

#include "rt/app/run.h"
#include "rt/bvh/bvh.h"
#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "test_support.h"

namespace {

using json = nlohmann::json;

// Our showcase scene (glass, a conductor, a mirror, a plane, two lights) at the given
// size, plus a PLY mesh, written into `dir`; returns the scene's path.
std::string write_scene(const std::string& dir, int width, int height, const std::string& image = "out.png") {
    json scene = json::parse(read_text(repo_file("scenes/showcase.json")));
    json& cam = scene["Scene"]["Cameras"]["Camera"];
    cam["ImageResolution"] = std::to_string(width) + " " + std::to_string(height);
    cam["ImageName"] = image;
    write_text(dir + "/tetra.ply",
               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
               "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
               "-2.5 0 1\n-1.5 0 1\n-2 0 2\n-2 1 1.5\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 2 0 3\n");
    scene["Scene"]["Objects"]["Mesh"].push_back(
        {{"_id", "3"}, {"Material", "4"}, {"Faces", {{"_plyFile", "tetra.ply"}}}});
    const std::string path = dir + "/scene.json";
    write_text(path, scene.dump(2));
    return path;
}

// Runs the raytracer with --stats; returns the parsed document (empty on failure).
json run_stats(const std::vector<std::string>& extra, const std::string& scene, const TempDir& dir,
               RunResult* result = nullptr) {
    const std::string stats = dir / "stats.json";
    std::vector<std::string> args = {"--stats", stats, "-o", dir.path()};
    args.insert(args.end(), extra.begin(), extra.end());
    args.push_back(scene);
    const RunResult r = run_raytracer(args);
    if (result) *result = r;
    EXPECT_EQ(r.exit_code, 0) << r.err;
    if (r.exit_code != 0 || !file_exists(stats)) return json();
    return json::parse(read_text(stats));
}

struct Rays {
    uint64_t camera, shadow, reflection, refraction;
};
Rays rays_of(const json& image) {
    const json& r = image.at("rays");
    return {r.at("camera").get<uint64_t>(), r.at("shadow").get<uint64_t>(), r.at("reflection").get<uint64_t>(),
            r.at("refraction").get<uint64_t>()};
}

TEST(Stats, JsonHasTheDocumentedFieldsWithPlausibleValues) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 96, 54);
    const json doc = run_stats({"-j", "2"}, scene, dir);
    ASSERT_TRUE(doc.is_object());
    EXPECT_EQ(doc.at("raytracer"), "raytracer 1.0 (" RT_ISA_NAME " kernels)");  // the copy that ran
    EXPECT_TRUE(doc.at("precision") == "double" || doc.at("precision") == "float");
    EXPECT_TRUE(doc.at("machine").at("cpu").is_string());
    // What std::thread::hardware_concurrency() says on this machine (0 when it cannot tell):
    // the raytracer runs here too, so it must report the same count.
    EXPECT_EQ(doc.at("machine").at("hardware_threads").get<unsigned>(), std::thread::hardware_concurrency());
    ASSERT_EQ(doc.at("images").size(), 1u);
    const json& im = doc.at("images")[0];
    EXPECT_EQ(im.at("scene"), scene);
    EXPECT_EQ(im.at("image"), dir / "out.png");
    EXPECT_EQ(im.at("camera"), 1);
    EXPECT_EQ(im.at("width"), 96);
    EXPECT_EQ(im.at("height"), 54);
    const json& p = im.at("primitives");
    EXPECT_EQ(p.at("triangles"), 2 + 3 + 4);
    EXPECT_EQ(p.at("spheres"), 3);
    EXPECT_EQ(p.at("planes"), 1);
    EXPECT_EQ(p.at("lights"), 2);
    EXPECT_EQ(p.at("degenerate_skipped"), 0);
    EXPECT_EQ(im.at("threads"), 2);
    EXPECT_EQ(im.at("cull"), true);
    EXPECT_EQ(im.at("min_weight"), 1e-4);  // the default
    EXPECT_EQ(im.at("max_recursion_depth"), 6);
    // The scene's epsilon as rt::Real holds it (1e-3 rounded to float in float).
    EXPECT_DOUBLE_EQ(im.at("shadow_ray_epsilon").get<double>(), double(rt::Real(1e-3)));
    for (const char* k : {"parse", "ply", "setup", "bvh", "render", "write"}) {
        const double s = im.at("seconds").at(k).get<double>();
        EXPECT_GE(s, 0) << k;
        EXPECT_LT(s, 60) << k;
    }
    EXPECT_GT(im.at("seconds").at("ply").get<double>(), 0);  // one PLY file was read
    EXPECT_GT(im.at("seconds").at("render").get<double>(), 0);
    const Rays r = rays_of(im);
    EXPECT_EQ(r.camera, 96u * 54u);                                     // one camera ray per pixel
    EXPECT_GT(r.shadow, 0u);                                            // two lights over a lit floor
    EXPECT_GT(r.reflection, 0u);                                        // mirror, conductor, glass
    EXPECT_GT(r.refraction, 0u);                                        // glass
    EXPECT_LE(r.shadow, 2 * (r.camera + r.reflection + r.refraction));  // at most one per light per hit
    EXPECT_EQ(im.at("rays").at("total").get<uint64_t>(), r.camera + r.shadow + r.reflection + r.refraction);
    EXPECT_GT(im.at("rays_per_second").get<double>(), 0);
    EXPECT_GE(im.at("bvh").at("nodes").get<int>(), 1);
    EXPECT_GE(im.at("bvh").at("depth").get<int>(), 1);
    EXPECT_EQ(im.at("bvh").at("max_leaf"), rt::kDefaultMaxLeaf);
    EXPECT_EQ(im.at("bvh").at("bins"), 16);
    EXPECT_EQ(im.at("bvh").at("split"), "sah");
    EXPECT_GT(im.at("peak_rss_bytes").get<uint64_t>(), 1u << 20);
    EXPECT_LT(im.at("peak_rss_bytes").get<uint64_t>(), uint64_t(4) << 30);
    // Resident at the end of the render: something, and never above the peak.
    EXPECT_GT(im.at("render_rss_bytes").get<uint64_t>(), 1u << 20);
    EXPECT_LE(im.at("render_rss_bytes").get<uint64_t>(), im.at("peak_rss_bytes").get<uint64_t>());
}

TEST(Stats, OneRecordPerImageAcrossScenes) {
    TempDir dir;
    const std::string a = write_scene(dir.path(), 32, 16, "a.png");
    const std::string sub = dir / "sub";
    ASSERT_EQ(::mkdir(sub.c_str(), 0777), 0);
    const std::string b = write_scene(sub, 16, 32, "b.png");
    const std::string stats = dir / "stats.json";
    const RunResult r = run_raytracer({"--stats=" + stats, "-o", dir.path(), a, b});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const json doc = json::parse(read_text(stats));
    ASSERT_EQ(doc.at("images").size(), 2u);
    EXPECT_EQ(doc["images"][0]["image"], dir / "a.png");
    EXPECT_EQ(doc["images"][1]["image"], dir / "b.png");
    EXPECT_EQ(doc["images"][1]["width"], 16);
    EXPECT_EQ(rays_of(doc["images"][1]).camera, 16u * 32u);
}

TEST(Stats, RayCountsDoNotDependOnTheThreadCount) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 80, 45);
    const json one = run_stats({"-j", "1"}, scene, dir);
    const json three = run_stats({"-j", "3"}, scene, dir);
    ASSERT_FALSE(one.is_null());
    ASSERT_FALSE(three.is_null());
    EXPECT_EQ(one["images"][0]["threads"], 1);
    EXPECT_EQ(three["images"][0]["threads"], 3);
    EXPECT_EQ(one["images"][0]["rays"], three["images"][0]["rays"]);
}

TEST(Stats, RenderStatsOfTheLibraryEqualTheCommandLines) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 64, 36);
    for (const bool cull : {true, false}) {
        const json doc = run_stats({"-j", "2", cull ? "--cull" : "--no-cull"}, scene, dir);
        ASSERT_FALSE(doc.is_null());
        const Rays cli = rays_of(doc["images"][0]);

        const rt::Scene s = rt::build_scene(rt::load_scene(scene));
        for (const int threads : {1, 2, 5}) {
            rt::RenderOptions o;
            o.threads = threads;
            o.trace.cull = cull;
            rt::RenderStats st;
            const rt::Image img = rt::render(s, 0, o, &st);
            EXPECT_EQ(st.threads, threads);
            EXPECT_EQ(st.tiles, 4 * 3);
            EXPECT_EQ(st.rays.camera, cli.camera);
            EXPECT_EQ(st.rays.shadow, cli.shadow);
            EXPECT_EQ(st.rays.reflection, cli.reflection);
            EXPECT_EQ(st.rays.refraction, cli.refraction);
            EXPECT_EQ(st.rays.total(), doc["images"][0]["rays"]["total"].get<uint64_t>());
            // The stats never change the picture.
            rt::Image plain = rt::render(s, 0, o);
            EXPECT_EQ(img.rgb, plain.rgb);
        }
    }
}

TEST(Stats, ProgressCallbackIsRareAndChangesNothing) {
    TempDir dir;
    const rt::Scene s = rt::build_scene(rt::load_scene(write_scene(dir.path(), 320, 180)));
    rt::RenderOptions o;
    o.threads = 2;
    rt::RenderStats plain_stats;
    const rt::Image plain = rt::render(s, 0, o, &plain_stats);
    int calls = 0, last_done = -1, total = 0;
    bool monotone = true;
    o.progress = [&](int done, int tiles) {
        ++calls;
        monotone = monotone && done >= last_done && done <= tiles;
        last_done = done;
        total = tiles;
    };
    o.progress_interval = 0.001;
    rt::RenderStats st;
    const rt::Image img = rt::render(s, 0, o, &st);
    EXPECT_EQ(img.rgb, plain.rgb);
    EXPECT_EQ(st.rays.total(), plain_stats.rays.total());
    EXPECT_TRUE(monotone);
    if (calls > 0) {
        EXPECT_EQ(total, 20 * 12);
    }
}

TEST(Stats, NoProgressLineWhenStderrIsNotATerminal) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 640, 360);
    const RunResult r = run_raytracer({"-j", "1", "-o", dir.path(), scene});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(r.err.find('\r'), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find('%'), std::string::npos) << r.err;
    const RunResult q = run_raytracer({"-q", "-o", dir.path(), scene});
    ASSERT_EQ(q.exit_code, 0);
    EXPECT_EQ(q.err, "");
}

// Runs ./raytracer with stderr (and stdout) on a new pseudo-terminal; returns what it wrote.
std::string run_on_terminal(const std::vector<std::string>& args, int* exit_code) {
    *exit_code = -1;
    const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
    if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) return "no pty";
    const char* slave_name = ::ptsname(master);
    if (!slave_name) return "no pty";
    const std::string slave_path = slave_name;
    std::vector<std::string> storage = raytracer_args(args);
    storage.insert(storage.begin(), raytracer_path());
    std::vector<char*> argv;
    for (std::string& s : storage) argv.push_back(s.data());
    argv.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::setsid();
        const int slave = ::open(slave_path.c_str(), O_RDWR);
        const int null = ::open("/dev/null", O_RDONLY);
        if (slave < 0 || null < 0 || ::dup2(null, 0) < 0 || ::dup2(slave, 1) < 0 || ::dup2(slave, 2) < 0) _exit(127);
        ::close(master);
        ::alarm(120);
        ::execv(argv[0], argv.data());
        _exit(127);
    }
    std::string out;
    char buf[4096];
    for (;;) {
        const ssize_t n = ::read(master, buf, sizeof buf);
        if (n > 0)
            out.append(buf, size_t(n));
        else if (n < 0 && errno == EINTR)
            continue;
        else
            break;  // EIO once the child has closed the terminal
    }
    ::close(master);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    *exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
    return out;
}

TEST(Stats, ProgressLineOnATerminalClearedBeforeTheSummary) {
    TempDir dir;
    // Large enough that the render, on one thread, lasts several 50 ms progress updates.
    const std::string scene = write_scene(dir.path(), 1280, 720);
    int code = 0;
    const std::string out = run_on_terminal({"-j", "1", "-o", dir.path(), scene}, &code);
    ASSERT_EQ(code, 0) << out;
    EXPECT_NE(out.find('\r'), std::string::npos) << out;
    EXPECT_NE(out.find("% "), std::string::npos) << out;
    EXPECT_NE(out.find("s elapsed"), std::string::npos) << out;
    // The summary is the last line, on a line of its own: cleared, then written.
    const std::string summary =
        dir / (std::string("out.png: 1280x720, ") + rt::kPrecisionName + ", 9 triangles, 3 spheres");
    const size_t at = out.rfind(summary);
    ASSERT_NE(at, std::string::npos) << out;
    EXPECT_EQ(out[at - 1], '\r');
    EXPECT_EQ(out.find('%', at), std::string::npos);

    const std::string quiet = run_on_terminal({"-q", "-j", "1", "-o", dir.path(), scene}, &code);
    EXPECT_EQ(code, 0);
    EXPECT_EQ(quiet, "");
}

TEST(Stats, MeasurementSwitches) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 64, 36);
    const json base = run_stats({}, scene, dir);
    ASSERT_FALSE(base.is_null());
    rt::Image ref;
    ASSERT_TRUE(load_png(dir / "out.png", ref));

    // MaxRecursionDepth 0: camera and shadow rays only.
    const json flat = run_stats({"--max-depth", "0"}, scene, dir);
    ASSERT_FALSE(flat.is_null());
    EXPECT_EQ(flat["images"][0]["max_recursion_depth"], 0);
    EXPECT_EQ(rays_of(flat["images"][0]).reflection, 0u);
    EXPECT_EQ(rays_of(flat["images"][0]).refraction, 0u);
    EXPECT_EQ(rays_of(flat["images"][0]).camera, rays_of(base["images"][0]).camera);

    const json eps = run_stats({"--epsilon-scale", "10"}, scene, dir);
    ASSERT_FALSE(eps.is_null());
    // In float: the float epsilon times the (double) scale, rounded to float (run.cpp).
    const double scaled = std::is_same_v<rt::Real, float> ? double(rt::Real(double(rt::Real(1e-3)) * 10)) : 1e-2;
    EXPECT_DOUBLE_EQ(eps["images"][0]["shadow_ray_epsilon"].get<double>(), scaled);

    // The BVH's shape never changes the picture, nor the rays traced.
    for (const std::vector<std::string>& bvh : std::vector<std::vector<std::string>>{
             {"--bvh-leaf", "1"}, {"--bvh-leaf", "16", "--bvh-bins", "4"}, {"--bvh-split", "median"}}) {
        const json doc = run_stats(bvh, scene, dir);
        ASSERT_FALSE(doc.is_null());
        rt::Image img;
        ASSERT_TRUE(load_png(dir / "out.png", img));
        EXPECT_EQ(img.rgb, ref.rgb) << bvh[0] << " " << bvh[1];
        EXPECT_EQ(doc["images"][0]["rays"], base["images"][0]["rays"]);
    }
    const json leaf = run_stats({"--bvh-leaf", "2", "--bvh-bins", "8", "--bvh-split", "median"}, scene, dir);
    ASSERT_FALSE(leaf.is_null());
    EXPECT_EQ(leaf["images"][0]["bvh"]["max_leaf"], 2);
    EXPECT_EQ(leaf["images"][0]["bvh"]["bins"], 8);
    EXPECT_EQ(leaf["images"][0]["bvh"]["split"], "median");
    // The block the tree was priced with: the chosen one, or block_for's.
    EXPECT_EQ(leaf["images"][0]["bvh"]["block"], rt::BvhBuildOptions{}.block_for(1));
    const json block = run_stats({"--bvh-block", "3"}, scene, dir);
    ASSERT_FALSE(block.is_null());
    EXPECT_EQ(block["images"][0]["bvh"]["block"], 3);

    for (const std::vector<std::string>& bad : std::vector<std::vector<std::string>>{{"--max-depth", "-1"},
                                                                                     {"--epsilon-scale", "0"},
                                                                                     {"--epsilon-scale", "x"},
                                                                                     {"--bvh-leaf", "0"},
                                                                                     {"--bvh-bins", "17"},
                                                                                     {"--bvh-split", "fast"},
                                                                                     {"--stats"}}) {
        std::vector<std::string> args = bad;
        if (bad.size() > 1) args.push_back(scene);
        const RunResult r = run_raytracer(args);
        EXPECT_EQ(r.exit_code, 2) << bad[0] << ": " << r.err;
    }
}

TEST(Stats, UnwritableStatsFileIsAnError) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 16, 16);
    const RunResult r = run_raytracer({"--stats", dir / "no/such/folder/stats.json", "-o", dir.path(), scene});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_NE(r.err.find("stats.json: cannot write"), std::string::npos) << r.err;
    EXPECT_TRUE(file_exists(dir / "out.png"));  // the image itself was written
}

// The command's pipeline as a library function: one record per image written, the
// figures --stats writes; a bad scene fails alone.
// The median of an odd count is the middle sample, of an even count the mean of the
// middle two; min and max are the extremes; order does not matter.
TEST(Stats, TimingOfSamples) {
    const rt::Timing odd = rt::timing_of({0.3, 0.1, 0.2});
    EXPECT_EQ(odd.median, 0.2);
    EXPECT_EQ(odd.min, 0.1);
    EXPECT_EQ(odd.max, 0.3);
    const rt::Timing even = rt::timing_of({4, 1, 3, 2});
    EXPECT_EQ(even.median, 2.5);
    EXPECT_EQ(even.min, 1);
    EXPECT_EQ(even.max, 4);
    const rt::Timing one = rt::timing_of({0.5});
    EXPECT_EQ(one.median, 0.5);
    EXPECT_EQ(one.min, 0.5);
    EXPECT_EQ(one.max, 0.5);
    const rt::Timing none = rt::timing_of({});
    EXPECT_EQ(none.median, 0);
    EXPECT_EQ(none.max, 0);
}

// --repeat N: every phase timed N times (median, fastest, slowest on the summary line and
// in --stats), the warnings printed once, the image written once and byte-identical to a
// single run's.
TEST(Stats, RepeatTimesEveryPhaseAndWritesTheImageOnce) {
    TempDir dir;
    const std::string scene = write_scene(dir.path(), 48, 27);
    json with_typo = json::parse(read_text(scene));
    with_typo["Scene"]["MaxRecursionDeph"] = "6";
    write_text(scene, with_typo.dump(2));
    RunResult r;
    const json doc = run_stats({"--repeat", "4", "-j", "2"}, scene, dir, &r);
    ASSERT_EQ(doc.at("images").size(), 1u) << r.err;
    const json& im = doc.at("images")[0];
    EXPECT_EQ(im.at("repeat"), 4);
    for (const char* k : {"parse", "ply", "setup", "bvh", "render", "write"}) {
        const double lo = im.at("seconds_min").at(k), mid = im.at("seconds").at(k), hi = im.at("seconds_max").at(k);
        EXPECT_LE(lo, mid) << k;
        EXPECT_LE(mid, hi) << k;
    }
    // Four renders: four different durations, to the nanosecond.
    EXPECT_LT(im.at("seconds_min").at("render").get<double>(), im.at("seconds_max").at("render").get<double>());
    EXPECT_LT(im.at("seconds_min").at("parse").get<double>(), im.at("seconds_max").at("parse").get<double>());
    // Written once: one sample.
    EXPECT_EQ(im.at("seconds_min").at("write"), im.at("seconds").at("write"));
    EXPECT_EQ(im.at("seconds_max").at("write"), im.at("seconds").at("write"));
    EXPECT_EQ(im.at("rays").at("camera"), 48 * 27);  // one run's rays, not four runs'
    const std::vector<std::string> lines = split_lines(r.err);
    ASSERT_EQ(lines.size(), 2u) << r.err;
    EXPECT_EQ(lines[0],
              "warning: " + scene + ": /Scene/MaxRecursionDeph: unknown key ignored (did you mean MaxRecursionDepth?)");
    EXPECT_TRUE(contains(lines[1], ", median (fastest..slowest) of 4 runs: load ")) << lines[1];
    EXPECT_TRUE(contains(lines[1], "s (written once), 1 warning")) << lines[1];
    EXPECT_EQ(list_files(dir.path()), (std::vector<std::string>{"out.png", "scene.json", "stats.json", "tetra.ply"}));
    // The same bytes as one run's image.
    const RunResult once = run_raytracer({"-q", "-o", dir / "once", scene});
    ASSERT_EQ(once.exit_code, 0) << once.err;
    EXPECT_EQ(read_text(dir / "out.png"), read_text(dir / "once/out.png"));
}

TEST(Stats, RunScenesReturnsARecordPerImage) {
    TempDir dir;
    const std::string a = write_scene(dir.path(), 32, 16, "a.png");
    write_text(dir / "bad.json", "{\"Scene\": 1}");
    rt::RunOptions o;
    o.output_dir = dir / "out";
    o.quiet = true;
    o.render.threads = 2;
    o.render.max_depth = 2;
    o.bvh.max_leaf = 4;
    const rt::RunReport report = rt::run_scenes({a, dir / "bad.json", a}, o);
    EXPECT_FALSE(report.ok);
    ASSERT_EQ(report.images.size(), 2u);
    for (const rt::ImageRecord& r : report.images) {
        EXPECT_EQ(r.scene, a);
        EXPECT_EQ(r.image, dir / "out/a.png");
        EXPECT_EQ(r.camera, 1u);
        EXPECT_EQ(r.width, 32);
        EXPECT_EQ(r.height, 16);
        EXPECT_EQ(r.figures.shapes[size_t(rt::ShapeKind::Triangle)], 2u + 3u + 4u);
        EXPECT_EQ(r.figures.shapes[size_t(rt::ShapeKind::Sphere)], 3u);
        EXPECT_EQ(r.figures.max_recursion_depth, 2);
        EXPECT_EQ(r.render_stats.threads, 2);
        EXPECT_EQ(r.render_stats.rays.camera, 32u * 16u);
        EXPECT_EQ(r.bvh.max_leaf, 4u);
        EXPECT_GT(r.peak_rss, 0u);
    }
    EXPECT_TRUE(file_exists(dir / "out/a.png"));
    const json doc = json::parse(rt::stats_json(report.images, "raytracer 1.0"));
    ASSERT_EQ(doc.at("images").size(), 2u);
    EXPECT_EQ(doc["images"][1]["primitives"]["triangles"], 9);
    EXPECT_EQ(doc["images"][1]["bvh"]["max_leaf"], 4);
}

// mkdir -p of an image's folder: missing folders are made, an existing one (or a file in
// its place, which the write reports) is no error, a folder that cannot be made is.
TEST(Stats, MakeParentFolders) {
    TempDir dir;
    rt::make_parent_folders(dir / "a/b/c/x.png");
    EXPECT_TRUE(file_exists(dir / "a/b/c"));
    rt::make_parent_folders(dir / "a/b/c/x.png");
    rt::make_parent_folders("x.png");
    write_text(dir / "file", "");
    rt::make_parent_folders(dir / "file/x.png");
    try {
        rt::make_parent_folders("/proc/no_such_dir/d/x.png");
        ADD_FAILURE() << "no error";
    } catch (const rt::InputError& e) {
        EXPECT_STREQ(e.what(),
                     "/proc/no_such_dir/d/x.png: cannot create folder /proc/no_such_dir: No such file or directory");
    }
}

// The SAH's leaf block: a given one (clamped to 16) whatever the scene; by default a
// leaf test's lanes, at most four where leaves read the double vertex copy.
TEST(Stats, LeafBlockFollowsTheVertexCopy) {
    rt::BvhBuildOptions o;
    const size_t small = o.double_copy_max, large = o.double_copy_max + 1;
    constexpr bool kDouble = std::is_same_v<rt::Real, double>;
    EXPECT_EQ(o.double_copies(small), kDouble);
    EXPECT_FALSE(o.double_copies(large));
    EXPECT_EQ(o.block_for(large), rt::kLeafBlock);
    EXPECT_EQ(o.block_for(small), kDouble ? std::min(rt::kLeafBlock, 4u) : rt::kLeafBlock);
    o.block = 3;
    EXPECT_EQ(o.block_for(small), 3u);
    EXPECT_EQ(o.block_for(large), 3u);
    o.block = 40;
    EXPECT_EQ(o.block_for(small), 16u);
    o.double_copy_max = 0;  // float copies only
    o.block = 0;
    EXPECT_EQ(o.block_for(small), rt::kLeafBlock);
}

// Default build options are the tuned constants: the tree is the same, node for node.
TEST(Stats, DefaultBvhOptionsBuildTheSameTree) {
    TempDir dir;
    const rt::SceneDesc d = rt::load_scene(write_scene(dir.path(), 16, 16));
    const rt::Scene a = rt::build_scene(d);
    rt::BvhBuildOptions o;
    EXPECT_EQ(o.max_leaf, rt::kDefaultMaxLeaf);
    EXPECT_EQ(o.bins, 16);
    EXPECT_FLOAT_EQ(o.traversal_cost, 1.0f);
    EXPECT_EQ(o.block, 0u);  // chosen by block_for
    EXPECT_TRUE(o.sah);
    const rt::Scene b = rt::build_scene(d, o);
    EXPECT_EQ(b.accel.bvh.block, o.block_for(b.accel.bvh.prims.size()));
    ASSERT_EQ(a.accel.bvh.nodes.size(), b.accel.bvh.nodes.size());
    EXPECT_EQ(0, std::memcmp(a.accel.bvh.nodes.begin(), b.accel.bvh.nodes.begin(),
                             a.accel.bvh.nodes.size() * sizeof(rt::BvhNode)));
    EXPECT_EQ(a.accel.bvh.prims, b.accel.bvh.prims);
    o.max_leaf = 1;
    const rt::Scene c = rt::build_scene(d, o);
    for (const rt::BvhNode& n : c.accel.bvh.nodes)
        for (int i = 0; i < rt::BvhNode::kWidth; ++i)
            if (n.is_leaf(i) && n.child[i] != rt::BvhNode::kEmpty) {
                EXPECT_LE(n.leaf_size(i), 1u);
            }
}

}  // namespace
