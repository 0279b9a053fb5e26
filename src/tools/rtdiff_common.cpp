// What rtdiff's modes share (rtdiff.h): the trace command, heatmap files and pages, folder walks.
#include <filesystem>
#include <fstream>
#include <system_error>

#include "rt/core/error.h"
#include "rt/io/atomic_file.h"
#include "rtdiff.h"

namespace fs = std::filesystem;

namespace rtdiff {

std::string shell_word(const std::string& s) {
    const bool plain = !s.empty() && s.find_first_not_of(
                                         "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz"
                                         "0123456789_./+,=:@%-") == std::string::npos;
    if (plain) return s;
    std::string out = "'";
    for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

std::string trace_command(const rt::PixelDiff& p, const std::string& scene, std::optional<long> camera) {
    std::string cmd = "./raytracer --trace " + std::to_string(p.x) + "," + std::to_string(p.y);
    if (camera) cmd += " --camera " + std::to_string(*camera);
    return cmd + " " + (scene.empty() ? "<scene.json>" : shell_word(scene));
}

void create_folder(const std::string& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw rt::InputError(dir + ": cannot create the folder: " + ec.message());
}

std::string page_heatmap(const std::string& name) {
    return "heatmaps/" + fs::path(name).replace_extension(".png").generic_string();
}

std::string relative_to(const std::string& file, const std::string& dir) {
    return fs::weakly_canonical(file).lexically_relative(fs::weakly_canonical(dir)).generic_string();
}

bool over_limit(const rt::ImageComparison& c, const Options& o) { return o.fail_above && c.pct_over > *o.fail_above; }

void write_pair_outputs(const rt::Image& heat, const std::string& a_path, const std::string& b_path,
                        const rt::ImageComparison& c, const std::vector<rt::PixelDiff>& worst, const Options& o) {
    if (!o.heatmap.empty()) rt::write_png(heat, o.heatmap);
    if (o.html.empty()) return;
    const std::string name = fs::path(a_path).filename().string();
    create_folder((fs::path(o.html) / "heatmaps").string());
    rt::write_png(heat, (fs::path(o.html) / page_heatmap(name)).string());
    const rt::DiffPageRow row{
        name, c, "", worst, relative_to(a_path, o.html), relative_to(b_path, o.html), page_heatmap(name)};
    rt::write_file_atomic((fs::path(o.html) / "index.html").string(),
                          rt::diff_page_html(a_path, b_path, o.tolerance, {row}, {}, {}));
}

void write_heatmaps(const rt::Image& heat, const std::string& name, const Options& o) {
    const std::string file = fs::path(name).replace_extension(".png").string();
    if (!o.heatmap.empty()) {
        const fs::path out = fs::path(o.heatmap) / file;
        create_folder(out.parent_path().string());
        rt::write_png(heat, out.string());
    }
    if (!o.html.empty()) {
        const fs::path out = fs::path(o.html) / page_heatmap(name);
        create_folder(out.parent_path().string());
        rt::write_png(heat, out.string());
    }
}

namespace {

bool is_image_name(const fs::path& p) {
    const rt::ImageFormat f = rt::image_format_of(p.string());
    return f == rt::ImageFormat::Png || f == rt::ImageFormat::Ppm;
}

// True when `dir` is the folder `other` names (an existing one).
bool same_folder(const fs::path& dir, const std::string& other) {
    std::error_code ec;
    return !other.empty() && fs::equivalent(dir, other, ec) && !ec;
}

// True when folder `dir` holds a page rtdiff --html wrote (its index.html's title says so).
bool holds_rtdiff_page(const fs::path& dir) {
    std::ifstream page(dir / "index.html");
    std::string head(160, '\0');
    page.read(&head[0], std::streamsize(head.size()));
    return head.find("<title>rtdiff: ") != std::string::npos;
}

}  // namespace

std::set<std::string> image_files(const std::string& dir, const Options& o) {
    std::set<std::string> names;
    std::error_code ec;
    fs::recursive_directory_iterator it(dir, ec);
    for (; !ec && it != fs::recursive_directory_iterator(); it.increment(ec)) {
        std::error_code ec2;
        if (it->is_directory(ec2)) {
            // rtdiff's own output is no render: a later run must not find its heatmaps.
            if (same_folder(it->path(), o.html) || same_folder(it->path(), o.heatmap) || holds_rtdiff_page(it->path()))
                it.disable_recursion_pending();
        } else if (it->is_regular_file(ec2) && is_image_name(it->path())) {
            names.insert(it->path().lexically_relative(dir).generic_string());
        }
    }
    if (ec) throw rt::InputError(dir + ": cannot read the folder: " + ec.message());
    return names;
}

}  // namespace rtdiff
