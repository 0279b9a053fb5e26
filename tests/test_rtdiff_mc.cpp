// The Monte Carlo comparison of rt/image/block_diff.h on hand-made images whose block means
// are known (a block shifted, half a level everywhere, checkerboard noise, edge blocks), its
// heatmap, and ./rtdiff --mc: two images with the noise floor, folders, the manifest's choice
// by NumSamples, exit statuses and usage errors.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rt/image/block_diff.h"
#include "rt/image/image.h"
#include "rt/image/image_diff.h"
#include "rtdiff_test_support.h"
#include "test_support.h"

using namespace rtdiff_test;

namespace {

// `img` with `delta` added to every channel of the pixels x0 <= x < x1, y0 <= y < y1.
rt::Image shifted(rt::Image img, int x0, int y0, int x1, int y1, int delta) {
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            for (int c = 0; c < 3; ++c) at(img, x, y, c) = uint8_t(int(at(img, x, y, c)) + delta);
    return img;
}

// `img` with `delta` added to every channel of the pixels where x + y is even and
// `odd_delta` where it is odd: a checkerboard.
rt::Image checkerboard(rt::Image img, int delta, int odd_delta) {
    for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x)
            for (int c = 0; c < 3; ++c)
                at(img, x, y, c) = uint8_t(int(at(img, x, y, c)) + ((x + y) % 2 == 0 ? delta : odd_delta));
    return img;
}

// The line of `out` that starts with `start`; empty when none does.
std::string line_starting(const std::string& out, const std::string& start) {
    for (const std::string& l : split_lines(out))
        if (l.rfind(start, 0) == 0) return l;
    return "";
}

// The index of the line of `out` that starts with `start`; -1 when none does.
int line_index(const std::string& out, const std::string& start) {
    const std::vector<std::string> lines = split_lines(out);
    for (size_t i = 0; i < lines.size(); ++i)
        if (lines[i].rfind(start, 0) == 0) return int(i);
    return -1;
}

const std::string kPass =
    "pass: at most 1% of the 16x16 blocks off by more than 3 levels and every channel's mean difference within 1 "
    "level";

}  // namespace

TEST(BlockDiff, OneBlockOfFourShiftedByFourLevelsIsAQuarterOff) {
    const rt::Image b = gradient(32, 32);
    const rt::Image a = shifted(b, 16, 0, 32, 16, 4);  // the top right block of 256 pixels
    const rt::BlockComparison c = rt::compare_blocks(a, b);
    ASSERT_TRUE(c.same_size);
    EXPECT_EQ(c.blocks_x, 2);
    EXPECT_EQ(c.blocks_y, 2);
    EXPECT_EQ(c.blocks, 4u);
    EXPECT_EQ(c.blocks_off, 1u);
    EXPECT_DOUBLE_EQ(c.pct_off, 25.0);
    EXPECT_EQ(c.block_diff, (std::vector<int>{0, 4, 0, 0}));
    EXPECT_EQ(c.max_block_diff, 4);
    for (int ch = 0; ch < 3; ++ch) EXPECT_DOUBLE_EQ(c.mean_diff[ch], 1.0);  // 4 * 256 / 1024
    EXPECT_DOUBLE_EQ(c.mean_diff_all, 1.0);
    EXPECT_DOUBLE_EQ(c.rmse, 2.0);  // sqrt(16 * 256 / 1024)
    EXPECT_DOUBLE_EQ(c.psnr, 10 * std::log10(255.0 * 255.0 / 4.0));
    EXPECT_DOUBLE_EQ(c.max_channel_bias(), 1.0);
    // The difference is signed, A - B.
    const rt::BlockComparison back = rt::compare_blocks(b, a);
    EXPECT_DOUBLE_EQ(back.mean_diff[1], -1.0);
    EXPECT_EQ(back.blocks_off, 1u);
    // Off means more than the threshold: 3 levels are not off at 3, but are at 2.
    const rt::Image three = shifted(b, 16, 0, 32, 16, 3);
    EXPECT_EQ(rt::compare_blocks(three, b).blocks_off, 0u);
    EXPECT_EQ(rt::compare_blocks(three, b, 16, 2).blocks_off, 1u);
    // One channel alone is enough.
    rt::Image red = b;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) at(red, x, y, 0) += 4;
    const rt::BlockComparison r = rt::compare_blocks(red, b);
    EXPECT_EQ(r.block_diff, (std::vector<int>{4, 0, 0, 0}));
    EXPECT_DOUBLE_EQ(r.mean_diff[0], 1.0);
    EXPECT_DOUBLE_EQ(r.mean_diff[1], 0.0);
    EXPECT_DOUBLE_EQ(r.mean_diff_all, 1.0 / 3);
}

TEST(BlockDiff, HalfALevelEverywhereIsNoBlockOffButAMeanOfHalf) {
    const rt::Image b = gradient(32, 32);
    const rt::Image a = checkerboard(b, 1, 0);  // +1 on half the pixels of every block
    const rt::BlockComparison c = rt::compare_blocks(a, b);
    EXPECT_EQ(c.blocks_off, 0u);
    EXPECT_EQ(c.pct_off, 0.0);
    EXPECT_EQ(c.block_diff, (std::vector<int>{1, 1, 1, 1}));  // 0.5 rounded up
    for (int ch = 0; ch < 3; ++ch) EXPECT_DOUBLE_EQ(c.mean_diff[ch], 0.5);
    EXPECT_DOUBLE_EQ(c.mean_diff_all, 0.5);
    EXPECT_DOUBLE_EQ(c.rmse, std::sqrt(0.5));
}

TEST(BlockDiff, CheckerboardNoiseOfTwentyLevelsIsNoBlockOffThoughEveryPixelIs) {
    const rt::Image b = gradient(32, 32);
    const rt::Image a = checkerboard(b, 20, -20);
    const rt::BlockComparison c = rt::compare_blocks(a, b);
    EXPECT_EQ(c.blocks_off, 0u);
    EXPECT_EQ(c.block_diff, (std::vector<int>{0, 0, 0, 0}));
    EXPECT_EQ(c.max_block_diff, 0);
    EXPECT_DOUBLE_EQ(c.mean_diff_all, 0.0);
    EXPECT_DOUBLE_EQ(c.rmse, 20.0);
    // Pixel by pixel, every pixel is off.
    EXPECT_DOUBLE_EQ(rt::compare_images(a, b).pct_over, 100.0);
}

TEST(BlockDiff, EdgeBlocksAverageThePixelsTheyHave) {
    // 20x18 in blocks of 16: columns of 16 and 4 pixels, rows of 16 and 2; the bottom right
    // block holds 4 x 2 = 8 pixels.
    const rt::Image b = gradient(20, 18);
    rt::Image a = b;
    at(a, 19, 17, 0) += 25;  // 25 / 8 = 3.125 levels over the bottom right block: off
    at(a, 0, 0, 0) += 25;    // 25 / 256 over a whole block: not off
    at(a, 18, 3, 2) += 25;   // 25 / 64 over the top right block (4 x 16): not off
    const rt::BlockComparison c = rt::compare_blocks(a, b);
    EXPECT_EQ(c.blocks_x, 2);
    EXPECT_EQ(c.blocks_y, 2);
    EXPECT_EQ(c.blocks, 4u);
    EXPECT_EQ(c.block_diff, (std::vector<int>{1, 1, 0, 4}));
    EXPECT_EQ(c.blocks_off, 1u);
    EXPECT_DOUBLE_EQ(c.pct_off, 25.0);
    EXPECT_DOUBLE_EQ(c.mean_diff[0], 50.0 / 360);
    // A block larger than the image is the whole image: 75 / 360 levels.
    const rt::BlockComparison whole = rt::compare_blocks(a, b, 64);
    EXPECT_EQ(whole.blocks, 1u);
    EXPECT_EQ(whole.block_diff, (std::vector<int>{1}));
    EXPECT_EQ(whole.blocks_off, 0u);
    // Blocks of one pixel are the pixels: 3 of 360 off by 25.
    EXPECT_EQ(rt::compare_blocks(a, b, 1).blocks_off, 3u);
}

TEST(BlockDiff, DifferentSizesAreNotMeasured) {
    const rt::BlockComparison c = rt::compare_blocks(gradient(20, 10), gradient(21, 10));
    EXPECT_FALSE(c.same_size);
    EXPECT_EQ(c.blocks, 0u);
    EXPECT_TRUE(rt::block_heatmap(gradient(20, 10), c).rgb.empty());
}

TEST(BlockDiff, HeatmapColoursEachBlockByItsLargestChannelMeanDifference) {
    const rt::Image b = gradient(32, 32);
    rt::Image a = shifted(b, 16, 0, 32, 16, 4);  // top right: off by 4, yellow
    a = shifted(a, 0, 16, 16, 32, 2);            // bottom left: within 3, blue
    at(a, 20, 20, 1) += 80;                      // bottom right: 80 / 256, blue all over
    const rt::BlockComparison c = rt::compare_blocks(a, b);
    EXPECT_EQ(c.block_diff, (std::vector<int>{0, 4, 2, 1}));
    const rt::Image h = rt::block_heatmap(a, c);
    ASSERT_EQ(h.width, 32);
    ASSERT_EQ(h.height, 32);
    const rt::Image grey = rt::diff_heatmap(a, a);  // every pixel equal: a's dimmed luma
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) {
            const int block = (y / 16) * 2 + x / 16;
            const uint8_t yellow[3] = {255, 255, 0}, blue[3] = {0, 0, 160};
            for (int ch = 0; ch < 3; ++ch) {
                const uint8_t want = block == 0 ? px(grey, x, y, ch) : block == 1 ? yellow[ch] : blue[ch];
                ASSERT_EQ(px(h, x, y, ch), want) << x << "," << y;
            }
        }
    // The legend of blocks: the heatmap at the top left, no ring line (a shorter strip).
    const rt::Image legend = rt::block_heatmap_with_legend(a, c);
    EXPECT_EQ(legend.rgb, rt::add_heatmap_legend(h, 3, 4, 16).rgb);
    EXPECT_EQ(legend.width, rt::kHeatmapLegendMinWidth);
    EXPECT_LT(legend.height, rt::add_heatmap_legend(h, 3, 4).height);
    for (int y = 0; y < 32; ++y)
        for (int x = 0; x < 32; ++x) ASSERT_EQ(px(legend, x, y, 0), px(h, x, y, 0));
}

// ./rtdiff --mc.

TEST_F(RtdiffTool, McTwoImagesPrintTheBlockFiguresAndAVerdict) {
    const rt::Image ref = gradient(32, 32);
    rt::write_png(ref, tmp_ / "ref.png");
    rt::write_png(shifted(ref, 16, 0, 32, 16, 4), tmp_ / "shift.png");
    rt::write_png(checkerboard(ref, 1, 0), tmp_ / "half.png");
    rt::write_png(checkerboard(ref, 20, -20), tmp_ / "noisy.png");
    rt::write_png(shifted(ref, 0, 0, 32, 32, 2), tmp_ / "bright.png");

    const RunResult r = run({"--mc", "shift.png", "ref.png"});
    EXPECT_EQ(r.exit_code, 1) << r.err;  // 25% of the blocks off
    EXPECT_EQ(r.err, "");
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 4u) << r.out;
    EXPECT_EQ(lines[0], "shift.png vs ref.png (reference): same size, 32x32, 4 blocks of 16x16 pixels");
    EXPECT_EQ(lines[1], "               % blocks >3     A-B: R      G      B    all      RMSE       PSNR");
    EXPECT_EQ(lines[2], "vs reference       25.0000      +1.00  +1.00  +1.00  +1.00      2.00   42.11 dB");
    EXPECT_EQ(lines[3], "FAIL: 25.0000% of the blocks off by more than 3 (at most 1%)");
    // The criterion's bounds are inclusive and can be moved.
    const RunResult loose = run({"--mc", "--max-off-blocks", "25", "shift.png", "ref.png"});
    EXPECT_EQ(loose.exit_code, 0);
    EXPECT_TRUE(contains(loose.out, "pass: at most 25% of the 16x16 blocks off")) << loose.out;
    EXPECT_EQ(run({"--mc", "--block-threshold", "4", "shift.png", "ref.png"}).exit_code, 0);
    const RunResult small = run({"--mc", "--block", "8", "shift.png", "ref.png"});
    EXPECT_EQ(small.exit_code, 1);
    EXPECT_TRUE(contains(small.out, "same size, 32x32, 16 blocks of 8x8 pixels\n")) << small.out;
    EXPECT_TRUE(contains(small.out, "FAIL: 25.0000% of the blocks off by more than 3")) << small.out;

    // Half a level everywhere: no block off, a mean of +0.50: a pass.
    const RunResult half = run({"--mc", "half.png", "ref.png"});
    EXPECT_EQ(half.exit_code, 0) << half.out;
    EXPECT_TRUE(contains(half.out, "vs reference        0.0000      +0.50  +0.50  +0.50  +0.50      0.71")) << half.out;
    EXPECT_EQ(split_lines(half.out).back(), kPass);
    // Noise of 20 levels: a pass by blocks, every pixel off pixel by pixel.
    const RunResult noisy = run({"--mc", "noisy.png", "ref.png"});
    EXPECT_EQ(noisy.exit_code, 0) << noisy.out;
    EXPECT_TRUE(contains(noisy.out, "vs reference        0.0000      +0.00  +0.00  +0.00  +0.00     20.00"))
        << noisy.out;
    EXPECT_TRUE(contains(run({"noisy.png", "ref.png"}).out, "1024 of 1024 pixels (100.0000%) off"));
    // Two levels brighter everywhere: no block off, but a bias.
    const RunResult bright = run({"--mc", "bright.png", "ref.png"});
    EXPECT_EQ(bright.exit_code, 1);
    EXPECT_EQ(split_lines(bright.out).back(), "FAIL: mean difference over 1 level: R +2.00, G +2.00, B +2.00");
    EXPECT_EQ(run({"--mc", "--max-mean-diff", "2", "bright.png", "ref.png"}).exit_code, 0);
    // The same image: a pass.
    const RunResult same = run({"--mc", "ref.png", "ref.png"});
    EXPECT_EQ(same.exit_code, 0);
    EXPECT_TRUE(contains(same.out, "vs reference        0.0000      +0.00  +0.00  +0.00  +0.00      0.00        inf"))
        << same.out;
    // --heatmap: the blocks' heatmap.
    EXPECT_EQ(run({"--mc", "--heatmap", "h.png", "shift.png", "ref.png"}).exit_code, 1);
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "h.png", h));
    const rt::Image shift = shifted(ref, 16, 0, 32, 16, 4);
    EXPECT_EQ(h.rgb, rt::block_heatmap_with_legend(shift, rt::compare_blocks(shift, ref)).rgb);
}

TEST_F(RtdiffTool, McNoiseFloorIsPrintedBesideTheFigures) {
    const rt::Image ref = gradient(32, 32);
    rt::write_png(ref, tmp_ / "ref.png");
    rt::write_png(checkerboard(ref, 20, -20), tmp_ / "seed1.png");
    rt::write_png(checkerboard(ref, -20, 20), tmp_ / "seed2.png");
    const RunResult r = run({"--mc", "--noise", "seed2.png", "seed1.png", "ref.png"});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 5u) << r.out;
    EXPECT_EQ(lines[0],
              "seed1.png vs ref.png (reference), other seed seed2.png: same size, 32x32, 4 blocks of 16x16 pixels");
    EXPECT_EQ(lines[2], "vs reference        0.0000      +0.00  +0.00  +0.00  +0.00     20.00   22.11 dB");
    EXPECT_EQ(lines[3], "vs other seed       0.0000      +0.00  +0.00  +0.00  +0.00     40.00   16.09 dB");
    EXPECT_EQ(lines[4], kPass);
    // The other seed must be A's size; a missing one is bad input.
    rt::write_png(gradient(32, 16), tmp_ / "short.png");
    const RunResult bad = run({"--mc", "--noise", "short.png", "seed1.png", "ref.png"});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_EQ(bad.err, "error: short.png: 32x16, but seed1.png is 32x32\n");
    EXPECT_EQ(bad.out, "");
    EXPECT_EQ(run({"--mc", "--noise", "none.png", "seed1.png", "ref.png"}).err, "error: none.png: no such file\n");
}

TEST_F(RtdiffTool, McFoldersWithTheirOtherSeeds) {
    const rt::Image ref = gradient(32, 32);
    for (const char* d : {"a", "b", "n", "h"}) create_dirs(tmp_ / d);
    rt::write_png(shifted(ref, 16, 0, 32, 16, 4), tmp_ / "a/x.png");
    rt::write_png(ref, tmp_ / "b/x.png");
    rt::write_png(checkerboard(ref, 20, -20), tmp_ / "a/y.png");
    rt::write_png(ref, tmp_ / "b/y.png");
    rt::write_png(checkerboard(ref, -20, 20), tmp_ / "n/y.png");  // no n/x.png
    const RunResult r = run({"--mc", "--noise-dir", "n", "--heatmap", "h", "a", "b"});
    EXPECT_EQ(r.exit_code, 1) << r.err;  // x.png is no pass
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 6u) << r.out;
    EXPECT_EQ(lines[0],
              "image                 size   % blocks >3     A-B: R      G      B    all      RMSE       PSNR");
    EXPECT_EQ(lines[1],
              "x.png                32x32       25.0000      +1.00  +1.00  +1.00  +1.00      2.00   42.11 dB  FAIL");
    EXPECT_EQ(lines[2], "  vs other seed: n/x.png: no such file");
    EXPECT_EQ(lines[3],
              "y.png                32x32        0.0000      +0.00  +0.00  +0.00  +0.00     20.00   22.11 dB");
    EXPECT_EQ(lines[4],
              "  vs other seed                   0.0000      +0.00  +0.00  +0.00  +0.00     40.00   16.09 dB");
    EXPECT_EQ(lines[5],
              "2 compared, 0 only in a, 0 only in b, 1 FAIL (a pass: at most 1% of the 16x16 blocks off by more than 3 "
              "levels and every channel's mean difference within 1 level)");
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "h/x.png", h));
    const rt::Image x = shifted(ref, 16, 0, 32, 16, 4);
    EXPECT_EQ(h.rgb, rt::block_heatmap_with_legend(x, rt::compare_blocks(x, ref)).rgb);
    // Only passes: exit status 0.
    EXPECT_EQ(run({"--mc", "--max-off-blocks", "25", "a", "b"}).exit_code, 0);
}

TEST_F(RtdiffTool, ManifestComparesScenesOfManySamplesByTheirBlocks) {
    const ManifestTree t(tmp_.path());
    const auto scene = [&t](const std::string& name, const std::string& cameras) {
        write_text(t.scenes + "/" + name, R"({"Scene": {"Cameras": {"Camera": )" + cameras + "}}}");
    };
    scene("one.json", R"({"_id": "1", "NumSamples": "1", "ImageName": "one.png"})");
    scene("none.json", R"({"_id": "1", "ImageName": "none.png"})");
    scene("many.json", R"({"_id": "1", "NumSamples": "100", "ImageName": "many.png"})");
    scene("arr.json", R"([{"_id": "1", "NumSamples": "1"}, {"_id": "2", "NumSamples": "16"}])");
    scene("num.json", R"({"_id": "1", "NumSamples": 4})");
    write_text(t.scenes + "/xml.xml",
               "<Scene><Cameras><Camera id=\"1\"><NumSamples>9</NumSamples><ImageName>xml.png</ImageName>"
               "</Camera></Cameras></Scene>\n");
    const std::vector<std::string> names = {"one", "none", "nofile", "many", "arr", "num", "xml"};
    const rt::Image ref = gradient(40, 40);  // blocks of 16, 16 and 8 pixels each way: 9
    const std::string out = tmp_ / "out", noise = tmp_ / "noise";
    create_dirs(out);
    create_dirs(noise);
    for (const std::string& n : names) {
        rt::write_png(ref, t.refs + "/" + n + ".png");
        // Noise of 20 levels: every pixel off, no block.
        rt::write_png(checkerboard(ref, 20, -20), out + "/" + n + ".png");
    }
    rt::write_png(shifted(ref, 0, 0, 16, 16, 4), out + "/many.png");  // 1 block of 9 off
    rt::write_png(checkerboard(ref, -20, 20), noise + "/arr.png");
    std::vector<std::string> lines;
    for (const std::string& n : names)
        lines.push_back((n == "xml" ? "xml.xml" : n + ".json") + "\t" + n + ".png\treferences/hw9/" + n +
                        ".png\tcomplete");
    const std::string m = t.manifest(lines);

    const RunResult r =
        run_program(rtdiff_path(), {"--manifest", m, "--noise-dir", noise, "--heatmap", tmp_ / "heat", out});
    EXPECT_EQ(r.exit_code, 1) << r.err;
    // Pixel by pixel (NumSamples 1, none, a scene that cannot be read): every pixel off.
    EXPECT_EQ(line_index(r.out, "verdict    image  "), 0) << r.out;
    for (const std::string n : {"one", "none", "nofile"})
        EXPECT_TRUE(contains(line_starting(r.out, "FAIL       " + n + ".png  "), "100.0000")) << r.out;
    // By blocks (NumSamples > 1: an object, any camera of an array, a number, XML), below their headings.
    const int mc_heading = line_index(r.out, "verdict    image            size   % blocks >3     A-B: R");
    EXPECT_GT(mc_heading, 0) << r.out;
    EXPECT_EQ(line_index(r.out, "FAIL       many.png        40x40       11.1111      +0.64  +0.64  +0.64  +0.64"),
              mc_heading + 1)
        << r.out;
    EXPECT_EQ(split_lines(r.out)[size_t(mc_heading) + 2], "  vs other seed: not in " + noise + " or its subfolders");
    EXPECT_EQ(split_lines(r.out)[size_t(mc_heading) + 3],
              "  fails: 11.1111% of the blocks off by more than 3 (at most 1%)");
    for (const std::string n : {"arr", "num", "xml"})
        EXPECT_TRUE(contains(line_starting(r.out, "pass       " + n + ".png  "), "0.0000      +0.00")) << r.out;
    const int arr = line_index(r.out, "pass       arr.png  ");
    EXPECT_EQ(split_lines(r.out)[size_t(arr) + 1],
              "  vs other seed                         0.0000      +0.00  +0.00  +0.00  +0.00     40.00   16.09 dB")
        << r.out;
    EXPECT_EQ(split_lines(r.out).back(),
              "7 scenes: 3 pass, 4 FAIL, 0 missing, 0 ambiguous, 0 error, 0 skipped (inputs incomplete); a pass has "
              "at most 0.2% of its pixels off by more than 1; a Monte Carlo scene's pass has at most 1% of the 16x16 "
              "blocks off by more than 3 levels and every channel's mean difference within 1 level");
    // The heatmaps: of pixels, or of blocks.
    rt::Image h;
    ASSERT_TRUE(load_png(tmp_ / "heat/many.png", h));
    const rt::Image many = shifted(ref, 0, 0, 16, 16, 4);
    EXPECT_EQ(h.rgb, rt::block_heatmap_with_legend(many, rt::compare_blocks(many, ref)).rgb);
    ASSERT_TRUE(load_png(tmp_ / "heat/one.png", h));
    const rt::Image one = checkerboard(ref, 20, -20);
    EXPECT_EQ(h.rgb, rt::heatmap_with_legend(one, ref, rt::compare_images(one, ref)).rgb);

    // --mc: every scene by its blocks, one heading; a looser bar passes them all.
    const RunResult all = run_program(rtdiff_path(), {"--manifest", m, "--mc", "--max-off-blocks", "12", out});
    EXPECT_EQ(all.exit_code, 0) << all.out << all.err;
    EXPECT_EQ(line_index(all.out, "verdict    image            size   % blocks >3"), 0) << all.out;
    EXPECT_TRUE(contains(split_lines(all.out).back(),
                         "7 scenes: 7 pass, 0 FAIL, 0 missing, 0 ambiguous, 0 error, 0 skipped (inputs incomplete); a "
                         "pass has at most 12% of the 16x16 blocks off"))
        << all.out;
    EXPECT_EQ(all.err, "");
}

TEST_F(RtdiffTool, McUsageErrorsExitTwo) {
    create_dirs(tmp_ / "d");
    const std::vector<std::vector<std::string>> cases = {
        {"--block", "8", "a.png", "b.png"},                        // without --mc
        {"--max-mean-diff", "2", "a.png", "b.png"},                // without --mc
        {"--noise", "b.png", "a.png", "b.png"},                    // without --mc
        {"--mc", "--tolerance", "2", "a.png", "b.png"},            // a pixel measure
        {"--mc", "--fail-above", "1", "a.png", "b.png"},           // a pixel measure
        {"--mc", "--scene", "s.json", "a.png", "b.png"},           // no pixel to trace
        {"--mc", "--noise-dir", "d", "a.png", "b.png"},            // two images take --noise
        {"--mc", "--noise", "a.png", "d", "d"},                    // folders take --noise-dir
        {"--mc", "--block", "0", "a.png", "b.png"},                // blocks of 1 pixel or more
        {"--mc", "--block-threshold", "256", "a.png", "b.png"},    // levels
        {"--mc", "--max-off-blocks", "101", "a.png", "b.png"},     // a percentage
        {"--mc", "--max-mean-diff", "-1", "a.png", "b.png"},       // levels
        {"--manifest", "m.tsv", "--noise", "a.png", "d"},          // manifests take --noise-dir
        {"--manifest", "m.tsv", "--mc", "--tolerance", "1", "d"},  // every scene by blocks
    };
    for (const std::vector<std::string>& args : cases) {
        const RunResult r = run(args);
        EXPECT_EQ(r.exit_code, 2) << args[0] << " " << args[1];
        EXPECT_EQ(r.err.rfind("error: ", 0), 0u) << r.err;
    }
    // A --noise-dir that is no folder is bad input.
    const RunResult r = run({"--mc", "--noise-dir", "nowhere", "d", "d"});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.err, "error: nowhere: not a folder\n");
}
