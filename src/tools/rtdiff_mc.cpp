// rtdiff's Monte Carlo comparison (rtdiff.h, docs/rtdiff.md): the figures of block means,
// the pass criterion, and two images compared by it with the noise floor beside them.
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "rt/core/error.h"
#include "rtdiff.h"

namespace rtdiff {

namespace {

// `v` with a magnitude too small to print as 0.00 made 0, so that it prints "+0.00", not "-0.00".
double printable(double v) { return std::abs(v) < 0.005 ? 0.0 : v; }

std::string format(const char* f, double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, f, v);
    return buf;
}

// The first column of the pair mode's lines.
constexpr int kLabelWidth = 14;

rt::Image read_same_size(const std::string& path, const rt::Image& a, const std::string& a_path) {
    rt::Image img = rt::read_image(path);
    if (img.width != a.width || img.height != a.height)
        throw rt::InputError(path + ": " + std::to_string(img.width) + "x" + std::to_string(img.height) + ", but " +
                             a_path + " is " + std::to_string(a.width) + "x" + std::to_string(a.height));
    return img;
}

}  // namespace

rt::BlockComparison compare_mc(const rt::Image& a, const rt::Image& b, const Options& o) {
    return rt::compare_blocks(a, b, o.block, o.block_threshold);
}

std::string mc_failure(const rt::BlockComparison& c, const Options& o) {
    std::string why;
    if (c.pct_off > o.max_off_blocks)
        why = format("%.4f", c.pct_off) + "% of the blocks off by more than " + std::to_string(o.block_threshold) +
              " (at most " + format("%g", o.max_off_blocks) + "%)";
    const char* const names[3] = {"R", "G", "B"};
    std::string channels;
    for (size_t ch = 0; ch < 3; ++ch)
        if (std::abs(c.mean_diff[ch]) > o.max_mean_diff)
            channels += std::string(channels.empty() ? "" : ", ") + names[ch] + " " + format("%+.2f", c.mean_diff[ch]);
    if (!channels.empty())
        why += std::string(why.empty() ? "" : "; ") + "mean difference over " + format("%g", o.max_mean_diff) +
               " level" + (o.max_mean_diff == 1 ? "" : "s") + ": " + channels;
    return why;
}

std::string mc_criterion(const Options& o) {
    const std::string side = std::to_string(o.block);
    return "at most " + format("%g", o.max_off_blocks) + "% of the " + side + "x" + side + " blocks off by more than " +
           std::to_string(o.block_threshold) + " levels and every channel's mean difference within " +
           format("%g", o.max_mean_diff) + " level" + (o.max_mean_diff == 1 ? "" : "s");
}

std::string mc_headings(const Options& o) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%12s  %9s %6s %6s %6s  %8s  %9s",
                  ("% blocks >" + std::to_string(o.block_threshold)).c_str(), "A-B: R", "G", "B", "all", "RMSE",
                  "PSNR");
    return buf;
}

std::string mc_figures(const rt::BlockComparison& c) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%12.4f  %+9.2f %+6.2f %+6.2f %+6.2f  %8.2f  %9s", c.pct_off,
                  printable(c.mean_diff[0]), printable(c.mean_diff[1]), printable(c.mean_diff[2]),
                  printable(c.mean_diff_all), c.rmse, rt::psnr_text(c.psnr).c_str());
    return buf;
}

std::optional<rt::BlockComparison> compare_noise(const rt::Image& a, const std::string& other_path, const Options& o,
                                                 std::string& note) {
    try {
        const rt::Image other = rt::read_image(other_path);
        if (other.width == a.width && other.height == a.height) return compare_mc(a, other, o);
        note = other_path + ": " + std::to_string(other.width) + "x" + std::to_string(other.height) + ", not " +
               std::to_string(a.width) + "x" + std::to_string(a.height);
    } catch (const rt::InputError& e) {
        note = e.what();
    }
    return std::nullopt;
}

int compare_files_mc(const std::string& a_path, const std::string& b_path, const Options& o) {
    const rt::Image a = rt::read_image(a_path);
    const rt::Image b = read_same_size(b_path, a, a_path);
    const rt::BlockComparison m = compare_mc(a, b, o);
    std::optional<rt::BlockComparison> noise;
    if (!o.noise.empty()) noise = compare_mc(a, read_same_size(o.noise, a, a_path), o);
    const bool partial = m.width % o.block != 0 || m.height % o.block != 0;
    std::printf("%s vs %s (reference)%s: same size, %dx%d, %zu blocks of %dx%d pixels%s\n", a_path.c_str(),
                b_path.c_str(), o.noise.empty() ? "" : (", other seed " + o.noise).c_str(), m.width, m.height, m.blocks,
                o.block, o.block, partial ? " (fewer at the right and bottom edges)" : "");
    std::printf("%-*s%s\n", kLabelWidth, "", mc_headings(o).c_str());
    std::printf("%-*s%s\n", kLabelWidth, "vs reference", mc_figures(m).c_str());
    if (noise) std::printf("%-*s%s\n", kLabelWidth, "vs other seed", mc_figures(*noise).c_str());
    const std::string why = mc_failure(m, o);
    if (why.empty())
        std::printf("pass: %s\n", mc_criterion(o).c_str());
    else
        std::printf("FAIL: %s\n", why.c_str());
    if (!o.heatmap.empty() || !o.html.empty()) {
        const rt::ImageComparison c = rt::compare_images(a, b, o.tolerance);
        write_pair_outputs(rt::block_heatmap_with_legend(a, m), a_path, b_path, c, {}, o);
    }
    return why.empty() ? 0 : 1;
}

}  // namespace rtdiff
