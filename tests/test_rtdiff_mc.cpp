// The Monte Carlo comparison of rt/image/block_diff.h on hand-made images whose block means
// are known (a block shifted, half a level everywhere, checkerboard noise, edge blocks), and
// its heatmap.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rt/image/block_diff.h"
#include "rt/image/image.h"
#include "rt/image/image_diff.h"
#include "rtdiff_test_support.h"

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
