// Comparing two 8-bit RGB images: the figures ./rtdiff prints and the conformance tests
// assert (issue 15), so both measure alike; and a heatmap of where they differ.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "rt/image/image.h"

namespace rt {

// The comparison of image A with image B at a tolerance (in levels).
struct ImageComparison {
    bool same_size = true;      // false: the figures below say "totally different"
    int width = 0, height = 0;  // A's size
    int tolerance = 1;
    int max_diff = 0;        // largest absolute difference of any channel, in levels (256: sizes differ)
    double mean_diff = 0;    // mean absolute difference over all channel values
    size_t pixels = 0;       // width * height
    size_t pixels_over = 0;  // pixels with some channel off by more than `tolerance`
    double pct_over = 0;     // pixels_over as a percentage of pixels
    double psnr = 0;         // over all channels, dB; +inf when identical
    // The smallest rectangle holding every pixel counted in pixels_over, inclusive
    // bounds (column x from the left, row y from the top); empty when none is.
    int box_x0 = 0, box_y0 = 0, box_x1 = -1, box_y1 = -1;
    bool box_empty() const { return box_x1 < box_x0; }
};

// Per-channel comparison of `a` and `b`. Images of different sizes (or malformed ones,
// rgb not width * height * 3 bytes) compare as totally different: same_size false,
// max_diff 256, mean_diff 255, pct_over 100, psnr 0, box the whole of `a`.
ImageComparison compare_images(const Image& a, const Image& b, int tolerance = 1);

// One pixel where `a` and `b` differ: where (column x from the left, row y from the top,
// 0-based, as `raytracer --trace X,Y` takes them), by how much and both values.
struct PixelDiff {
    int x = 0, y = 0;
    int diff = 0;  // the largest channel difference, in levels
    uint8_t a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
};

// The `count` pixels of same-size images that differ most (by their largest channel
// difference), largest first, ties in reading order (row, then column); only pixels that
// differ at all, so fewer when fewer do. Empty when the sizes differ.
std::vector<PixelDiff> worst_pixels(const Image& a, const Image& b, size_t count = 5);

// "216,216 off by 91: A 111 111 111, B 20 0 0".
std::string pixel_text(const PixelDiff& p);

// An image of a's size showing where and how much `a` and `b` differ, per pixel by the
// largest channel difference d: equal pixels are a's luminance dimmed to a quarter (to
// show where one is), d within the tolerance dark blue, d above it yellow (just over)
// to red (64 levels or more over). Requires same-size images (compare_images().same_size).
Image diff_heatmap(const Image& a, const Image& b, int tolerance = 1);

// Draws a cyan ring around each small spot of off pixels of `heat` (diff_heatmap's image of
// `a` and `b`), so that a single off pixel stays visible on a page that shows the heatmap
// scaled down: around each 8-connected group of pixels over the tolerance whose box is
// smaller than max(3, L / 160) pixels each way, a ring of radius max(6, L / 50) (more by half
// the box) and thickness max(1, L / 200), L the image's larger side, unless more than 8 off
// pixels in all lie within two ring radii of it (a crowd of rings would hide the colours).
// The rings cover equal and within-tolerance pixels only, never an off pixel. Returns the
// number of rings.
size_t ring_small_spots(Image& heat, const Image& a, const Image& b, int tolerance);

// The narrowest heatmap with a legend: a narrower heatmap is padded on the right to this
// width, so that the legend's text stays readable at its smallest size.
constexpr int kHeatmapLegendMinWidth = 256;

// `heat` (diff_heatmap's image) with a legend strip below it, as rtdiff writes heatmaps:
// the largest difference and the tolerance, the colours as swatches and a ramp labelled in
// levels (0; 1 to the tolerance; just over it to 64 over), a mark at `max_diff`, what
// each colour means and what a ring (ring_small_spots) means. `heat` is kept unchanged at the top left; the image is
// max(heat.width, kHeatmapLegendMinWidth) wide, and white outside `heat` but for the legend.
// `block` > 0: the legend of block_heatmap's image of `block` x `block` blocks
// (rt/image/block_diff.h), its caption naming them, without the ring's line.
Image add_heatmap_legend(const Image& heat, int tolerance, int max_diff, int block = 0);

// The heatmap as rtdiff writes it: diff_heatmap at c's tolerance, its small spots ringed,
// and the legend for c's largest difference. `c` is compare_images(a, b, tolerance).
Image heatmap_with_legend(const Image& a, const Image& b, const ImageComparison& c);

// "39.18 dB", or "inf" for identical images.
std::string psnr_text(double psnr);
// "x 0..799 y 0..798" (ImageComparison's box), or "none".
std::string box_text(const ImageComparison& c);

// One pair of images of a comparison, as the --html page shows it. The links are relative
// to the page (URL-encoded by diff_page_html); empty when there is no such file.
struct DiffPageRow {
    std::string name;
    ImageComparison c;
    std::string error;             // not empty: the pair could not be compared (sizes, unreadable)
    std::vector<PixelDiff> worst;  // worst_pixels of the pair
    std::string a_link, b_link, heatmap_link;
    std::string verdict = "";  // rtdiff --manifest: "pass", "FAIL", "missing", ..., a column of its own
    bool failed = false;       // marked as failed on the page (rows with an error always are)
    bool skipped = false;      // not compared and no failure (a manifest's scene with incomplete inputs)
};

// The HTML page of a comparison (rtdiff --html; two images are one row): a table of every
// row in the order given (rtdiff: worst first; a verdict column when some row has one),
// then the images found in one folder only,
// then per row its worst pixels and the two images and the heatmap side by side.
// `a_label`, `b_label`: the folders (or the images).
std::string diff_page_html(const std::string& a_label, const std::string& b_label, int tolerance,
                           const std::vector<DiffPageRow>& rows, const std::vector<std::string>& only_a,
                           const std::vector<std::string>& only_b);

// Reads a PNG or PPM (anything stb_image reads) as 8-bit RGB. Throws rt::InputError
// "<path>: <what>" when it cannot (no such file, a folder, not an image).
Image read_image(const std::string& path);

}  // namespace rt
