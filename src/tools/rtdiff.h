// rtdiff's modes: what the modes of rtdiff_main.cpp (two images, two folders), the manifest
// mode (rtdiff_manifest.cpp) and the Monte Carlo comparison (rtdiff_mc.cpp) share. Outside
// namespace rt: compiled once, in the double library, as nothing here uses Real.
#pragma once
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "rt/image/block_diff.h"
#include "rt/image/image.h"
#include "rt/image/image_diff.h"

namespace rtdiff {

struct Options {
    int tolerance = 1;
    std::string heatmap;               // two images: a PNG; folders and manifests: a folder
    std::optional<double> fail_above;  // percent of pixels
    std::string html;                  // a folder for index.html and its heatmaps
    std::string scene;                 // two images: the scene of the trace command, when known
    std::optional<long> camera;        // two images: the trace command's --camera
    bool only_common = false;          // two folders: say nothing of images in one folder only
    std::string manifest;              // the manifest mode: the course's MANIFEST.tsv
    // The Monte Carlo comparison (rt/image/block_diff.h): for every pair with --mc, for a
    // manifest's scenes whose cameras take more than one sample per pixel without it.
    bool mc = false;
    int block = 16;             // pixels a side
    int block_threshold = 3;    // a block is off when some channel's mean is off by more (levels)
    double max_off_blocks = 1;  // a pass: at most this percent of the blocks off,
    double max_mean_diff = 1;   // and every channel's mean signed difference within this (levels)
    std::string noise;          // two images: A rendered with another seed, the noise floor
    std::string noise_dir;      // folders, manifests: the renders with another seed
};

// `s` as one shell word: as it is when it holds only characters no shell treats specially,
// else in single quotes.
std::string shell_word(const std::string& s);

// The command that traces pixel `p`: "./raytracer --trace X,Y [--camera N] SCENE", the
// scene "<scene.json>" when unknown (empty).
std::string trace_command(const rt::PixelDiff& p, const std::string& scene, std::optional<long> camera);

// Creates `dir` and its parents; throws rt::InputError when it cannot.
void create_folder(const std::string& dir);

// The --html page's heatmap of image `name` (a path relative to the folders compared),
// relative to the page: heatmaps/<name with .png>.
std::string page_heatmap(const std::string& name);

// `file` relative to folder `dir` (both existing), as a page in `dir` links to it.
std::string relative_to(const std::string& file, const std::string& dir);

bool over_limit(const rt::ImageComparison& c, const Options& o);

// Two images' outputs, when asked for: `heat` as the --heatmap file, and the --html page of
// one row named as A is (its figures `c` and its `worst` pixels).
void write_pair_outputs(const rt::Image& heat, const std::string& a_path, const std::string& b_path,
                        const rt::ImageComparison& c, const std::vector<rt::PixelDiff>& worst, const Options& o);

// Writes `heat`, the heatmap of the pair named `name` (relative path), into the folders
// --heatmap and --html name, when given (their subfolders created as needed).
void write_heatmaps(const rt::Image& heat, const std::string& name, const Options& o);

// The image files (PNG, PPM) under folder `dir` and its subfolders, as sorted relative
// paths with '/' ("grass/grass_desert.png"); the --html and --heatmap folders, and any
// folder holding an rtdiff page (index.html), are not entered. Throws rt::InputError when `dir` cannot be read.
std::set<std::string> image_files(const std::string& dir, const Options& o);

// The Monte Carlo comparison of `a` with `b` at o's block size and threshold.
rt::BlockComparison compare_mc(const rt::Image& a, const rt::Image& b, const Options& o);

// Why `c` is no pass by o's criterion (--max-off-blocks, --max-mean-diff), as "12.5000% of
// the blocks off by more than 3 (at most 1%)" and "mean difference over 1 level: R +2.10,
// B -1.20" joined by "; "; empty for a pass.
std::string mc_failure(const rt::BlockComparison& c, const Options& o);

// What a pass is: "at most 1% of the 16x16 blocks off by more than 3 levels and every
// channel's mean difference within 1 level".
std::string mc_criterion(const Options& o);

// The column headings of mc_figures, and the figures of `c` under them: the share of blocks
// off, the mean signed difference of R, G, B and all channels, RMSE and PSNR.
std::string mc_headings(const Options& o);
std::string mc_figures(const rt::BlockComparison& c);

// The noise floor: A against `other_path`, A rendered with another seed; nullopt and `note`
// saying why when that image cannot be read or its size is not A's.
std::optional<rt::BlockComparison> compare_noise(const rt::Image& a, const std::string& other_path, const Options& o,
                                                 std::string& note);

// Two images compared by --mc (docs/rtdiff.md), with o.noise's figures beside them when
// given; exit status 0 (a pass) or 1.
int compare_files_mc(const std::string& a_path, const std::string& b_path, const Options& o);

// The manifest mode (docs/rtdiff.md): every image o.manifest names, found under `out_dir`,
// compared with its reference; returns the exit status, 0 or 1.
int compare_manifest(const std::string& out_dir, const Options& o);

}  // namespace rtdiff
