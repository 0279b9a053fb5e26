// rtdiff --manifest (docs/rtdiff.md): each image a course manifest (scenes/hwN/MANIFEST.tsv)
// names, found under a folder of renders, compared with its reference; one row per scene,
// pixel by pixel, or by --mc's block means for a scene whose cameras take many samples.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "rt/cli/options.h"
#include "rt/core/error.h"
#include "rt/io/atomic_file.h"
#include "rt/io/files.h"
#include "rt/loader/scene_tree.h"
#include "rtdiff.h"

namespace fs = std::filesystem;

namespace rtdiff {
namespace {

// A scene passes when at most this share of its pixels is off, unless --fail-above says
// otherwise: the bar the conformance tests hold our renderer to.
constexpr double kPassPct = 0.2;
// How many of the files found for one image an ambiguous row names before "...".
constexpr size_t kAmbiguousNames = 3;

// One line of a manifest: four tab-separated columns.
struct Entry {
    std::string scene;      // relative to the manifest's folder
    std::string image;      // the image the scene writes (its ImageName)
    std::string reference;  // relative to the shared folder
    std::string inputs;     // "complete ...", or why the scene cannot be rendered
    int line = 0;
};

std::string trim(const std::string& s) {
    const size_t b = s.find_first_not_of(" \t\r\n");
    if (b == std::string::npos) return "";
    return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

bool image_name(const std::string& name) { return rt::image_format_of(name) != rt::ImageFormat::Unknown; }

// The manifest's entries; each malformed line is an error "<path>:<line>: <what>" in `errors`.
std::vector<Entry> read_manifest(const std::string& path, std::vector<std::string>& errors) {
    std::istringstream text(rt::read_text_file(path));
    std::vector<Entry> entries;
    std::map<std::string, int> image_line;
    std::string line;
    for (int number = 1; std::getline(text, line); ++number) {
        const std::string where = path + ":" + std::to_string(number) + ": ";
        if (trim(line).empty() || trim(line)[0] == '#') continue;
        std::vector<std::string> cols;
        std::istringstream fields(line);
        for (std::string col; std::getline(fields, col, '\t');) cols.push_back(trim(col));
        if (cols.size() != 4) {
            errors.push_back(where + "4 tab-separated columns expected (scene, image, reference, inputs), found " +
                             std::to_string(cols.size()));
            continue;
        }
        Entry e{cols[0], cols[1], cols[2], cols[3], number};
        const char* const names[4] = {"scene", "image", "reference", "inputs"};
        const auto empty = std::find(cols.begin(), cols.end(), "");
        if (empty != cols.end())
            errors.push_back(where + "the " + names[empty - cols.begin()] + " column is empty");
        else if (!image_name(e.image) || !image_name(e.reference))
            errors.push_back(where + (image_name(e.image) ? e.reference : e.image) + ": not a .png or .ppm name");
        else if (fs::path(e.reference).is_absolute())
            errors.push_back(where + e.reference + ": the reference must be relative to the shared folder");
        else if (!image_line.emplace(e.image, number).second)
            errors.push_back(where + e.image + " is named on line " + std::to_string(image_line[e.image]) + " too");
        else
            entries.push_back(e);
    }
    if (entries.empty() && errors.empty()) errors.push_back(path + ": names no image");
    return entries;
}

// The files of `files` (paths relative to the renders' folder) that are image `image`: the
// same relative path, or the same path in a subfolder.
std::vector<std::string> matches(const std::set<std::string>& files, const std::string& image) {
    const std::string name = fs::path(image).lexically_normal().generic_string();
    std::vector<std::string> out;
    for (const std::string& f : files)
        if (f == name || (f.size() > name.size() && f.compare(f.size() - name.size(), name.size(), name) == 0 &&
                          f[f.size() - name.size() - 1] == '/'))
            out.push_back(f);
    return out;
}

// A scene file's tree (an XML scene read as the course's JSON, rt/loader/scene_tree.h), or
// why it cannot be read.
struct SceneTree {
    std::optional<nlohmann::ordered_json> tree;
    std::string why;
};

SceneTree read_scene(const std::string& scene) {
    SceneTree s;
    try {
        const std::string text = rt::read_text_file(scene);
        s.tree = rt::lower_extension(scene) == ".xml" ? rt::xml_to_json_tree(text, scene)
                                                      : rt::parse_json_tree<nlohmann::ordered_json>(text, scene);
    } catch (const rt::InputError& e) {
        s.why = std::string("cannot read it (") + e.what() + ")";
    }
    return s;
}

// The scene's /Scene/Cameras/Camera, one object or an array; nullptr when there is none.
const nlohmann::ordered_json* cameras(const SceneTree& s) {
    if (!s.tree) return nullptr;
    const nlohmann::ordered_json& t = *s.tree;
    if (t.contains("Scene") && t["Scene"].is_object() && t["Scene"].contains("Cameras") &&
        t["Scene"]["Cameras"].is_object() && t["Scene"]["Cameras"].contains("Camera"))
        return &t["Scene"]["Cameras"]["Camera"];
    return nullptr;
}

// True when some camera of the scene takes more than one sample per pixel (NumSamples, a
// string such as "100" or a number; XML's <NumSamples> under <Camera>): a Monte Carlo
// render, compared by its block means. False when the scene cannot be read.
bool monte_carlo(const SceneTree& s) {
    const nlohmann::ordered_json* cams = cameras(s);
    if (!cams) return false;
    for (const auto& c : cams->is_array() ? *cams : nlohmann::ordered_json::array({*cams})) {
        if (!c.is_object() || !c.contains("NumSamples")) continue;
        const auto& n = c["NumSamples"];
        if (n.is_number() && n.get<double>() > 1) return true;
        if (!n.is_string()) continue;
        const std::string text = trim(n.get<std::string>());
        char* end = nullptr;
        const double v = std::strtod(text.c_str(), &end);
        if (!text.empty() && *end == '\0' && v > 1) return true;
    }
    return false;
}

// The 1-based camera of `scene` (read as `s`) that writes `image`, for --trace --camera;
// nullopt for the first (or only) one, and after a warning when the scene does not tell.
std::optional<long> camera_of(const std::string& scene, const SceneTree& s, const std::string& image) {
    const auto warn = [&](const std::string& why) {
        std::fflush(stdout);
        std::fprintf(stderr, "warning: %s: %s; the trace command is for its first camera\n", scene.c_str(),
                     why.c_str());
        return std::nullopt;
    };
    if (!s.tree) return warn(s.why);
    const nlohmann::ordered_json* cams = cameras(s);
    if (!cams) return warn("no /Scene/Cameras/Camera");
    if (!cams->is_array()) return std::nullopt;
    const std::string want = fs::path(image).filename().string();
    for (size_t i = 0; i < cams->size(); ++i) {
        const auto& c = (*cams)[i];
        if (c.is_object() && c.contains("ImageName") && c["ImageName"].is_string() &&
            fs::path(c["ImageName"].get<std::string>()).filename().string() == want)
            return i == 0 ? std::nullopt : std::optional<long>(long(i) + 1);
    }
    return warn("no camera writes " + image);
}

// What became of one entry.
struct Result {
    Entry e;
    std::string verdict;  // pass, FAIL, missing, ambiguous, error, skipped
    std::string note;     // not compared: why
    std::string found;    // the render, relative to the renders' folder
    rt::ImageComparison c;
    std::vector<rt::PixelDiff> worst;
    std::string trace;  // the command that traces the worst pixel
    // A Monte Carlo scene (--mc, or NumSamples > 1): its block comparison, why it is no
    // pass, and --noise-dir's figures of the render against its other seed, or why none.
    bool mc = false;
    rt::BlockComparison m;
    std::string failure;
    std::optional<rt::BlockComparison> noise;
    std::string noise_note;
    bool compared() const { return note.empty(); }
    // Worst first: failures, then passes, then skipped scenes.
    int rank() const { return verdict == "skipped" ? 2 : verdict == "pass" ? 1 : 0; }
};

// The files of `files` under `dir` that are image `image`, as one: its path, or empty and
// `note` saying why ("not in DIR or its subfolders", or the files found when more than one).
std::string find_one(const std::set<std::string>& files, const std::string& image, const std::string& dir,
                     std::string& note) {
    const std::vector<std::string> found = matches(files, image);
    if (found.size() == 1) return found.front();
    if (found.empty()) {
        note = "not in " + dir + " or its subfolders";
        return "";
    }
    note = std::to_string(found.size()) + " files under " + dir + ":";
    for (size_t i = 0; i < found.size() && i < kAmbiguousNames; ++i) note += (i ? ", " : " ") + found[i];
    if (found.size() > kAmbiguousNames) note += ", ...";
    return "";
}

// Compares entry `e`'s image, found under `out_dir` (`files`), with its reference: by block
// means when `mc`, its other seed's found under --noise-dir (`noise_files`).
Result compare_entry(const Entry& e, const std::string& out_dir, const std::set<std::string>& files,
                     const std::set<std::string>& noise_files, const std::string& scene, const SceneTree& tree, bool mc,
                     const fs::path& shared, const Options& o, double pass_pct) {
    Result r;
    r.e = e;
    r.mc = mc;
    if (e.inputs.rfind("complete", 0) != 0) {
        r.verdict = "skipped";
        r.note = e.inputs;
        return r;
    }
    r.found = find_one(files, e.image, out_dir, r.note);
    if (r.found.empty()) {
        r.verdict = matches(files, e.image).empty() ? "missing" : "ambiguous";
        if (r.verdict == "missing") r.note += " (render " + scene + ")";
        return r;
    }
    try {
        const rt::Image a = rt::read_image((fs::path(out_dir) / r.found).string());
        const rt::Image b = rt::read_image((shared / e.reference).lexically_normal().string());
        r.c = rt::compare_images(a, b, o.tolerance);
        if (!r.c.same_size) {
            r.verdict = "error";
            r.note = "sizes differ: " + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " vs the reference's " + std::to_string(b.width) + "x" + std::to_string(b.height);
            return r;
        }
        if (mc) {
            r.m = compare_mc(a, b, o);
            r.failure = mc_failure(r.m, o);
            r.verdict = r.failure.empty() ? "pass" : "FAIL";
            if (!o.noise_dir.empty()) {
                const std::string other = find_one(noise_files, e.image, o.noise_dir, r.noise_note);
                if (!other.empty())
                    r.noise = compare_noise(a, (fs::path(o.noise_dir) / other).string(), o, r.noise_note);
            }
            if (!o.heatmap.empty() || !o.html.empty())
                write_heatmaps(rt::block_heatmap_with_legend(a, r.m), e.image, o);
            return r;
        }
        r.verdict = r.c.pct_over > pass_pct ? "FAIL" : "pass";
        r.worst = rt::worst_pixels(a, b, 1);
        if (!r.worst.empty()) r.trace = trace_command(r.worst.front(), scene, camera_of(scene, tree, e.image));
        if (!o.heatmap.empty() || !o.html.empty()) write_heatmaps(rt::heatmap_with_legend(a, b, r.c), e.image, o);
    } catch (const rt::InputError& ex) {
        r.verdict = "error";
        r.note = ex.what();
    }
    return r;
}

void write_page(const std::string& out_dir, const std::string& manifest, const fs::path& shared, const Options& o,
                const std::vector<Result>& results) {
    std::vector<rt::DiffPageRow> page;
    for (const Result& r : results) {
        rt::DiffPageRow p{r.e.image, r.c, r.note, r.worst, "", "", ""};
        if (!r.found.empty()) p.a_link = relative_to((fs::path(out_dir) / r.found).string(), o.html);
        const fs::path ref = shared / r.e.reference;
        std::error_code ec;
        if (fs::exists(ref, ec)) p.b_link = relative_to(ref.string(), o.html);
        if (r.compared()) p.heatmap_link = page_heatmap(r.e.image);
        p.verdict = r.verdict;
        p.failed = r.rank() == 0;
        p.skipped = r.verdict == "skipped";
        page.push_back(p);
    }
    rt::write_file_atomic((fs::path(o.html) / "index.html").string(),
                          rt::diff_page_html(out_dir, "references of " + manifest, o.tolerance, page, {}, {}));
}

}  // namespace

int compare_manifest(const std::string& out_dir, const Options& o) {
    std::error_code ec;
    if (!fs::is_directory(out_dir, ec)) throw rt::InputError(out_dir + ": not a folder");
    std::vector<std::string> errors;
    const std::vector<Entry> entries = read_manifest(o.manifest, errors);
    if (!errors.empty()) {
        for (const std::string& e : errors) rt::cli::print_error(e);
        return 1;
    }
    // The manifest's folder is shared/scenes/hwN: the references are two folders up.
    fs::path manifest_dir = fs::path(o.manifest).parent_path();
    if (manifest_dir.empty()) manifest_dir = ".";
    const fs::path shared = (manifest_dir / ".." / "..").lexically_normal();
    const double pass_pct = o.fail_above ? *o.fail_above : kPassPct;
    const std::set<std::string> files = image_files(out_dir, o);
    const std::set<std::string> noise_files =
        o.noise_dir.empty() ? std::set<std::string>() : image_files(o.noise_dir, o);
    if (!o.html.empty()) create_folder((fs::path(o.html) / "heatmaps").string());
    std::vector<Result> results;
    for (const Entry& e : entries) {
        const std::string scene = (manifest_dir / e.scene).lexically_normal().string();
        const SceneTree tree = read_scene(scene);
        results.push_back(
            compare_entry(e, out_dir, files, noise_files, scene, tree, o.mc || monte_carlo(tree), shared, o, pass_pct));
    }
    // The scenes compared pixel by pixel, then the Monte Carlo ones; each worst first.
    std::stable_sort(results.begin(), results.end(), [](const Result& x, const Result& y) {
        if (x.mc != y.mc) return y.mc;
        if (x.rank() != y.rank()) return x.rank() < y.rank();
        if (x.mc) {
            if (x.m.pct_off != y.m.pct_off) return x.m.pct_off > y.m.pct_off;
            return x.m.max_channel_bias() > y.m.max_channel_bias();
        }
        if (x.c.pct_over != y.c.pct_over) return x.c.pct_over > y.c.pct_over;
        return x.c.max_diff > y.c.max_diff;
    });

    size_t width = 5;
    for (const Result& r : results) width = std::max(width, r.e.image.size());
    const int w = int(width);
    std::map<std::string, size_t> counts;
    size_t pixel_rows = 0;
    for (size_t i = 0; i < results.size(); ++i) {
        const Result& r = results[i];
        ++counts[r.verdict];
        if (!r.mc) ++pixel_rows;
        if (i == 0 && !r.mc)
            std::printf("%-9s  %-*s  %9s  %4s  %10s  %9s\n", "verdict", w, "image", "size", "max", "% off", "PSNR");
        if (r.mc && (i == 0 || !results[i - 1].mc))
            std::printf("%-9s  %-*s  %9s  %s\n", "verdict", w, "image", "size", mc_headings(o).c_str());
        if (!r.compared()) {
            std::printf("%-9s  %-*s  %s\n", r.verdict.c_str(), w, r.e.image.c_str(), r.note.c_str());
            continue;
        }
        const std::string size = std::to_string(r.c.width) + "x" + std::to_string(r.c.height);
        if (r.mc)
            std::printf("%-9s  %-*s  %9s  %s\n", r.verdict.c_str(), w, r.e.image.c_str(), size.c_str(),
                        mc_figures(r.m).c_str());
        else
            std::printf("%-9s  %-*s  %9s  %4d  %10.4f  %9s\n", r.verdict.c_str(), w, r.e.image.c_str(), size.c_str(),
                        r.c.max_diff, r.c.pct_over, rt::psnr_text(r.c.psnr).c_str());
        if (r.noise)
            std::printf("%-*s  %9s  %s\n", w + 11, "  vs other seed", "", mc_figures(*r.noise).c_str());
        else if (r.mc && !o.noise_dir.empty())
            std::printf("  vs other seed: %s\n", r.noise_note.c_str());
        if (r.e.inputs != "complete") std::printf("  manifest: %s\n", r.e.inputs.c_str());  // its note
        if (!r.worst.empty())
            std::printf("  worst pixel %s\n  trace it: %s\n", rt::pixel_text(r.worst.front()).c_str(), r.trace.c_str());
        if (!r.failure.empty()) std::printf("  fails: %s\n", r.failure.c_str());
    }
    const size_t failed = results.size() - counts["pass"] - counts["skipped"];
    std::printf(
        "%zu scenes: %zu pass, %zu FAIL, %zu missing, %zu ambiguous, %zu error, %zu skipped (inputs incomplete)",
        results.size(), counts["pass"], counts["FAIL"], counts["missing"], counts["ambiguous"], counts["error"],
        counts["skipped"]);
    if (pixel_rows > 0)
        std::printf("; a pass has at most %g%% of its pixels off by more than %d", pass_pct, o.tolerance);
    if (pixel_rows < results.size())
        std::printf("%s %s", pixel_rows > 0 ? "; a Monte Carlo scene's pass has" : "; a pass has",
                    mc_criterion(o).c_str());
    std::printf("\n");
    if (!o.html.empty()) write_page(out_dir, o.manifest, shared, o, results);
    if (counts["pass"] + failed == 0) {
        // Every scene skipped: nothing was compared, which a check must not pass.
        std::fflush(stdout);
        rt::cli::print_error(o.manifest + ": no scene with complete inputs");
        return 1;
    }
    return failed > 0 ? 1 : 0;
}

}  // namespace rtdiff
