// The image comparison of rt/image/image_diff.h on hand-made images with known differences,
// and ./rtdiff on them: figures, worst pixels, the heatmap, its rings and its legend, exit
// statuses, --fail-above, folders, --html, bad input (subfolders and --manifest:
// test_rtdiff_manifest.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rt/core/error.h"
#include "rt/image/bitmap_font.h"
#include "rt/image/image.h"
#include "rt/image/image_diff.h"
#include "rtdiff_test_support.h"
#include "test_support.h"

using namespace rtdiff_test;

namespace {

// A 10x8 gradient `a` and a copy `b` with seven pixels off by known amounts. By largest
// channel difference: 8,6 by 30 (A 94 95 96, B 94 65 96); 2,3 and 1,5 by 9; 6,1 by 5
// (another channel by 3); 5,4 and 3,7 by 2; 7,0 by 1.
void known_pair(rt::Image& a, rt::Image& b) {
    a = gradient(10, 8);
    b = a;
    at(b, 8, 6, 1) -= 30;
    at(b, 2, 3, 2) += 9;
    at(b, 1, 5, 0) += 9;
    at(b, 6, 1, 0) += 5;
    at(b, 6, 1, 2) -= 3;
    at(b, 5, 4, 1) += 2;
    at(b, 3, 7, 0) -= 2;
    at(b, 7, 0, 1) += 1;
}

// The number of pixels of `img` in rows y0 to y1 (excluded; -1: to the bottom) with
// exactly colour r, g, b.
size_t count_colour(const rt::Image& img, int y0, uint8_t r, uint8_t g, uint8_t b, int y1 = -1) {
    size_t n = 0;
    for (int y = y0; y < (y1 < 0 ? img.height : y1); ++y)
        for (int x = 0; x < img.width; ++x)
            if (px(img, x, y, 0) == r && px(img, x, y, 1) == g && px(img, x, y, 2) == b) ++n;
    return n;
}

// True when the top left heat.width x heat.height of `img` is `heat`.
bool starts_with_image(const rt::Image& img, const rt::Image& heat) {
    if (img.width < heat.width || img.height < heat.height) return false;
    for (int y = 0; y < heat.height; ++y)
        for (int x = 0; x < heat.width; ++x)
            for (int c = 0; c < 3; ++c)
                if (px(img, x, y, c) != px(heat, x, y, c)) return false;
    return true;
}

}  // namespace

TEST(ImageDiff, IdenticalImagesDifferNowhere) {
    const rt::Image a = gradient(7, 5);
    const rt::ImageComparison c = rt::compare_images(a, a);
    EXPECT_TRUE(c.same_size);
    EXPECT_EQ(c.max_diff, 0);
    EXPECT_EQ(c.mean_diff, 0);
    EXPECT_EQ(c.pixels, 35u);
    EXPECT_EQ(c.pixels_over, 0u);
    EXPECT_EQ(c.pct_over, 0);
    EXPECT_TRUE(std::isinf(c.psnr) && c.psnr > 0);
    EXPECT_TRUE(c.box_empty());
}

TEST(ImageDiff, OnePixelOffByTwo) {
    const rt::Image a = gradient(7, 5);
    rt::Image b = a;
    at(b, 4, 2, 1) += 2;
    const rt::ImageComparison c = rt::compare_images(a, b);
    EXPECT_EQ(c.max_diff, 2);
    EXPECT_EQ(c.pixels_over, 1u);
    EXPECT_DOUBLE_EQ(c.pct_over, 100.0 / 35);
    EXPECT_DOUBLE_EQ(c.mean_diff, 2.0 / (35 * 3));
    EXPECT_DOUBLE_EQ(c.psnr, 10 * std::log10(255.0 * 255.0 / (4.0 / (35 * 3))));
    EXPECT_FALSE(c.box_empty());
    EXPECT_EQ(c.box_x0, 4);
    EXPECT_EQ(c.box_x1, 4);
    EXPECT_EQ(c.box_y0, 2);
    EXPECT_EQ(c.box_y1, 2);
    // At tolerance 2 the pixel is within it; the max and PSNR stay.
    const rt::ImageComparison c2 = rt::compare_images(a, b, 2);
    EXPECT_EQ(c2.pixels_over, 0u);
    EXPECT_TRUE(c2.box_empty());
    EXPECT_EQ(c2.max_diff, 2);
    // The tests' compare() is the same measure at tolerance 1.
    const ImageDiff d = compare(a, b);
    EXPECT_EQ(d.max_diff, c.max_diff);
    EXPECT_EQ(d.mean_diff, c.mean_diff);
    EXPECT_EQ(d.pct_over_1, c.pct_over);
    EXPECT_EQ(d.psnr, c.psnr);
}

TEST(ImageDiff, OffByOneIsWithinTheDefaultTolerance) {
    const rt::Image a = gradient(4, 4);
    rt::Image b = a;
    at(b, 0, 0, 0) -= 1;
    EXPECT_EQ(rt::compare_images(a, b).pixels_over, 0u);
    EXPECT_EQ(rt::compare_images(a, b, 0).pixels_over, 1u);
}

TEST(ImageDiff, BoundingBoxSpansEveryOffPixel) {
    const rt::Image a = gradient(10, 8);
    rt::Image b = a;
    at(b, 6, 1, 0) += 5;
    at(b, 2, 3, 2) += 9;
    at(b, 8, 6, 1) -= 30;
    const rt::ImageComparison c = rt::compare_images(a, b);
    EXPECT_EQ(c.pixels_over, 3u);
    EXPECT_EQ(c.max_diff, 30);
    EXPECT_EQ(c.box_x0, 2);
    EXPECT_EQ(c.box_x1, 8);
    EXPECT_EQ(c.box_y0, 1);
    EXPECT_EQ(c.box_y1, 6);
}

TEST(ImageDiff, DifferentSizesAreTotallyDifferent) {
    const rt::ImageComparison c = rt::compare_images(gradient(4, 4), gradient(4, 5));
    EXPECT_FALSE(c.same_size);
    EXPECT_EQ(c.max_diff, 256);
    EXPECT_EQ(c.pct_over, 100);
    EXPECT_EQ(c.psnr, 0);
    const ImageDiff d = compare(gradient(4, 4), gradient(5, 4));
    EXPECT_EQ(d.max_diff, 256);
    EXPECT_EQ(d.mean_diff, 255);
    EXPECT_EQ(d.pct_over_1, 100);
    EXPECT_EQ(d.psnr, 0);
}

TEST(ImageDiff, HeatmapMarksOnlyTheOffPixels) {
    const rt::Image a = gradient(6, 4);
    rt::Image b = a;
    at(b, 1, 1, 0) += 1;   // within the tolerance
    at(b, 3, 2, 2) += 10;  // over it
    const rt::Image h = rt::diff_heatmap(a, b);
    ASSERT_EQ(h.width, 6);
    ASSERT_EQ(h.height, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) {
            const uint8_t r = px(h, x, y, 0), g = px(h, x, y, 1), bl = px(h, x, y, 2);
            if (x == 3 && y == 2) {
                EXPECT_EQ(r, 255);
                EXPECT_EQ(bl, 0);
            } else if (x == 1 && y == 1) {
                EXPECT_EQ(r, 0);
                EXPECT_GT(bl, 0);
            } else {
                EXPECT_TRUE(r == g && g == bl && r < 64) << x << "," << y;  // dimmed grey
            }
        }
}

TEST(ImageDiff, WorstPixelsLargestFirstTiesInReadingOrder) {
    rt::Image a, b;
    known_pair(a, b);
    const std::vector<rt::PixelDiff> w = rt::worst_pixels(a, b);
    ASSERT_EQ(w.size(), 5u);
    const int expected[5][3] = {{8, 6, 30}, {2, 3, 9}, {1, 5, 9}, {6, 1, 5}, {5, 4, 2}};  // x, y, diff
    for (size_t i = 0; i < 5; ++i) {
        EXPECT_EQ(w[i].x, expected[i][0]) << i;
        EXPECT_EQ(w[i].y, expected[i][1]) << i;
        EXPECT_EQ(w[i].diff, expected[i][2]) << i;
        for (int c = 0; c < 3; ++c) {
            EXPECT_EQ(w[i].a[c], px(a, w[i].x, w[i].y, c)) << i;
            EXPECT_EQ(w[i].b[c], px(b, w[i].x, w[i].y, c)) << i;
        }
    }
    EXPECT_EQ(rt::pixel_text(w[0]), "8,6 off by 30: A 94 95 96, B 94 65 96");
    // All seven when asked for more; none for equal images or different sizes.
    const std::vector<rt::PixelDiff> all = rt::worst_pixels(a, b, 20);
    ASSERT_EQ(all.size(), 7u);
    EXPECT_EQ(all[5].x, 3);
    EXPECT_EQ(all[5].y, 7);
    EXPECT_EQ(all[6].diff, 1);
    EXPECT_TRUE(rt::worst_pixels(a, a).empty());
    EXPECT_TRUE(rt::worst_pixels(a, gradient(10, 9)).empty());
    EXPECT_TRUE(rt::worst_pixels(a, b, 0).empty());
}

TEST(ImageDiff, HeatmapLegendIsAStripBelowTheUnchangedDiffArea) {
    rt::Image a, b;
    known_pair(a, b);
    const rt::Image heat = rt::diff_heatmap(a, b);
    const rt::Image h = rt::add_heatmap_legend(heat, 1, 30);
    // A 10-pixel-wide heatmap is padded to the legend's least width, white beside it.
    EXPECT_EQ(h.width, rt::kHeatmapLegendMinWidth);
    EXPECT_GT(h.height, heat.height + 20);
    EXPECT_TRUE(starts_with_image(h, heat));
    EXPECT_EQ(count_colour(h, 0, 255, 255, 255) - count_colour(h, heat.height, 255, 255, 255),
              size_t(h.width - heat.width) * size_t(heat.height));
    // The strip: a caption (black text in its first rows, above the bar), the
    // within-tolerance swatch, the ramp from yellow to red.
    EXPECT_GT(count_colour(h, heat.height, 0, 0, 0, heat.height + 11), 100u);
    EXPECT_GT(count_colour(h, heat.height, 0, 0, 160), 100u);
    EXPECT_GT(count_colour(h, heat.height, 255, 255, 0), 0u);
    EXPECT_GT(count_colour(h, heat.height, 255, 0, 0), 0u);
    EXPECT_GT(count_colour(h, heat.height, 0, 255, 255), 0u);  // the ring's key
    // The mark at the largest difference moves with it; a tolerance of 0 has no blue.
    EXPECT_NE(rt::add_heatmap_legend(heat, 1, 60).rgb, h.rgb);
    EXPECT_EQ(count_colour(rt::add_heatmap_legend(heat, 0, 30), heat.height, 0, 0, 160), 0u);
    // A wide heatmap keeps its width; the text grows with it.
    const rt::Image wide = rt::diff_heatmap(gradient(700, 4), gradient(700, 4));
    const rt::Image hw = rt::add_heatmap_legend(wide, 1, 0);
    EXPECT_EQ(hw.width, 700);
    EXPECT_TRUE(starts_with_image(hw, wide));
    EXPECT_GT(hw.height - wide.height, h.height - heat.height);
}

namespace {

// `img` scaled down by `f` each way, each pixel the mean of f x f: a page showing it smaller.
rt::Image shrink(const rt::Image& img, int f) {
    rt::Image out;
    out.width = img.width / f;
    out.height = img.height / f;
    out.rgb.resize(size_t(out.width) * size_t(out.height) * 3);
    for (int y = 0; y < out.height; ++y)
        for (int x = 0; x < out.width; ++x)
            for (int c = 0; c < 3; ++c) {
                int sum = 0;
                for (int dy = 0; dy < f; ++dy)
                    for (int dx = 0; dx < f; ++dx) sum += px(img, x * f + dx, y * f + dy, c);
                at(out, x, y, c) = uint8_t(sum / (f * f));
            }
    return out;
}

// The pixels of `img` with some channel 64 levels or more from `base`'s: what stands out.
size_t standing_out(const rt::Image& img, const rt::Image& base) {
    size_t n = 0;
    for (size_t p = 0; p < img.rgb.size(); p += 3)
        for (size_t c = 0; c < 3; ++c)
            if (std::abs(int(img.rgb[p + c]) - int(base.rgb[p + c])) >= 64) {
                ++n;
                break;
            }
    return n;
}

}  // namespace

TEST(ImageDiff, ASinglePixelOffStaysVisibleOnAPageScaledDownFourTimes) {
    const rt::Image a = gradient(800, 800);
    rt::Image b = a;
    at(b, 401, 302, 1) += 2;  // one pixel, just over the tolerance
    const rt::Image equal = shrink(rt::diff_heatmap(a, a), 4);
    // Alone, it is lost when the page scales the heatmap down.
    EXPECT_EQ(standing_out(shrink(rt::diff_heatmap(a, b), 4), equal), 0u);
    // Ringed, it stands out: a ring of some dozens of pixels around it.
    rt::Image heat = rt::diff_heatmap(a, b);
    EXPECT_EQ(rt::ring_small_spots(heat, a, b, 1), 1u);
    const rt::Image small = shrink(heat, 4);
    EXPECT_GE(standing_out(small, equal), 20u);
    // Only near the pixel, and never over it: it keeps the ramp's colour.
    for (int y = 0; y < small.height; ++y)
        for (int x = 0; x < small.width; ++x) {
            if (std::abs(x - 100) > 5 || std::abs(y - 75) > 5) {
                ASSERT_EQ(px(small, x, y, 1), px(equal, x, y, 1)) << x << "," << y;
            }
        }
    EXPECT_EQ(px(heat, 401, 302, 0), 255);
    EXPECT_EQ(px(heat, 401, 302, 1), 255);
    EXPECT_EQ(px(heat, 401, 302, 2), 0);
    // Two spots near each other get a ring each; a crowd of spots none, as rings would
    // cover it.
    rt::Image two = b;
    at(two, 421, 302, 0) += 5;
    rt::Image two_heat = rt::diff_heatmap(a, two);
    EXPECT_EQ(rt::ring_small_spots(two_heat, a, two, 1), 2u);
    rt::Image crowd = a;
    for (int y = 300; y < 340; y += 4)
        for (int x = 300; x < 340; x += 4) at(crowd, x, y, 0) ^= 0x80;
    rt::Image crowd_heat = rt::diff_heatmap(a, crowd);
    EXPECT_EQ(rt::ring_small_spots(crowd_heat, a, crowd, 1), 0u);
    // A spot large enough to be seen gets no ring; rtdiff's heatmap is the ringed one.
    rt::Image big = a;
    for (int y = 100; y < 140; ++y)
        for (int x = 100; x < 140; ++x) at(big, x, y, 0) ^= 0x80;
    rt::Image big_heat = rt::diff_heatmap(a, big);
    EXPECT_EQ(rt::ring_small_spots(big_heat, a, big, 1), 0u);
    EXPECT_EQ(big_heat.rgb, rt::diff_heatmap(a, big).rgb);
    const rt::ImageComparison c = rt::compare_images(a, b);
    EXPECT_EQ(rt::heatmap_with_legend(a, b, c).rgb, rt::add_heatmap_legend(heat, 1, c.max_diff).rgb);
}

TEST(BitmapFont, GlyphsAreDistinctAndLowerCaseIsUpper) {
    const std::string chars = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ:,.-+=<>()/%?";
    const uint8_t ink[3] = {0, 0, 0};
    auto draw = [&ink](const std::string& text) {
        rt::Image img;
        img.width = rt::text_width(text, 2);
        img.height = rt::kGlyphHeight * 2;
        img.rgb.assign(size_t(img.width) * size_t(img.height) * 3, 255);
        rt::draw_text(img, 0, 0, text, 2, ink);
        return img.rgb;
    };
    std::vector<std::vector<uint8_t>> seen;
    for (char c : chars) {
        const std::vector<uint8_t> g = draw(std::string(1, c));
        EXPECT_NE(g, std::vector<uint8_t>(g.size(), 255)) << c;
        for (const auto& other : seen) EXPECT_NE(g, other) << c;
        seen.push_back(g);
    }
    EXPECT_EQ(draw("max"), draw("MAX"));
    EXPECT_EQ(draw("~"), draw("?"));
    EXPECT_EQ(draw(" "), std::vector<uint8_t>(draw(" ").size(), 255));
    EXPECT_EQ(rt::text_width("AB", 1), 11);
    EXPECT_EQ(rt::text_width("", 3), 0);
}

TEST(ImageDiff, ReadImageReadsPngAndPpmAndNamesBadFiles) {
    TempDir tmp;
    const rt::Image a = gradient(5, 3);
    rt::write_png(a, tmp / "a.png");
    rt::write_ppm(a, tmp / "a.ppm");
    EXPECT_EQ(rt::read_image(tmp / "a.png").rgb, a.rgb);
    EXPECT_EQ(rt::read_image(tmp / "a.ppm").rgb, a.rgb);
    write_text(tmp / "text.png", "not an image\n");
    for (const std::string& bad : {tmp / "missing.png", tmp / "text.png", tmp.path()}) {
        try {
            rt::read_image(bad);
            ADD_FAILURE() << bad << " was read";
        } catch (const rt::InputError& e) {
            EXPECT_EQ(std::string(e.what()).rfind(bad + ": ", 0), 0u) << e.what();
        }
    }
}

// ./rtdiff itself.

TEST_F(RtdiffTool, IdenticalImagesPrintZeroAndInf) {
    const RunResult r = run({"a.png", "a.ppm"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "same size, 20x10")) << r.out;
    EXPECT_TRUE(contains(r.out, "max 0, mean 0.0000, 0 of 200 pixels (0.0000%) off by more than 1, PSNR inf, box none"))
        << r.out;
    EXPECT_EQ(r.err, "");
}

TEST_F(RtdiffTool, OnePixelOffByTwo) {
    const RunResult r = run({"a.png", "b.png"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "max 2, ")) << r.out;
    EXPECT_TRUE(contains(r.out, "1 of 200 pixels (0.5000%) off by more than 1")) << r.out;
    EXPECT_TRUE(contains(r.out, "box x 13..13 y 7..7")) << r.out;
    EXPECT_TRUE(contains(r.out, "trace the worst: ./raytracer --trace 13,7 <scene.json>\n")) << r.out;
    const RunResult t = run({"--tolerance", "2", "a.png", "b.png"});
    EXPECT_EQ(t.exit_code, 0);
    EXPECT_TRUE(contains(t.out, "0 of 200 pixels (0.0000%) off by more than 2")) << t.out;
}

TEST_F(RtdiffTool, PrintsTheWorstPixelsAndTheCommandThatTracesTheWorst) {
    rt::Image a, b;
    known_pair(a, b);
    rt::write_png(a, tmp_ / "ka.png");
    rt::write_png(b, tmp_ / "kb.png");
    const RunResult r = run({"ka.png", "kb.png"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 9u) << r.out;
    EXPECT_EQ(lines[2], "worst pixels (x,y as raytracer --trace takes them), largest channel difference first:");
    const std::vector<std::string> expected = {"8,6 off by 30", "2,3 off by 9", "1,5 off by 9", "6,1 off by 5",
                                               "5,4 off by 2"};
    for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(lines[3 + i].rfind("  " + expected[i] + ": A ", 0), 0u);
    EXPECT_EQ(lines[3], "  8,6 off by 30: A 94 95 96, B 94 65 96");
    EXPECT_EQ(lines[8], "trace the worst: ./raytracer --trace 8,6 <scene.json>");
    // --scene names the scene (one shell word), --camera its camera.
    const RunResult s = run({"--scene", "../shared/scenes/hw1/simple.json", "ka.png", "kb.png"});
    EXPECT_TRUE(contains(s.out, "trace the worst: ./raytracer --trace 8,6 ../shared/scenes/hw1/simple.json\n"))
        << s.out;
    const RunResult c = run({"--scene", "my scenes/it's.json", "--camera", "2", "ka.png", "kb.png"});
    EXPECT_TRUE(contains(c.out, "trace the worst: ./raytracer --trace 8,6 --camera 2 'my scenes/it'\\''s.json'\n"))
        << c.out;
    // Equal images: no worst pixel, no command.
    const RunResult same = run({"--scene", "x.json", "ka.png", "ka.png"});
    EXPECT_EQ(same.exit_code, 0);
    EXPECT_FALSE(contains(same.out, "worst")) << same.out;
    EXPECT_FALSE(contains(same.out, "--trace")) << same.out;
    EXPECT_EQ(run({"--camera", "0", "ka.png", "kb.png"}).exit_code, 2);
}

TEST_F(RtdiffTool, FailAboveExitsOneOnlyWhenOver) {
    EXPECT_EQ(run({"--fail-above", "0.5", "a.png", "b.png"}).exit_code, 0);  // 0.5% is not more than 0.5%
    const RunResult over = run({"--fail-above", "0.4", "a.png", "b.png"});
    EXPECT_EQ(over.exit_code, 1);
    EXPECT_TRUE(contains(over.out, "over --fail-above")) << over.out;
    EXPECT_EQ(run({"--fail-above=0", "a.png", "a.png"}).exit_code, 0);
}

TEST_F(RtdiffTool, HeatmapIsWritten) {
    const RunResult r = run({"--heatmap", "h.png", "a.png", "b.png"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "h.png", h));
    // The heatmap, its one off pixel ringed, with its legend below it, for this pair's
    // largest difference.
    rt::Image heat = rt::diff_heatmap(a_, b_);
    EXPECT_EQ(rt::ring_small_spots(heat, a_, b_, 1), 1u);
    EXPECT_TRUE(starts_with_image(h, heat));
    EXPECT_GT(h.height, heat.height);
    EXPECT_EQ(h.rgb, rt::add_heatmap_legend(heat, 1, 2).rgb);
    EXPECT_EQ(h.rgb, rt::heatmap_with_legend(a_, b_, rt::compare_images(a_, b_)).rgb);
}

TEST_F(RtdiffTool, BadInputIsOneLineAndExitOne) {
    write_text(tmp_ / "text.png", "hello\n");
    rt::write_png(gradient(21, 10), tmp_ / "wide.png");
    const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
        {{"missing.png", "a.png"}, "error: missing.png: no such file\n"},
        {{"a.png", "text.png"}, "error: text.png: not a PNG or PPM image"},
        {{"a.png", "wide.png"}, "error: wide.png: 21x10, but a.png is 20x10\n"},
    };
    for (const auto& [args, line] : cases) {
        const RunResult r = run(args);
        EXPECT_EQ(r.exit_code, 1) << args[0] << " " << args[1];
        EXPECT_EQ(r.err.rfind(line, 0), 0u) << r.err;
        EXPECT_EQ(split_lines(r.err).size(), 1u) << r.err;
        EXPECT_EQ(r.out, "");
    }
}

TEST_F(RtdiffTool, UsageErrorsExitTwo) {
    for (const std::vector<std::string>& args : {std::vector<std::string>{"a.png"},
                                                 {"a.png", "b.png", "c.png"},
                                                 {"--tolerance", "x", "a.png", "b.png"},
                                                 {"--fail-above", "101", "a.png", "b.png"},
                                                 {"--bogus", "a.png", "b.png"}}) {
        const RunResult r = run(args);
        EXPECT_EQ(r.exit_code, 2) << args[0];
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    }
}

namespace {

// Folders a and b: same.png identical, `one` one pixel off by 2, many.png 5% of its
// pixels off, only_a.png and only_b.ppm on one side.
void write_folders(const rt::Image& a_img, const rt::Image& b_img, const TempDir& a, const TempDir& b,
                   const std::string& one) {
    rt::Image big = a_img;
    for (int x = 0; x < 10; ++x) at(big, x, 0, 2) ^= 0x80;
    rt::write_png(a_img, a / "same.png");
    rt::write_png(a_img, b / "same.png");
    rt::write_png(a_img, a / one);
    rt::write_png(b_img, b / one);
    rt::write_png(a_img, a / "many.png");
    rt::write_png(big, b / "many.png");
    rt::write_png(a_img, a / "only_a.png");
    rt::write_ppm(a_img, b / "only_b.ppm");
}

}  // namespace

TEST_F(RtdiffTool, FoldersCompareByNameWorstFirst) {
    TempDir a, b;
    write_folders(a_, b_, a, b, "one.png");
    write_text(a / "notes.txt", "not an image, not listed\n");
    const RunResult r = run_program(rtdiff_path(), {a.path(), b.path()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 9u) << r.out;
    // Each pair that differs has its worst pixel on the line below it.
    EXPECT_EQ(lines[1].rfind("many.png", 0), 0u) << r.out;
    EXPECT_EQ(lines[2], "  worst pixel 0,0 off by 128: A 40 41 42, B 40 41 170") << r.out;
    EXPECT_EQ(lines[3].rfind("one.png", 0), 0u) << r.out;
    EXPECT_EQ(lines[4], "  worst pixel 13,7 off by 2: A " + std::to_string(px(a_, 13, 7, 0)) + " " +
                            std::to_string(px(a_, 13, 7, 1)) + " " + std::to_string(px(a_, 13, 7, 2)) + ", B " +
                            std::to_string(px(b_, 13, 7, 0)) + " " + std::to_string(px(b_, 13, 7, 1)) + " " +
                            std::to_string(px(b_, 13, 7, 2)))
        << r.out;
    EXPECT_EQ(lines[5].rfind("same.png", 0), 0u) << r.out;
    EXPECT_TRUE(contains(lines[3], "x 13..13 y 7..7")) << lines[3];
    EXPECT_TRUE(contains(lines[5], "inf")) << lines[5];
    EXPECT_EQ(lines[6], "1 image only in " + a.path() + " (not compared): only_a.png") << r.out;
    EXPECT_EQ(lines[7], "1 image only in " + b.path() + " (not compared): only_b.ppm") << r.out;
    EXPECT_EQ(lines[8], "3 compared, 1 only in " + a.path() + ", 1 only in " + b.path()) << r.out;
    EXPECT_FALSE(contains(r.out, "notes.txt"));
    // many.png has 5% of its pixels off, one.png 0.5%.
    EXPECT_EQ(run_program(rtdiff_path(), {"--fail-above", "5", a.path(), b.path()}).exit_code, 0);
    const RunResult over = run_program(rtdiff_path(), {"--fail-above", "1", a.path(), b.path()});
    EXPECT_EQ(over.exit_code, 1);
    EXPECT_TRUE(contains(over.out, "1 over --fail-above")) << over.out;
}

TEST_F(RtdiffTool, HtmlPageListsWorstFirstAndLinksExistingFiles) {
    TempDir a, b;
    write_folders(a_, b_, a, b, "one off.png");  // a space: the links must be encoded
    const RunResult r = run({"--html", "page", a.path(), b.path()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const std::string page = read_text(tmp_ / "page/index.html");
    // The summary table, worst first.
    const size_t table = page.find("<table"), table_end = page.find("</table>");
    ASSERT_NE(table, std::string::npos);
    const size_t many = page.find(">many.png<", table), one = page.find(">one off.png<", table),
                 same = page.find(">same.png<", table);
    EXPECT_LT(many, one);
    EXPECT_LT(one, same);
    EXPECT_LT(same, table_end);
    EXPECT_NE(page.find("only in A: only_a.png"), std::string::npos);
    EXPECT_NE(page.find("only in B: only_b.ppm"), std::string::npos);
    // Three images per compared pair (A, B, heatmap), every link a file that exists.
    const std::vector<std::string> srcs = attributes(page, "src");
    EXPECT_EQ(srcs.size(), 9u);
    std::vector<std::string> links = srcs;
    for (const std::string& h : attributes(page, "href"))
        if (h.rfind("#", 0) != 0) links.push_back(h);
    for (const std::string& l : links) {
        EXPECT_EQ(l.find(' '), std::string::npos) << l;
        EXPECT_TRUE(file_exists(tmp_ / "page/" + url_decode(l))) << l;
    }
    // The heatmap is the one rt::diff_heatmap draws, with its legend; the worst pixel is listed.
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "page/heatmaps/one off.png", h));
    EXPECT_EQ(h.rgb, rt::heatmap_with_legend(a_, b_, rt::compare_images(a_, b_)).rgb);
    EXPECT_TRUE(contains(page, "<li>13,7 off by 2: A ")) << page;
}

TEST_F(RtdiffTool, HtmlPageForTwoImages) {
    rt::Image a, b;
    known_pair(a, b);
    rt::write_png(a, tmp_ / "ka.png");
    rt::write_png(b, tmp_ / "kb.png");
    const RunResult r = run({"--html", "p2", "ka.png", "kb.png"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(contains(r.out, "trace the worst: ")) << r.out;  // the text report is printed too
    const std::string page = read_text(tmp_ / "p2/index.html");
    EXPECT_TRUE(contains(page, ">ka.png<")) << page;
    EXPECT_TRUE(contains(page, "<li>8,6 off by 30: A 94 95 96, B 94 65 96</li>")) << page;
    // A, B and the heatmap, every link a file that exists; the heatmap is rtdiff's, legend included.
    const std::vector<std::string> srcs = attributes(page, "src");
    ASSERT_EQ(srcs.size(), 3u) << page;
    for (const std::string& l : srcs) EXPECT_TRUE(file_exists(tmp_ / "p2/" + url_decode(l))) << l;
    EXPECT_EQ(url_decode(srcs[0]), "../ka.png");
    EXPECT_EQ(url_decode(srcs[1]), "../kb.png");
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "p2/" + url_decode(srcs[2]), h));
    EXPECT_EQ(h.rgb, rt::heatmap_with_legend(a, b, rt::compare_images(a, b)).rgb);
    // Images of different sizes: bad input, no page.
    rt::write_png(gradient(11, 8), tmp_ / "wide.png");
    EXPECT_EQ(run({"--html", "p3", "ka.png", "wide.png"}).exit_code, 1);
    EXPECT_FALSE(file_exists(tmp_ / "p3/index.html"));
}

TEST_F(RtdiffTool, ImagesInOneFolderOnlyAreOneLineOrNone) {
    TempDir a, b;
    rt::write_png(a_, a / "common.png");
    rt::write_png(b_, b / "common.png");
    for (int i = 0; i < 6; ++i) rt::write_png(a_, b / ("b" + std::to_string(i) + ".png"));
    rt::write_png(a_, a / "mine.png");
    const RunResult r = run_program(rtdiff_path(), {a.path(), b.path()});
    EXPECT_EQ(r.exit_code, 0) << r.err;  // images in one folder only do not change the status
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 6u) << r.out;
    EXPECT_EQ(lines[3], "1 image only in " + a.path() + " (not compared): mine.png");
    EXPECT_EQ(lines[4], "6 images only in " + b.path() + " (not compared): b0.png, b1.png, b2.png, b3.png, ...");
    EXPECT_FALSE(contains(r.out, "b4.png")) << r.out;
    EXPECT_EQ(lines[5], "1 compared, 1 only in " + a.path() + ", 6 only in " + b.path());
    // --only-common: not a word of them, on stdout or on the page; the same status.
    const RunResult c = run_program(rtdiff_path(), {"--only-common", "--html", tmp_ / "pc", a.path(), b.path()});
    EXPECT_EQ(c.exit_code, 0) << c.err;
    EXPECT_FALSE(contains(c.out, "only")) << c.out;
    EXPECT_FALSE(contains(c.out, "mine.png")) << c.out;
    EXPECT_EQ(split_lines(c.out).back(), "1 compared");
    EXPECT_FALSE(contains(read_text(tmp_ / "pc/index.html"), "mine.png"));
    // The status of the compared pairs stays: over --fail-above is 1 with --only-common too.
    EXPECT_EQ(run_program(rtdiff_path(), {"--only-common", "--fail-above", "0.1", a.path(), b.path()}).exit_code, 1);
    // No image in both folders: nothing was compared, which is not a success.
    TempDir empty;
    const RunResult none = run_program(rtdiff_path(), {"--only-common", empty.path(), b.path()});
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_EQ(none.err, "error: no image is in both " + empty.path() + " and " + b.path() + "\n");
    // Options for the other mode are usage errors.
    EXPECT_EQ(run({"--only-common", "a.png", "b.png"}).exit_code, 2);
    EXPECT_EQ(run_program(rtdiff_path(), {"--scene", "s.json", a.path(), b.path()}).exit_code, 2);
}

TEST_F(RtdiffTool, AFolderAndAFileIsBadInput) {
    const RunResult mixed = run({tmp_.path(), "a.png"});
    EXPECT_EQ(mixed.exit_code, 1);
    EXPECT_EQ(mixed.err, "error: a.png: not a folder, but " + tmp_.path() + " is one\n");
}
