// Comparing two Monte Carlo renders (many random samples per pixel, assignment 3): pixel
// by pixel they differ by their sampling noise; a bias shows in the means over blocks of
// pixels. The figures rtdiff --mc prints (docs/rtdiff.md) and its heatmap of the blocks.
#pragma once
#include <cstddef>
#include <vector>

#include "rt/image/image.h"

namespace rt {

// The block comparison of image A with image B. Differences are A - B, in levels (0..255).
struct BlockComparison {
    bool same_size = true;      // false: sizes differ (or an image is malformed), nothing measured
    int width = 0, height = 0;  // A's size
    int block = 16;             // blocks of block x block pixels from the top left; those at the
                                // right and bottom edges hold the pixels there are
    int threshold = 3;          // a block is off when some channel's block mean differs by more
    int blocks_x = 0, blocks_y = 0;
    size_t blocks = 0;      // blocks_x * blocks_y
    size_t blocks_off = 0;  // blocks with some channel's mean off by more than `threshold`
    double pct_off = 0;     // blocks_off as a percentage of blocks
    // Per block, in reading order: the largest channel's |difference of the block means|
    // rounded up to a whole level, so that a block is off exactly when it exceeds `threshold`.
    std::vector<int> block_diff;
    int max_block_diff = 0;           // the largest of block_diff
    double mean_diff[3] = {0, 0, 0};  // mean signed difference per channel (R, G, B)
    double mean_diff_all = 0;         // mean signed difference over every channel value
    double rmse = 0;                  // root mean square difference over every channel value
    double psnr = 0;                  // from rmse, dB; +inf when identical
    double max_channel_bias() const;  // the largest |mean_diff| of the three channels
};

// Compares `a` with `b` by the means of their `block` x `block` blocks (block >= 1) at
// `threshold` levels (>= 0), and pixel by pixel for RMSE and PSNR.
BlockComparison compare_blocks(const Image& a, const Image& b, int block = 16, int threshold = 3);

// A heatmap of the blocks, as diff_heatmap's of pixels (rt/image/image_diff.h): each pixel
// coloured by its block's block_diff at c's threshold (grey where the block means are
// equal, a's luminance dimmed; blue within the threshold; yellow to red over it). `c` is
// compare_blocks(a, b, ...), same_size.
Image block_heatmap(const Image& a, const BlockComparison& c);

// block_heatmap with its legend strip (add_heatmap_legend for blocks), as rtdiff writes it.
Image block_heatmap_with_legend(const Image& a, const BlockComparison& c);

}  // namespace rt
