// Block comparison of Monte Carlo renders (rt/image/block_diff.h). Sums are whole numbers
// of levels, so a block is off by an exact test (|sum| > threshold * pixels).
#include "rt/image/block_diff.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>

namespace rt {

double BlockComparison::max_channel_bias() const {
    return std::max({std::abs(mean_diff[0]), std::abs(mean_diff[1]), std::abs(mean_diff[2])});
}

BlockComparison compare_blocks(const Image& a, const Image& b, int block, int threshold) {
    BlockComparison r;
    r.width = a.width;
    r.height = a.height;
    r.block = std::max(block, 1);
    r.threshold = std::max(threshold, 0);
    const auto well_formed = [](const Image& img) {
        return img.width >= 0 && img.height >= 0 && img.rgb.size() == size_t(img.width) * size_t(img.height) * 3;
    };
    if (a.width != b.width || a.height != b.height || !well_formed(a) || !well_formed(b)) {
        r.same_size = false;
        return r;
    }
    const int n = r.block, w = a.width, h = a.height;
    r.blocks_x = (w + n - 1) / n;
    r.blocks_y = (h + n - 1) / n;
    r.blocks = size_t(r.blocks_x) * size_t(r.blocks_y);
    r.block_diff.reserve(r.blocks);
    int64_t total[3] = {0, 0, 0};
    double sum_sq = 0;
    std::vector<int64_t> sums(size_t(r.blocks_x) * 3);  // one row of blocks, per channel
    for (int by = 0; by < r.blocks_y; ++by) {
        std::fill(sums.begin(), sums.end(), 0);
        const int y1 = std::min(h, (by + 1) * n);
        for (int y = by * n; y < y1; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t p = (size_t(y) * size_t(w) + size_t(x)) * 3;
                for (size_t c = 0; c < 3; ++c) {
                    const int d = int(a.rgb[p + c]) - int(b.rgb[p + c]);
                    sums[size_t(x / n) * 3 + c] += d;
                    total[c] += d;
                    sum_sq += double(d) * d;
                }
            }
        for (int bx = 0; bx < r.blocks_x; ++bx) {
            const int64_t pixels = int64_t(std::min(w, (bx + 1) * n) - bx * n) * (y1 - by * n);
            int64_t worst = 0;
            for (size_t c = 0; c < 3; ++c) worst = std::max(worst, std::abs(sums[size_t(bx) * 3 + c]));
            if (worst > int64_t(r.threshold) * pixels) ++r.blocks_off;
            const int diff = int((worst + pixels - 1) / pixels);  // rounded up
            r.block_diff.push_back(diff);
            r.max_block_diff = std::max(r.max_block_diff, diff);
        }
    }
    const double count = double(w) * double(h);
    if (count == 0) {
        r.psnr = std::numeric_limits<double>::infinity();
        return r;
    }
    r.pct_off = 100.0 * double(r.blocks_off) / double(r.blocks);
    for (size_t c = 0; c < 3; ++c) r.mean_diff[c] = double(total[c]) / count;
    r.mean_diff_all = double(total[0] + total[1] + total[2]) / (3 * count);
    const double mse = sum_sq / (3 * count);
    r.rmse = std::sqrt(mse);
    // As compare_images computes it, so that both modes print one PSNR for a pair.
    r.psnr = mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
    return r;
}

}  // namespace rt
