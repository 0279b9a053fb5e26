// The heatmap of where two images differ and its legend strip (rt/image/image_diff.h): one
// colour rule for both, so the legend shows exactly the colours the heatmap uses.
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "rt/image/bitmap_font.h"
#include "rt/image/image_diff.h"

namespace rt {
namespace {

// Levels over the tolerance at which the ramp reaches red.
constexpr int kRampLevels = 64;

const uint8_t kPaper[3] = {255, 255, 255};
const uint8_t kInk[3] = {0, 0, 0};
const uint8_t kWithin[3] = {0, 0, 160};  // within the tolerance
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
        uint8_t* out = &h.rgb[p];
        if (d == 0) {
            // Rec. 601 luma of a, dimmed: context only.
            const int luma = (299 * a.rgb[p] + 587 * a.rgb[p + 1] + 114 * a.rgb[p + 2]) / 1000;
            out[0] = out[1] = out[2] = uint8_t(luma / 4);
        } else if (d <= tolerance) {
            std::copy(kWithin, kWithin + 3, out);
        } else {
            over_colour(d - tolerance, out);
        }
    }
    return h;
}

// The strip, top to bottom: a caption (largest difference, tolerance); a bar of swatches
// (equal, within the tolerance when it is not 0) and the yellow-to-red ramp, with a mark
// above it at max_diff; the levels under each; what each colour means. All sizes are in
// units of `s`, the text's scale: 1 up to 639 pixels wide, 2 up to 959, then 3.
Image add_heatmap_legend(const Image& heat, int tolerance, int max_diff) {
    const int width = std::max(heat.width, kHeatmapLegendMinWidth);
    const int s = std::clamp(width / 320, 1, 3);
    const int pad = 4 * s, line = kGlyphHeight * s;
    const int caption_y = heat.height + pad;
    const int bar_y = caption_y + line + 5 * s, bar_h = 10 * s;
    const int levels_y = bar_y + bar_h + 4 * s;
    const int key_y = levels_y + line + 4 * s;
    Image out;
    out.width = width;
    out.height = key_y + line + pad;
    out.rgb.assign(size_t(out.width) * size_t(out.height) * 3, kPaper[0]);
    for (int y = 0; y < heat.height; ++y)
        std::copy_n(&heat.rgb[size_t(y) * size_t(heat.width) * 3], size_t(heat.width) * 3,
                    &out.rgb[size_t(y) * size_t(width) * 3]);

    draw_text(out, pad, caption_y,
              "MAX CHANNEL DIFF " + std::to_string(max_diff) + ", TOLERANCE " + std::to_string(tolerance), s, kInk);

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
    return out;
}

}  // namespace rt
