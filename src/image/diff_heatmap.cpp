// The heatmap of where two images differ, the rings around its small spots and its legend
// strip (rt/image/image_diff.h), and its form for blocks of a Monte Carlo comparison
// (rt/image/block_diff.h): one colour rule for all, so the legend shows exactly the colours
// the heatmap uses.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "rt/image/bitmap_font.h"
#include "rt/image/block_diff.h"
#include "rt/image/image_diff.h"

namespace rt {
namespace {

// Levels over the tolerance at which the ramp reaches red.
constexpr int kRampLevels = 64;

const uint8_t kPaper[3] = {255, 255, 255};
const uint8_t kInk[3] = {0, 0, 0};
const uint8_t kWithin[3] = {0, 0, 160};  // within the tolerance
const uint8_t kRing[3] = {0, 255, 255};  // around a small spot of off pixels
// A spot is ringed only where at most this many off pixels (its own included) lie within
// two ring radii: a crowd of spots would fill the heatmap with rings and hide its colours.
constexpr uint32_t kRingCrowd = 8;
// Equal pixels' swatch: one of the dimmed greys (a's luma / 4, 0..63) they show as.
const uint8_t kEqualSwatch[3] = {48, 48, 48};

// The colour of a difference `over` levels over the tolerance (1 or more): yellow at 1,
// red from kRampLevels on.
void over_colour(int over, uint8_t out[3]) {
    over = std::clamp(over, 1, kRampLevels);
    out[0] = 255;
    out[1] = uint8_t(255 - (over - 1) * 255 / (kRampLevels - 1));
    out[2] = 0;
}

// The colour of a pixel whose difference is `d` levels at `tolerance`; `a_px` is its value in
// image a, which an equal pixel shows as its Rec. 601 luma dimmed to a quarter (context only).
void heat_colour(const uint8_t* a_px, int d, int tolerance, uint8_t out[3]) {
    if (d == 0) {
        const int luma = (299 * a_px[0] + 587 * a_px[1] + 114 * a_px[2]) / 1000;
        out[0] = out[1] = out[2] = uint8_t(luma / 4);
    } else if (d <= tolerance) {
        std::copy(kWithin, kWithin + 3, out);
    } else {
        over_colour(d - tolerance, out);
    }
}

void set(Image& img, int x, int y, const uint8_t rgb[3]) {
    if (x < 0 || y < 0 || x >= img.width || y >= img.height) return;
    uint8_t* out = &img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3];
    out[0] = rgb[0];
    out[1] = rgb[1];
    out[2] = rgb[2];
}

void fill(Image& img, int x0, int y0, int w, int h, const uint8_t rgb[3]) {
    for (int y = y0; y < y0 + h; ++y)
        for (int x = x0; x < x0 + w; ++x) set(img, x, y, rgb);
}

// A `t`-pixel ink outline just outside the rectangle x0, y0, w, h.
void outline(Image& img, int x0, int y0, int w, int h, int t) {
    fill(img, x0 - t, y0 - t, w + 2 * t, t, kInk);
    fill(img, x0 - t, y0 + h, w + 2 * t, t, kInk);
    fill(img, x0 - t, y0, t, h, kInk);
    fill(img, x0 + w, y0, t, h, kInk);
}

// A ring of colour `rgb`, `t` pixels thick, of outer radius r around cx, cy; only over
// pixels where `keep` is 0 (when given: one byte per pixel of `img`).
void ring(Image& img, int cx, int cy, int r, int t, const uint8_t rgb[3], const std::vector<uint8_t>* keep = nullptr) {
    for (int y = cy - r; y <= cy + r; ++y)
        for (int x = cx - r; x <= cx + r; ++x) {
            const int d2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
            if (d2 > r * r || d2 <= (r - t) * (r - t) || x < 0 || y < 0 || x >= img.width || y >= img.height) continue;
            if (!keep || !(*keep)[size_t(y) * size_t(img.width) + size_t(x)]) set(img, x, y, rgb);
        }
}

// `text` centred on column cx.
void draw_centred(Image& img, int cx, int y, const std::string& text, int scale) {
    draw_text(img, cx - text_width(text, scale) / 2, y, text, scale, kInk);
}

}  // namespace

Image diff_heatmap(const Image& a, const Image& b, int tolerance) {
    Image h;
    if (!compare_images(a, b, tolerance).same_size) return h;
    h.width = a.width;
    h.height = a.height;
    h.rgb.resize(a.rgb.size());
    for (size_t p = 0; p < a.rgb.size(); p += 3) {
        int d = 0;
        for (size_t c = 0; c < 3; ++c) d = std::max(d, std::abs(int(a.rgb[p + c]) - int(b.rgb[p + c])));
        heat_colour(&a.rgb[p], d, tolerance, &h.rgb[p]);
    }
    return h;
}

Image block_heatmap(const Image& a, const BlockComparison& c) {
    Image h;
    if (!c.same_size || a.width != c.width || a.height != c.height || c.block_diff.size() != c.blocks) return h;
    h.width = a.width;
    h.height = a.height;
    h.rgb.resize(a.rgb.size());
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < a.width; ++x) {
            const size_t p = (size_t(y) * size_t(a.width) + size_t(x)) * 3;
            const int d = c.block_diff[size_t(y / c.block) * size_t(c.blocks_x) + size_t(x / c.block)];
            heat_colour(&a.rgb[p], d, c.threshold, &h.rgb[p]);
        }
    return h;
}

size_t ring_small_spots(Image& heat, const Image& a, const Image& b, int tolerance) {
    if (!compare_images(a, b, tolerance).same_size || heat.width != a.width || heat.height != a.height) return 0;
    const int w = a.width;
    std::vector<uint8_t> off(size_t(w) * size_t(a.height));
    for (size_t i = 0; i < off.size(); ++i)
        for (size_t c = 0; c < 3; ++c)
            if (std::abs(int(a.rgb[3 * i + c]) - int(b.rgb[3 * i + c])) > tolerance) off[i] = 1;
    // Sizes grow with the image, as the factor by which a page scales it down does.
    const int extent = std::max(w, a.height);
    const int small = std::max(3, extent / 160), radius = std::max(6, extent / 50), thick = std::max(1, extent / 200);
    // Off pixels counted over rectangles through a summed-area table.
    const size_t stride = size_t(w) + 1;
    std::vector<uint32_t> sum(stride * (size_t(a.height) + 1));
    for (int y = 0; y < a.height; ++y)
        for (int x = 0; x < w; ++x)
            sum[(size_t(y) + 1) * stride + size_t(x) + 1] =
                off[size_t(y) * size_t(w) + size_t(x)] + sum[size_t(y) * stride + size_t(x) + 1] +
                sum[(size_t(y) + 1) * stride + size_t(x)] - sum[size_t(y) * stride + size_t(x)];
    const auto off_within = [&](int cx, int cy, int r) {
        const size_t x0 = size_t(std::max(cx - r, 0)), x1 = size_t(std::min(cx + r, w - 1)) + 1;
        const size_t y0 = size_t(std::max(cy - r, 0)), y1 = size_t(std::min(cy + r, a.height - 1)) + 1;
        return sum[y1 * stride + x1] - sum[y0 * stride + x1] - sum[y1 * stride + x0] + sum[y0 * stride + x0];
    };
    // The 8-connected spots of off pixels, each by its box, found by flood fill.
    std::vector<uint8_t> seen(off.size());
    std::vector<size_t> todo;
    size_t rings = 0;
    for (size_t start = 0; start < off.size(); ++start) {
        if (!off[start] || seen[start]) continue;
        int x0 = int(start % size_t(w)), x1 = x0, y0 = int(start / size_t(w)), y1 = y0;
        seen[start] = 1;
        todo.assign(1, start);
        while (!todo.empty()) {
            const size_t i = todo.back();
            todo.pop_back();
            const int x = int(i % size_t(w)), y = int(i / size_t(w));
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
            for (int ny = std::max(y - 1, 0); ny <= std::min(y + 1, a.height - 1); ++ny)
                for (int nx = std::max(x - 1, 0); nx <= std::min(x + 1, w - 1); ++nx) {
                    const size_t n = size_t(ny) * size_t(w) + size_t(nx);
                    if (off[n] && !seen[n]) {
                        seen[n] = 1;
                        todo.push_back(n);
                    }
                }
        }
        if (x1 - x0 >= small || y1 - y0 >= small) continue;  // large enough to be seen
        const int cx = (x0 + x1) / 2, cy = (y0 + y1) / 2, r = radius + std::max(x1 - x0, y1 - y0) / 2;
        if (off_within(cx, cy, 2 * r) > kRingCrowd) continue;
        ring(heat, cx, cy, r, thick, kRing, &off);
        ++rings;
    }
    return rings;
}

// The strip, top to bottom: a caption (largest difference, tolerance); a bar of swatches
// (equal, within the tolerance when it is not 0) and the yellow-to-red ramp, with a mark
// above it at max_diff; the levels under each; what each colour means; what a ring means
// (not for blocks, which are not ringed). All sizes are in units of `s`, the text's scale: 1
// up to 639 pixels wide, 2 up to 959, then 3.
Image add_heatmap_legend(const Image& heat, int tolerance, int max_diff, int block) {
    const int width = std::max(heat.width, kHeatmapLegendMinWidth);
    const int s = std::clamp(width / 320, 1, 3);
    const int pad = 4 * s, line = kGlyphHeight * s;
    const int caption_y = heat.height + pad;
    const int bar_y = caption_y + line + 5 * s, bar_h = 10 * s;
    const int levels_y = bar_y + bar_h + 4 * s;
    const int key_y = levels_y + line + 4 * s;
    const int ring_y = key_y + line + 3 * s;
    Image out;
    out.width = width;
    out.height = (block > 0 ? key_y : ring_y) + line + pad;
    out.rgb.assign(size_t(out.width) * size_t(out.height) * 3, kPaper[0]);
    for (int y = 0; y < heat.height; ++y)
        std::copy_n(&heat.rgb[size_t(y) * size_t(heat.width) * 3], size_t(heat.width) * 3,
                    &out.rgb[size_t(y) * size_t(width) * 3]);

    const std::string caption =
        block > 0 ? std::to_string(block) + "X" + std::to_string(block) + " BLOCK MEANS: MAX DIFF " +
                        std::to_string(max_diff) + ", TOL " + std::to_string(tolerance)
                  : "MAX CHANNEL DIFF " + std::to_string(max_diff) + ", TOLERANCE " + std::to_string(tolerance);
    draw_text(out, pad, caption_y, caption, s, kInk);

    // The bar: equal swatch, within-tolerance swatch, ramp; each outlined.
    const int gap = 6 * s, equal_w = 20 * s, within_w = tolerance > 0 ? 36 * s : 0;
    const int equal_x = pad, within_x = equal_x + equal_w + gap;
    const int ramp_x = within_x + (within_w > 0 ? within_w + gap : 0);
    const int ramp_w = width - pad - ramp_x;
    fill(out, equal_x, bar_y, equal_w, bar_h, kEqualSwatch);
    outline(out, equal_x, bar_y, equal_w, bar_h, 1);
    draw_centred(out, equal_x + equal_w / 2, levels_y, "0", s);
    if (within_w > 0) {
        fill(out, within_x, bar_y, within_w, bar_h, kWithin);
        outline(out, within_x, bar_y, within_w, bar_h, 1);
        draw_centred(out, within_x + within_w / 2, levels_y, tolerance == 1 ? "1" : "1-" + std::to_string(tolerance),
                     s);
    }
    for (int i = 0; i < ramp_w; ++i) {
        uint8_t c[3];
        over_colour(1 + i * (kRampLevels - 1) / std::max(ramp_w - 1, 1), c);
        fill(out, ramp_x + i, bar_y, 1, bar_h, c);
    }
    outline(out, ramp_x, bar_y, ramp_w, bar_h, 1);
    draw_text(out, ramp_x, levels_y, std::to_string(tolerance + 1), s, kInk);
    const std::string top = std::to_string(tolerance + kRampLevels) + "+";
    draw_text(out, ramp_x + ramp_w - text_width(top, s), levels_y, top, s, kInk);

    // The mark: a triangle pointing down at max_diff's place in the bar.
    int mark_x = equal_x + equal_w / 2;
    if (max_diff > tolerance)
        mark_x = ramp_x + (std::min(max_diff - tolerance, kRampLevels) - 1) * (ramp_w - 1) / (kRampLevels - 1);
    else if (max_diff > 0)
        mark_x = within_x + within_w / 2;
    const int mark_h = 4 * s;
    mark_x = std::clamp(mark_x, mark_h, width - mark_h);  // the whole triangle in the image
    for (int r = 0; r < mark_h; ++r) {
        const int half = mark_h - 1 - r;
        fill(out, mark_x - half, bar_y - 1 - mark_h + r, 2 * half + 1, 1, kInk);
    }

    draw_text(out, pad, key_y,
              tolerance > 0 ? "GREY EQUAL, BLUE <= TOL, YELLOW-RED OVER" : "GREY EQUAL, YELLOW-RED OVER", s, kInk);
    if (block > 0) return out;
    // A ring as ring_small_spots draws one, and its meaning.
    const int icon_r = (line + 1) / 2;
    ring(out, pad + icon_r, ring_y + line / 2, icon_r, s, kRing);
    draw_text(out, pad + 2 * icon_r + 3 * s, ring_y, "RING: A SMALL SPOT OF OFF PIXELS", s, kInk);
    return out;
}

Image heatmap_with_legend(const Image& a, const Image& b, const ImageComparison& c) {
    Image heat = diff_heatmap(a, b, c.tolerance);
    ring_small_spots(heat, a, b, c.tolerance);
    return add_heatmap_legend(heat, c.tolerance, c.max_diff);
}

Image block_heatmap_with_legend(const Image& a, const BlockComparison& c) {
    return add_heatmap_legend(block_heatmap(a, c), c.threshold, c.max_block_diff, c.block);
}

}  // namespace rt
