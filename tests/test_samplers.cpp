// The samplers and adaptive sampling (docs/sampling.md): the patterns' stratification
// (hand-checkable counting properties), every sample uniform on its own, the samplers'
// pixel means agreeing within noise, determinism, a pixel's samples added in parts, and
// adaptive sampling's cap and target.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "distribution_test_support.h"
#include "rt/core/random.h"
#include "rt/core/sample_patterns.h"
#include "rt/geometry/traverse.h"
#include "rt/render/render.h"
#include "rt/shading/pixel_samples.h"

namespace {

using distribution_test::build;
using distribution_test::everything;
using distribution_test::json;
using rt::Real;
using rt::SamplerKind;

const SamplerKind kPatterned[] = {SamplerKind::Stratified, SamplerKind::Sobol};
const SamplerKind kAll[] = {SamplerKind::Random, SamplerKind::Stratified, SamplerKind::Sobol};

// Pair `pair` (0-based) of the first `n` samples of a pixel.
std::vector<std::pair<Real, Real>> points(SamplerKind kind, uint64_t pixel, int n, int pair, uint64_t seed = 1) {
    std::vector<std::pair<Real, Real>> out;
    for (int k = 0; k < n; ++k) {
        rt::SampleStream s(kind, seed, pixel, uint32_t(k), uint32_t(n));
        Real a = 0, b = 0;
        for (int i = 0; i <= pair; ++i) s.next2(a, b);
        out.emplace_back(a, b);
    }
    return out;
}

// How many of `p` fall in each of the cols x rows cells of the unit square.
std::vector<int> cell_counts(const std::vector<std::pair<Real, Real>>& p, int cols, int rows) {
    std::vector<int> count(size_t(cols * rows), 0);
    for (const auto& [a, b] : p) {
        EXPECT_GE(a, 0);
        EXPECT_LT(a, 1);
        EXPECT_GE(b, 0);
        EXPECT_LT(b, 1);
        ++count[size_t(int(b * rows) * cols + int(a * cols))];
    }
    return count;
}

TEST(SamplePatterns, PermuteIndexIsABijection) {
    for (uint32_t n : {1u, 2u, 3u, 7u, 16u, 100u, 129u, 1000u})
        for (uint32_t seed : {0u, 1u, 0xdeadbeefu}) {
            std::set<uint32_t> seen;
            for (uint32_t i = 0; i < n; ++i) seen.insert(rt::permute_index(i, n, seed));
            EXPECT_EQ(seen.size(), n) << n;
            EXPECT_LT(*seen.rbegin(), n);
        }
}

TEST(SamplePatterns, SobolSecondDimensionIsItsDirectionNumbersXored) {
    // Bit by bit from the recurrence v_0 = 2^31, v_j+1 = v_j ^ v_j >> 1: the table's sum.
    for (uint32_t i : {0u, 1u, 2u, 3u, 255u, 256u, 0x12345678u, 0xffffffffu}) {
        uint32_t want = 0, v = 0x80000000u;
        for (uint32_t k = i; k; k >>= 1, v ^= v >> 1)
            if (k & 1u) want ^= v;
        uint32_t a, b;
        rt::sobol2(i, a, b);
        EXPECT_EQ(b, want) << i;
        EXPECT_EQ(a, rt::reverse_bits(i));
    }
    // The first points by hand: (0, 0), (1/2, 1/2), (1/4, 3/4), (3/4, 1/4).
    const uint32_t want_b[] = {0u, 0x80000000u, 0xc0000000u, 0x40000000u};
    for (uint32_t i = 0; i < 4; ++i) {
        uint32_t a, b;
        rt::sobol2(i, a, b);
        EXPECT_EQ(b, want_b[i]) << i;
    }
}

TEST(SamplePatterns, ScrambledSobolIsTheCompositionOfItsParts) {
    for (uint32_t t = 0; t < 20000; ++t) {
        const uint32_t i = t % 977, shuffle = t * 2654435761u, sa = t * 0x85ebca6bu + 7, sb = ~t * 0xc2b2ae35u;
        uint32_t x, y, a, b;
        rt::sobol2(rt::nested_scramble(i, shuffle), x, y);
        rt::scrambled_sobol2(i, shuffle, sa, sb, a, b);
        ASSERT_EQ(a, rt::nested_scramble(x, sa)) << t;
        ASSERT_EQ(b, rt::nested_scramble(y, sb)) << t;
    }
}

TEST(SamplePatterns, SobolPrefixesAreNetsInEveryPairAndPixel) {
    // 16 points: one in each of the 16 cells of every elementary shape (1x16, 2x8, 4x4,
    // 8x2, 16x1): a (0, 4, 2)-net, which scrambling and shuffling keep.
    for (uint64_t pixel : {0u, 77u, 12345u})
        for (int pair : {0, 1, 5}) {
            const auto p = points(SamplerKind::Sobol, pixel, 16, pair);
            for (int cols = 1; cols <= 16; cols *= 2)
                for (int c : cell_counts(p, cols, 16 / cols)) EXPECT_EQ(c, 1) << pixel << " " << pair << " " << cols;
        }
    // Pairs are decorrelated: another pair's points are not the same.
    EXPECT_NE(points(SamplerKind::Sobol, 3, 16, 0), points(SamplerKind::Sobol, 3, 16, 1));
}

TEST(SamplePatterns, StratifiedIsOnePerCellAndPerRowAndColumnOfTheFineGrid) {
    for (int n : {16, 36, 100})
        for (int pair : {0, 2}) {
            const int m = int(std::lround(std::sqrt(n)));
            const auto p = points(SamplerKind::Stratified, 9, n, pair);
            for (int c : cell_counts(p, m, m)) EXPECT_EQ(c, 1) << n;
            for (int c : cell_counts(p, n, 1)) EXPECT_EQ(c, 1) << n;
            for (int c : cell_counts(p, 1, n)) EXPECT_EQ(c, 1) << n;
        }
    // 12 = 4 x 3: one per cell of the 4 x 3 grid.
    for (int c : cell_counts(points(SamplerKind::Stratified, 9, 12, 0), 4, 3)) EXPECT_EQ(c, 1);
}

TEST(SamplePatterns, RandomDrawsTheNumbersOfItsStreamInPairs) {
    // next2 is two next(): the default sampler's images are those of before it existed.
    rt::SampleStream a(5, 6, 7), b(5, 6, 7);
    Real x, y;
    a.next2(x, y);
    EXPECT_EQ(x, b.next());
    EXPECT_EQ(y, b.next());
    rt::SampleStream c(SamplerKind::Random, 5, 6, 7, 100);
    EXPECT_EQ(c.next(), rt::SampleStream(5, 6, 7).next());
}

TEST(SamplePatterns, EverySampleIsUniformOnItsOwn) {
    // Over many pixels, each sample index's numbers fill 8 bins evenly (chi-square,
    // 7 degrees of freedom: 30 is beyond its 0.9999 quantile).
    for (SamplerKind kind : kAll)
        for (int n : {5, 16}) {
            std::vector<int> bins(8, 0);
            const int pixels = 4000;
            for (int p = 0; p < pixels; ++p) {
                rt::SampleStream s(kind, 3, uint64_t(p), uint32_t(p % n), uint32_t(n));
                Real a, b;
                s.next2(a, b);
                ++bins[size_t(a * 8)];
                ++bins[size_t(b * 8)];
            }
            double chi2 = 0;
            const double expect = 2.0 * pixels / 8;
            for (int c : bins) chi2 += (c - expect) * (c - expect) / expect;
            EXPECT_LT(chi2, 30) << rt::sampler_name(kind) << " n " << n;
        }
}

// Each pixel's radiance (sum of channels) under `o`.
std::vector<double> pixel_means(const rt::Scene& s, const rt::SamplingOptions& o) {
    const rt::Camera& cam = s.setup.cameras[0];
    const rt::PixelSampling ps = rt::pixel_sampling(s, 0, o);
    rt::TraceCache cache;
    std::vector<double> out;
    for (int y = 0; y < cam.height; ++y)
        for (int x = 0; x < cam.width; ++x) {
            const rt::Vec3 v = rt::sample_pixel(s, cam, ps, x, y, {}, &cache).radiance;
            out.push_back(double(v.x + v.y + v.z));
        }
    return out;
}

TEST(Samplers, PatternsMeansAgreeWithRandomsWithinNoise) {
    json j = everything();
    j["Scene"]["Cameras"]["Camera"]["NumSamples"] = "16";
    const rt::Scene s = build(j);
    rt::SamplingOptions o;
    o.sampler = SamplerKind::Random;
    const std::vector<double> base = pixel_means(s, o);
    for (SamplerKind kind : kPatterned) {
        o.sampler = kind;
        const std::vector<double> other = pixel_means(s, o);
        ASSERT_EQ(other.size(), base.size());
        // The mean over the image of the pixels' differences, against its standard error
        // (pixels' noise is independent).
        double sum = 0, squares = 0;
        for (size_t i = 0; i < base.size(); ++i) {
            const double d = other[i] - base[i];
            sum += d;
            squares += d * d;
        }
        const double n = double(base.size()), mean = sum / n;
        const double se = std::sqrt((squares / n - mean * mean) / (n - 1));
        EXPECT_GT(se, 0) << "the samplers gave the same image: the test shows nothing";
        EXPECT_LT(std::abs(mean), 4 * se + 1e-9) << rt::sampler_name(kind) << ": mean " << mean << ", se " << se;
        EXPECT_NE(other, base) << rt::sampler_name(kind);
    }
}

TEST(Samplers, SameBytesForAnyThreadCountAndSeedChangesNoise) {
    const rt::Scene s = build(everything());
    for (SamplerKind kind : kPatterned) {
        rt::RenderOptions o;
        o.sampling.sampler = kind;
        o.threads = 1;
        const rt::Image one = rt::render(s, 0, o);
        o.threads = 3;
        EXPECT_EQ(rt::render(s, 0, o).rgb, one.rgb) << rt::sampler_name(kind);
        o.sampling.seed = 99;
        EXPECT_NE(rt::render(s, 0, o).rgb, one.rgb) << rt::sampler_name(kind);
    }
}

TEST(PixelSamples, AddedInPartsAreTheWhole) {
    const rt::Scene s = build(everything());
    const rt::Camera& cam = s.setup.cameras[0];
    for (SamplerKind kind : kAll) {
        rt::SamplingOptions o;
        o.sampler = kind;
        rt::PixelSampling ps = rt::pixel_sampling(s, 0, o);
        ps.samples = 40;
        rt::TraceCache cache;
        rt::PixelSum whole, parts;
        rt::add_samples(s, cam, ps, 7, 9, 0, 40, {}, &cache, whole);
        for (int k = 0; k < 40; k += rt::kPacket)
            rt::add_samples(s, cam, ps, 7, 9, k, std::min(40, k + rt::kPacket), {}, &cache, parts);
        EXPECT_EQ(parts.n, 40);
        EXPECT_EQ(parts.sum.x, whole.sum.x);
        EXPECT_EQ(parts.sum.y, whole.sum.y);
        EXPECT_EQ(parts.sum.z, whole.sum.z);
        EXPECT_EQ(parts.squares[1], whole.squares[1]);
    }
}

TEST(AdaptiveSampling, HonoursItsCapAndItsTarget) {
    const rt::Scene s = build(everything());
    const rt::Camera& cam = s.setup.cameras[0];
    for (SamplerKind kind : kAll) {
        rt::SamplingOptions o;
        o.sampler = kind;
        o.noise_target = 2;
        o.max_samples = 100;
        const rt::PixelSampling ps = rt::pixel_sampling(s, 0, o);
        ASSERT_EQ(ps.max_samples, 100);
        rt::TraceCache cache;
        int at_cap = 0, early = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const rt::PixelValue v = rt::sample_pixel(s, cam, ps, x, y, {}, &cache);
                ASSERT_GE(v.samples, rt::kAdaptiveFirst);
                ASSERT_TRUE(v.samples == 100 || (v.samples - rt::kAdaptiveFirst) % rt::kPacket == 0) << v.samples;
                ASSERT_LE(v.samples, 100);
                if (v.samples == 100) {
                    ++at_cap;
                    continue;
                }
                ++early;
                // Stopped early: its estimate met the target, and one packet fewer did not.
                rt::PixelSum acc;
                rt::add_samples(s, cam, ps, x, y, 0, v.samples, {}, &cache, acc);
                EXPECT_LE(acc.standard_error(), 2);
                if (v.samples > rt::kAdaptiveFirst) {
                    rt::PixelSum before;
                    rt::add_samples(s, cam, ps, x, y, 0, v.samples - rt::kPacket, {}, &cache, before);
                    EXPECT_GT(before.standard_error(), 2);
                }
            }
        // The scene has both flat pixels and noisy ones: the test sees both ends.
        EXPECT_GT(at_cap, 0) << rt::sampler_name(kind);
        EXPECT_GT(early, 0) << rt::sampler_name(kind);
    }
}

TEST(AdaptiveSampling, DeterministicAndCountsEverySample) {
    const rt::Scene s = build(everything());
    rt::RenderOptions o;
    o.sampling.sampler = SamplerKind::Sobol;
    o.sampling.noise_target = 3;
    o.count_samples = true;
    o.threads = 1;
    rt::RenderStats one, three;
    const rt::Image a = rt::render(s, 0, o, &one);
    o.threads = 3;
    EXPECT_EQ(rt::render(s, 0, o, &three).rgb, a.rgb);
    EXPECT_EQ(three.pixel_samples, one.pixel_samples);
    uint64_t sum = 0;
    for (uint32_t n : one.pixel_samples) sum += n;
    EXPECT_EQ(sum, one.samples);
    EXPECT_EQ(one.rays.camera, one.samples);
    // The default cap: kAdaptiveCapFactor times the scene's 8.
    EXPECT_EQ(*std::max_element(one.pixel_samples.begin(), one.pixel_samples.end()),
              uint32_t(rt::kAdaptiveCapFactor * 8));
}

TEST(AdaptiveSampling, NothingRandomIsTheCentreRay) {
    // Without samples, lens, motion, area light or roughness, a noise target changes nothing.
    const rt::Scene s = build(loader_test::sample());
    rt::RenderOptions o;
    const rt::Image plain = rt::render(s, 0, o);
    o.sampling.noise_target = 1;
    EXPECT_EQ(rt::pixel_sampling(s, 0, o.sampling).noise_target, 0);
    EXPECT_EQ(rt::render(s, 0, o).rgb, plain.rgb);
}

}  // namespace
