// rtdiff's modes: what the modes of rtdiff_main.cpp (two images, two folders) and the
// manifest mode (rtdiff_manifest.cpp) share. Outside namespace rt: compiled once, in the
// double library, as nothing here uses Real.
#pragma once
#include <optional>
#include <set>
#include <string>

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

// Writes `heat`, the heatmap of the pair named `name` (relative path), into the folders
// --heatmap and --html name, when given (their subfolders created as needed).
void write_heatmaps(const rt::Image& heat, const std::string& name, const Options& o);

// The image files (PNG, PPM) under folder `dir` and its subfolders, as sorted relative
// paths with '/' ("grass/grass_desert.png"); the --html and --heatmap folders, and any
// folder holding an rtdiff page (index.html), are not entered. Throws rt::InputError when `dir` cannot be read.
std::set<std::string> image_files(const std::string& dir, const Options& o);

// The manifest mode (docs/rtdiff.md): every image o.manifest names, found under `out_dir`,
// compared with its reference; returns the exit status, 0 or 1.
int compare_manifest(const std::string& out_dir, const Options& o);

}  // namespace rtdiff
