// rtdiff: compares two images, every image of the same relative path in two folders, or
// every image a course manifest names with its reference, with the measure the
// conformance tests use (rt/image/image_diff.h; issue 15), or with --mc by the means of
// blocks of pixels (rt/image/block_diff.h). The manifest mode is in rtdiff_manifest.cpp, the
// Monte Carlo figures and two images compared by them in rtdiff_mc.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <new>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rt/cli/options.h"
#include "rt/core/error.h"
#include "rt/image/image.h"
#include "rt/image/image_diff.h"
#include "rt/io/atomic_file.h"
#include "rtdiff.h"

namespace fs = std::filesystem;

namespace {

using rtdiff::Options;

const rt::cli::Program kProgram{
    "rtdiff", "rtdiff 1.0",
    "usage: rtdiff [--tolerance N] [--heatmap OUT] [--html DIR] [--fail-above P]\n"
    "              [--scene FILE [--camera N]] [--only-common] A B\n"
    "       rtdiff --mc [--block N] [--block-threshold L] [--max-off-blocks P] [--max-mean-diff L]\n"
    "              [--noise OTHER | --noise-dir DIR] [--heatmap OUT] [--html DIR] [--only-common] A B\n"
    "       rtdiff --manifest MANIFEST.tsv [--tolerance N] [--heatmap DIR] [--html DIR]\n"
    "              [--fail-above P] [--mc] [--block N] [--block-threshold L] [--max-off-blocks P]\n"
    "              [--max-mean-diff L] [--noise-dir DIR] OUTDIR",
    "Compares image A with image B (PNG or PPM), or every image of the same relative path in\n"
    "folders A and B and their subfolders: size, largest and mean channel difference, the\n"
    "pixels with some channel off by more than the tolerance (count, share and bounding box)\n"
    "and PSNR; then where: the 5 pixels that differ most (x,y as raytracer --trace takes them,\n"
    "both values) and the command that traces the worst (folders: the worst pixel of each pair\n"
    "that differs). Images in one folder only are not compared; one line per folder names them.\n"
    "--manifest: each image the course's MANIFEST.tsv names, found in OUTDIR or a subfolder,\n"
    "against its reference: one row per scene (pass, FAIL over --fail-above, default 0.2%;\n"
    "missing; ambiguous; skipped when the scene's inputs are incomplete) and a total.\n"
    "--mc, for Monte Carlo renders (many random samples per pixel), instead: the share of\n"
    "16x16 blocks with some channel's block mean off by more than 3 levels, the mean signed\n"
    "difference A - B per channel and overall, RMSE and PSNR; a pass has at most 1% of the\n"
    "blocks off and every channel's mean difference within 1 level. --manifest compares so\n"
    "every scene whose cameras take NumSamples > 1. --noise: the same figures of A against\n"
    "A rendered with another seed, the noise floor.\n",
    "exit status: 0 compared (and within --fail-above); 1 bad input, a pair of folders' images\n"
    "that could not be compared, no image in both folders, or over --fail-above; --mc: a pair\n"
    "that is not a pass; manifests: a malformed line, or a scene that is not a pass (skipped\n"
    "ones aside); 2 usage error.\n"
    "Images in one folder only do not change it."};

// How many of the worst pixels two images' comparison lists.
constexpr size_t kWorstPixels = 5;
// How many names the line of the images in one folder only lists before "...".
constexpr size_t kOnlyNames = 4;

using rtdiff::create_folder;
using rtdiff::over_limit;
using rtdiff::page_heatmap;
using rtdiff::relative_to;

// One pair of images; exit status 0 or 1.
int compare_files(const std::string& a_path, const std::string& b_path, const Options& o) {
    const rt::Image a = rt::read_image(a_path);
    const rt::Image b = rt::read_image(b_path);
    const rt::ImageComparison c = rt::compare_images(a, b, o.tolerance);
    if (!c.same_size)
        throw rt::InputError(b_path + ": " + std::to_string(b.width) + "x" + std::to_string(b.height) + ", but " +
                             a_path + " is " + std::to_string(a.width) + "x" + std::to_string(a.height));
    std::printf("%s vs %s: same size, %dx%d\n", a_path.c_str(), b_path.c_str(), c.width, c.height);
    std::printf("max %d, mean %.4f, %zu of %zu pixels (%.4f%%) off by more than %d, PSNR %s, box %s\n", c.max_diff,
                c.mean_diff, c.pixels_over, c.pixels, c.pct_over, c.tolerance, rt::psnr_text(c.psnr).c_str(),
                rt::box_text(c).c_str());
    const std::vector<rt::PixelDiff> worst = rt::worst_pixels(a, b, kWorstPixels);
    if (!worst.empty()) {
        std::printf("worst pixels (x,y as raytracer --trace takes them), largest channel difference first:\n");
        for (const rt::PixelDiff& p : worst) std::printf("  %s\n", rt::pixel_text(p).c_str());
        std::printf("trace the worst: %s\n", rtdiff::trace_command(worst.front(), o.scene, o.camera).c_str());
    }
    if (!o.heatmap.empty() || !o.html.empty())
        rtdiff::write_pair_outputs(rt::heatmap_with_legend(a, b, c), a_path, b_path, c, worst, o);
    if (over_limit(c, o)) {
        std::printf("over --fail-above %g%%\n", *o.fail_above);
        return 1;
    }
    return 0;
}

struct Row {
    std::string name;
    rt::ImageComparison c;
    std::string error;                 // not empty: this pair could not be compared
    std::vector<rt::PixelDiff> worst;  // its worst pixel, when any differs
    // --mc: the block comparison, why it is no pass (empty for a pass), and --noise-dir's
    // figures of A against its other seed, or why there are none.
    rt::BlockComparison m;
    std::string failure;
    std::optional<rt::BlockComparison> noise;
    std::string noise_note;
};

// The table of compare_dirs: one row per pair, "  OVER" after those over --fail-above, the
// worst pixel under each that differs; returns the pairs over --fail-above.
size_t print_rows(const std::vector<Row>& rows, int w, const Options& o) {
    std::printf("%-*s  %9s  %4s  %8s  %10s  %9s  %s\n", w, "image", "size", "max", "mean", "% off", "PSNR", "box");
    size_t over = 0;
    for (const Row& r : rows) {
        if (!r.error.empty()) {
            std::printf("%-*s  %s\n", w, r.name.c_str(), r.error.c_str());
            continue;
        }
        const std::string size = std::to_string(r.c.width) + "x" + std::to_string(r.c.height);
        const bool bad = over_limit(r.c, o);
        if (bad) ++over;
        std::printf("%-*s  %9s  %4d  %8.4f  %10.4f  %9s  %s%s\n", w, r.name.c_str(), size.c_str(), r.c.max_diff,
                    r.c.mean_diff, r.c.pct_over, rt::psnr_text(r.c.psnr).c_str(), rt::box_text(r.c).c_str(),
                    bad ? "  OVER" : "");
        if (!r.worst.empty()) std::printf("  worst pixel %s\n", rt::pixel_text(r.worst.front()).c_str());
    }
    return over;
}

// The table of compare_dirs with --mc: one row per pair, "  FAIL" after those that are no
// pass, the other seed's figures under each when --noise-dir is given; returns the FAILs.
size_t print_mc_rows(const std::vector<Row>& rows, int w, const Options& o) {
    std::printf("%-*s  %9s  %s\n", w, "image", "size", rtdiff::mc_headings(o).c_str());
    size_t failed = 0;
    for (const Row& r : rows) {
        if (!r.error.empty()) {
            std::printf("%-*s  %s\n", w, r.name.c_str(), r.error.c_str());
            continue;
        }
        const std::string size = std::to_string(r.c.width) + "x" + std::to_string(r.c.height);
        if (!r.failure.empty()) ++failed;
        std::printf("%-*s  %9s  %s%s\n", w, r.name.c_str(), size.c_str(), rtdiff::mc_figures(r.m).c_str(),
                    r.failure.empty() ? "" : "  FAIL");
        if (r.noise)
            std::printf("%-*s  %9s  %s\n", w, "  vs other seed", "", rtdiff::mc_figures(*r.noise).c_str());
        else if (!o.noise_dir.empty())
            std::printf("  vs other seed: %s\n", r.noise_note.c_str());
    }
    return failed;
}

// "21 images only in B (not compared): a.png, b.png, c.png, d.png, ...": one line for all
// the images found in folder `dir` only; nothing when there are none.
void print_only_in(const std::string& dir, const std::vector<std::string>& names) {
    if (names.empty()) return;
    std::string list;
    for (size_t i = 0; i < names.size() && i < kOnlyNames; ++i) list += (i ? ", " : "") + names[i];
    if (names.size() > kOnlyNames) list += ", ...";
    std::printf("%zu image%s only in %s (not compared): %s\n", names.size(), names.size() == 1 ? "" : "s", dir.c_str(),
                list.c_str());
}

// Writes the --html page: index.html in o.html, beside the heatmaps compare_dirs wrote.
void write_page(const std::string& a_dir, const std::string& b_dir, const Options& o, const std::vector<Row>& rows,
                const std::vector<std::string>& only_a, const std::vector<std::string>& only_b) {
    std::vector<rt::DiffPageRow> page;
    for (const Row& r : rows) {
        rt::DiffPageRow p{r.name,
                          r.c,
                          r.error,
                          r.worst,
                          relative_to((fs::path(a_dir) / r.name).string(), o.html),
                          relative_to((fs::path(b_dir) / r.name).string(), o.html),
                          ""};
        if (r.error.empty()) p.heatmap_link = page_heatmap(r.name);
        page.push_back(p);
    }
    rt::write_file_atomic((fs::path(o.html) / "index.html").string(),
                          rt::diff_page_html(a_dir, b_dir, o.tolerance, page, only_a, only_b));
}

// Two folders; exit status 0 or 1.
int compare_dirs(const std::string& a_dir, const std::string& b_dir, const Options& o) {
    const std::set<std::string> a_names = rtdiff::image_files(a_dir, o), b_names = rtdiff::image_files(b_dir, o);
    if (!o.heatmap.empty()) create_folder(o.heatmap);
    if (!o.html.empty()) create_folder((fs::path(o.html) / "heatmaps").string());
    std::vector<Row> rows;
    std::vector<std::string> only_a, only_b;
    if (!o.only_common) {
        for (const std::string& n : a_names)
            if (!b_names.count(n)) only_a.push_back(n);
        for (const std::string& n : b_names)
            if (!a_names.count(n)) only_b.push_back(n);
    }
    int status = 0;
    for (const std::string& n : a_names) {
        if (!b_names.count(n)) continue;
        Row r;
        r.name = n;
        const std::string a_path = (fs::path(a_dir) / n).string(), b_path = (fs::path(b_dir) / n).string();
        try {
            const rt::Image a = rt::read_image(a_path), b = rt::read_image(b_path);
            r.c = rt::compare_images(a, b, o.tolerance);
            if (!r.c.same_size) {
                r.error = "sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) + " vs " +
                          std::to_string(b.width) + "x" + std::to_string(b.height);
            } else if (o.mc) {
                r.m = rtdiff::compare_mc(a, b, o);
                r.failure = rtdiff::mc_failure(r.m, o);
                if (!o.noise_dir.empty())
                    r.noise = rtdiff::compare_noise(a, (fs::path(o.noise_dir) / n).string(), o, r.noise_note);
            } else {
                r.worst = rt::worst_pixels(a, b, 1);
            }
            if (r.c.same_size && (!o.heatmap.empty() || !o.html.empty()))
                rtdiff::write_heatmaps(
                    o.mc ? rt::block_heatmap_with_legend(a, r.m) : rt::heatmap_with_legend(a, b, r.c), n, o);
        } catch (const rt::InputError& e) {
            r.error = e.what();
        }
        if (!r.error.empty()) status = 1;
        rows.push_back(r);
    }
    // Worst first: failures, then by share of pixels off, then by largest difference; --mc:
    // those that are no pass, then by share of blocks off, then by the largest channel's bias.
    std::stable_sort(rows.begin(), rows.end(), [&o](const Row& x, const Row& y) {
        if (x.error.empty() != y.error.empty()) return !x.error.empty();
        if (o.mc) {
            if (x.failure.empty() != y.failure.empty()) return !x.failure.empty();
            if (x.m.pct_off != y.m.pct_off) return x.m.pct_off > y.m.pct_off;
            return x.m.max_channel_bias() > y.m.max_channel_bias();
        }
        if (x.c.pct_over != y.c.pct_over) return x.c.pct_over > y.c.pct_over;
        return x.c.max_diff > y.c.max_diff;
    });
    size_t width = o.mc ? 15 : 5;  // --mc: "  vs other seed" under the rows
    for (const Row& r : rows) width = std::max(width, r.name.size());
    const size_t over = o.mc ? 0 : print_rows(rows, int(width), o);
    const size_t mc_failed = o.mc ? print_mc_rows(rows, int(width), o) : 0;
    print_only_in(a_dir, only_a);
    print_only_in(b_dir, only_b);
    std::printf("%zu compared", rows.size());
    if (!o.only_common)
        std::printf(", %zu only in %s, %zu only in %s", only_a.size(), a_dir.c_str(), only_b.size(), b_dir.c_str());
    if (o.fail_above) std::printf(", %zu over --fail-above %g%%", over, *o.fail_above);
    if (o.mc) std::printf(", %zu FAIL (a pass: %s)", mc_failed, rtdiff::mc_criterion(o).c_str());
    std::printf("\n");
    if (over > 0 || mc_failed > 0) status = 1;
    if (!o.html.empty()) write_page(a_dir, b_dir, o, rows, only_a, only_b);
    if (rows.empty()) {
        // Nothing compared is no success: a wrong folder must not pass a check.
        std::fflush(stdout);
        rt::cli::print_error("no image is in both " + a_dir + " and " + b_dir);
        status = 1;
    }
    return status;
}

bool is_dir(const std::string& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

bool percent(double v) { return v >= 0 && v <= 100; }
bool levels(double v) { return v >= 0 && v <= 255; }

// The usage error of a combination of options that does not go with the mode (nullopt when
// none); `folders`: two folders, not two images.
std::optional<std::string> mc_usage_error(const CLI::App& app, const Options& o, bool folders) {
    const bool manifest = !o.manifest.empty();
    size_t mc_options = 0;
    for (const char* name : {"--block", "--block-threshold", "--max-off-blocks", "--max-mean-diff"})
        mc_options += app.count(name);
    if (mc_options > 0 && !o.mc && !manifest)
        return "--block, --block-threshold, --max-off-blocks and --max-mean-diff need --mc (or --manifest)";
    if (o.mc && (app.count("--tolerance") || app.count("--fail-above")))
        return "--tolerance and --fail-above measure pixels, not --mc's blocks (--max-off-blocks, --max-mean-diff)";
    if (o.mc && (!o.scene.empty() || o.camera)) return "--scene and --camera do not go with --mc";
    if (!o.noise.empty() && (manifest || folders))
        return "--noise is for two images: with folders and --manifest, --noise-dir DIR";
    if (!o.noise_dir.empty() && !manifest && !folders) return "--noise-dir is for folders: with two images, --noise";
    if ((!o.noise.empty() || (!o.noise_dir.empty() && !manifest)) && !o.mc)
        return "--noise and --noise-dir need --mc (or --manifest)";
    return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
    namespace cli = rt::cli;
    Options o;
    std::vector<std::string> files;
    CLI::App app;
    cli::setup(app, kProgram);
    cli::add_whole(app, "--tolerance", "N",
                   "a pixel is off when some channel differs by more than N levels (default 1)", o.tolerance, 0, 255);
    cli::add_text(app, "--heatmap", "OUT",
                  "write where and how much the images differ as a PNG, its legend below it (folders and "
                  "--manifest: a folder of them)",
                  o.heatmap, "a file name");
    cli::add_value(app, "--fail-above", "P",
                   "exit status 1 when more than P% of the pixels are off (--manifest: a scene's FAIL, default 0.2)",
                   [&o](const std::string& v) {
                       o.fail_above = cli::number("--fail-above", v, "a percentage from 0 to 100", percent);
                   });
    cli::add_text(app, "--html", "DIR",
                  "write DIR/index.html: the figures, the images and heatmaps side by side (folders: worst first)",
                  o.html, "a folder name");
    cli::add_text(app, "--scene", "FILE",
                  "two images: the scene they were rendered from, for the command that traces the worst pixel", o.scene,
                  "a file name");
    cli::add_value(app, "--camera", "N", "two images: the scene's camera (1-based), for that command too",
                   [&o](const std::string& v) { o.camera = cli::whole_number("--camera", v, 1, 1 << 30); });
    app.add_flag("--only-common", o.only_common,
                 "two folders: compare the images in both and say nothing of those in one folder only");
    cli::add_text(app, "--manifest", "FILE",
                  "compare each image the course's MANIFEST.tsv names, found in OUTDIR or its subfolders, with "
                  "its reference (relative to the folder two above the manifest's)",
                  o.manifest, "a file name");
    app.add_flag("--mc", o.mc,
                 "compare as Monte Carlo renders: by the means of blocks of pixels (--manifest: every scene; "
                 "without it, the scenes whose cameras take NumSamples > 1)");
    cli::add_whole(app, "--block", "N", "--mc: blocks of N x N pixels (default 16)", o.block, 1, 1 << 16);
    cli::add_whole(app, "--block-threshold", "L",
                   "--mc: a block is off when some channel's block mean differs by more than L levels (default 3)",
                   o.block_threshold, 0, 255);
    cli::add_number(app, "--max-off-blocks", "P", "--mc: a pass has at most P% of the blocks off (default 1)",
                    o.max_off_blocks, "a percentage from 0 to 100", percent);
    cli::add_number(app, "--max-mean-diff", "L",
                    "--mc: a pass has every channel's mean signed difference within L levels (default 1)",
                    o.max_mean_diff, "a number of levels from 0 to 255", levels);
    cli::add_text(app, "--noise", "OTHER",
                  "--mc, two images: A rendered with another seed; its figures against A are printed too, the "
                  "noise floor",
                  o.noise, "a file name");
    cli::add_text(app, "--noise-dir", "DIR",
                  "--mc and --manifest: the renders with another seed, by the same names, for the noise floor",
                  o.noise_dir, "a folder name");
    app.add_option("files", files);
    app.final_callback([&files, &o] {
        const size_t want = o.manifest.empty() ? 2 : 1;
        if (files.size() < want)
            cli::usage_error(o.manifest.empty() ? "needs two images or two folders" : "--manifest needs OUTDIR");
        if (files.size() > want)
            cli::usage_error(o.manifest.empty() ? "too many files" : "--manifest takes one folder");
    });
    if (const auto status = cli::parse(app, kProgram, argc, argv)) return *status;

    try {
        const bool folders = o.manifest.empty() && is_dir(files[0]) && is_dir(files[1]);
        if (const auto error = mc_usage_error(app, o, folders)) return cli::report_usage_error(kProgram, *error);
        if (!o.noise_dir.empty() && !is_dir(o.noise_dir)) throw rt::InputError(o.noise_dir + ": not a folder");
        if (!o.manifest.empty()) {
            if (!o.scene.empty() || o.camera || o.only_common)
                return cli::report_usage_error(kProgram,
                                               "--scene, --camera and --only-common do not go with --manifest");
            return rtdiff::compare_manifest(files[0], o);
        }
        const bool a_dir = is_dir(files[0]), b_dir = is_dir(files[1]);
        if (a_dir && b_dir) {
            if (!o.scene.empty() || o.camera)
                return cli::report_usage_error(kProgram, "--scene and --camera need two images, not folders");
            return compare_dirs(files[0], files[1], o);
        }
        if (o.only_common && !a_dir && !b_dir)
            return cli::report_usage_error(kProgram, "--only-common needs two folders");
        if (a_dir != b_dir)
            throw rt::InputError((a_dir ? files[1] : files[0]) + ": not a folder, but " +
                                 (a_dir ? files[0] : files[1]) + " is one");
        return o.mc ? rtdiff::compare_files_mc(files[0], files[1], o) : compare_files(files[0], files[1], o);
    } catch (const rt::InputError& e) {
        rt::cli::print_error(e.what());
    } catch (const std::bad_alloc&) {
        rt::cli::print_error("out of memory");
    } catch (const std::exception& e) {
        rt::cli::print_error(e.what());
    }
    return 1;
}
