// The samplers and adaptive sampling (docs/sampling.md): the patterns' stratification
// (hand-checkable counting properties), every sample uniform on its own, the samplers'
// pixel means agreeing within noise, determinism, a pixel's samples added in parts, and
// adaptive sampling's cap and target.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
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

// How many of the points `p` (each `dims` 32-bit fractions) fall in each box of the
// elementary shape that halves coordinate d bits[d] times.
std::vector<int> box_counts(const std::vector<std::vector<uint32_t>>& p, const std::vector<int>& bits) {
    int total = 0;
    for (int b : bits) total += b;
    std::vector<int> count(size_t(1) << total, 0);
    for (const auto& q : p) {
        size_t box = 0;
        for (size_t d = 0; d < bits.size(); ++d)
            if (bits[d] > 0) box = box << bits[d] | q[d] >> (32 - bits[d]);
        ++count[box];
    }
    return count;
}

// Every split of k bits among `dims` coordinates.
void each_shape(int dims, int k, std::vector<int>& bits, const std::function<void()>& f) {
    if (int(bits.size()) == dims - 1) {
        bits.push_back(k);
        f();
        bits.pop_back();
        return;
    }
    for (int b = 0; b <= k; ++b) {
        bits.push_back(b);
        each_shape(dims, k - b, bits, f);
        bits.pop_back();
    }
}

TEST(SamplePatterns, SobolHigherDimensionsFollowTheirRecurrences) {
    // By hand from the initial direction numbers (dimension 2: 1/2, 3/4; 3: 1/2, 3/4, 1/8;
    // 4: 1/2, 1/4, 1/8): point i is the XOR of those of i's set bits.
    const double want[3][5] = {{0, 0.5, 0.75, 0.25, 0.375}, {0, 0.5, 0.75, 0.25, 0.125}, {0, 0.5, 0.25, 0.75, 0.125}};
    for (int d = 2; d <= 4; ++d)
        for (uint32_t i = 0; i < 5; ++i) EXPECT_EQ(rt::sobol_higher(d, i) * 0x1p-32, want[d - 2][i]) << d << " " << i;
    // The first 2^k points of dimensions 0, 1 and 2 are a (1, k, 3)-net: two in every
    // elementary box of volume 2^(1-k), whatever its shape; each dimension alone one per
    // interval of 1/2^k.
    for (int k : {4, 6, 8}) {
        std::vector<std::vector<uint32_t>> p;
        for (uint32_t i = 0; i < (1u << k); ++i) {
            uint32_t a, b;
            rt::sobol2(i, a, b);
            p.push_back({a, b, rt::sobol_higher(2, i), rt::sobol_higher(3, i), rt::sobol_higher(4, i)});
        }
        std::vector<int> bits;
        std::vector<std::vector<uint32_t>> first3;
        for (const auto& q : p) first3.push_back({q[0], q[1], q[2]});
        each_shape(3, k - 1, bits, [&] {
            for (int c : box_counts(first3, bits)) EXPECT_EQ(c, 2) << k;
        });
        for (int d = 2; d <= 4; ++d) {
            std::vector<int> one(5, 0);
            one[size_t(d)] = k;
            for (int c : box_counts(p, one)) EXPECT_EQ(c, 1) << k << " " << d;
        }
    }
}

TEST(SamplePatterns, SobolCameraPointsAreStratifiedTogether) {
    // A pixel's first 2^k camera points (pixel, lens, time) under sobol: the pixel pair is
    // the pair next2 draws; pixel and time together a (1, k, 3)-net, as scrambling and
    // shuffling keep nets; every coordinate one per interval of 1/2^k.
    for (uint64_t pixel : {0u, 77u, 12345u})
        for (int k : {4, 7}) {
            std::vector<std::vector<uint32_t>> pixel_time, all;
            for (uint32_t i = 0; i < (1u << k); ++i) {
                rt::SampleStream s(SamplerKind::Sobol, 9, pixel, i, 1u << k), t = s;
                Real u[5], a, b;
                s.sobol_point(u, 5);
                t.next2(a, b);
                EXPECT_EQ(u[0], a);
                EXPECT_EQ(u[1], b);
                std::vector<uint32_t> q;
                for (Real v : u) q.push_back(uint32_t(double(v) * 0x1p32));
                all.push_back(q);
                // Time is the third number when the camera has no lens.
                rt::SampleStream r(SamplerKind::Sobol, 9, pixel, i, 1u << k);
                r.sobol_point(u, 3);
                pixel_time.push_back({uint32_t(double(u[0]) * 0x1p32), uint32_t(double(u[1]) * 0x1p32),
                                      uint32_t(double(u[2]) * 0x1p32)});
            }
            std::vector<int> bits;
            each_shape(3, k - 1, bits, [&] {
                for (int c : box_counts(pixel_time, bits)) EXPECT_EQ(c, 2) << pixel << " " << k;
            });
            for (int d = 0; d < 5; ++d) {
                std::vector<int> one(5, 0);
                one[size_t(d)] = k;
                for (int c : box_counts(all, one)) EXPECT_EQ(c, 1) << pixel << " " << k << " " << d;
            }
        }
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
    // 16: the pixel grid; 12: none, Sobol's camera numbers one joint point.
    for (const char* count : {"16", "12"}) {
        json j = everything();
        j["Scene"]["Cameras"]["Camera"]["NumSamples"] = count;
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

rt::Vec3 rgb(double r, double g, double b) { return rt::Vec3{Real(r), Real(g), Real(b)}; }

TEST(AdaptiveSampling, EstimatesFromSamplesOrFromBlocksOfSobolPoints) {
    // 8 samples, red 0, 10, 0, 10, ...: independent samples' variance (400 - 40^2 / 8) / 7,
    // over 8; Sobol's blocks of 2 all sum to 10: no spread.
    rt::PixelSum alternating;
    for (int k = 0; k < 8; ++k) alternating.add(rgb(k % 2 ? 10 : 0, 5, 300), true);
    EXPECT_NEAR(alternating.standard_error(false), std::sqrt(200.0 / 7 / 8), 1e-12);
    EXPECT_NEAR(alternating.standard_error(true), 0, 1e-12);
    // Red 0, 0, 10, 10, ...: blocks of 2 sum to 0, 20, 0, 20, their means 0, 10, 0, 10:
    // variance 100 / 3, over 4 blocks.
    rt::PixelSum pairs;
    for (int k = 0; k < 8; ++k) pairs.add(rgb(k % 4 < 2 ? 0 : 10, 5, 300), true);
    EXPECT_NEAR(pairs.standard_error(false), std::sqrt(200.0 / 7 / 8), 1e-12);
    EXPECT_NEAR(pairs.standard_error(true), std::sqrt(100.0 / 3 / 4), 1e-12);
    // 24 samples: blocks of 4 (6 of them); 40: blocks of 8 (5). Red 0 in the first half
    // of each block of 8, 10 in the second: blocks of 4 alternate 0 and 10 (variance 30
    // over 6, its mean 5: (6 * 25 + ...) = 150 / 5 = 30); blocks of 8 all mean 5.
    rt::PixelSum halves;
    for (int k = 0; k < 24; ++k) halves.add(rgb(k % 8 < 4 ? 0 : 10, 5, 5), true);
    EXPECT_NEAR(halves.standard_error(true), std::sqrt(30.0 / 6), 1e-12);
    for (int k = 24; k < 40; ++k) halves.add(rgb(k % 8 < 4 ? 0 : 10, 5, 5), true);
    EXPECT_NEAR(halves.standard_error(true), 0, 1e-12);
    // Below two samples nothing is known; clamped values above 255 do not vary.
    rt::PixelSum one;
    one.add(rgb(1, 2, 3), true);
    EXPECT_TRUE(std::isinf(one.standard_error(true)));
    // Without noise sums (a fixed count) only the radiance is summed.
    rt::PixelSum plain;
    plain.add(rgb(1, 2, 3), false);
    EXPECT_EQ(plain.n, 1);
    EXPECT_EQ(plain.squares[0], 0);
}

TEST(AdaptiveSampling, FirstSamplesAPowerOfTwoFrom4To32UpToASixthOfTheCount) {
    EXPECT_EQ(rt::adaptive_first(0), 4);
    EXPECT_EQ(rt::adaptive_first(36), 4);
    EXPECT_EQ(rt::adaptive_first(47), 4);
    EXPECT_EQ(rt::adaptive_first(48), 8);
    EXPECT_EQ(rt::adaptive_first(95), 8);
    EXPECT_EQ(rt::adaptive_first(96), 16);
    EXPECT_EQ(rt::adaptive_first(100), 16);
    EXPECT_EQ(rt::adaptive_first(192), 32);
    EXPECT_EQ(rt::adaptive_first(900), 32);
}

TEST(AdaptiveSampling, APixelIsJudgedByItsOwnNoiseOrItsNeighbours) {
    // A 3 x 2 region: per-sample noise 8 at (1, 0), 4 at (2, 1), 0 elsewhere.
    const double noise[6] = {0, 8, 0, 0, 0, 4};
    // (0, 0): neighbours (1, 0), (0, 1), (1, 1): mean 8 / 3.
    EXPECT_DOUBLE_EQ(rt::judged_noise(noise, 3, 2, 0, 0), rt::kNeighbourShare * 8 / 3);
    // (1, 0): its own 8 against its five neighbours' mean 4 / 5.
    EXPECT_DOUBLE_EQ(rt::judged_noise(noise, 3, 2, 1, 0), std::max(8.0, rt::kNeighbourShare * 4 / 5));
    // (2, 1): its own 4 against (1, 0), (2, 0), (1, 1): 8 / 3.
    EXPECT_DOUBLE_EQ(rt::judged_noise(noise, 3, 2, 2, 1), std::max(4.0, rt::kNeighbourShare * 8 / 3));
    // A region of one pixel: its own.
    EXPECT_DOUBLE_EQ(rt::judged_noise(noise + 1, 1, 1, 0, 0), 8);
}

TEST(AdaptiveSampling, HonoursItsCapAndItsTarget) {
    // Each region replayed pass by pass from the rule: every pixel takes its first
    // samples (adaptive_first); then, each pass, every pixel under the cap whose judged noise (over the
    // region as the pass starts) is above the target takes kPacket more, until a pass
    // adds none. The render's counts are the replay's, and at the end every pixel under
    // the cap meets the target.
    const rt::Scene s = build(everything());
    const rt::Camera& cam = s.setup.cameras[0];
    const double target = 2;
    const int cap = 100;
    for (SamplerKind kind : kAll) {
        rt::SamplingOptions o;
        o.sampler = kind;
        o.noise_target = target;
        o.max_samples = cap;
        const rt::PixelSampling ps = rt::pixel_sampling(s, 0, o);
        ASSERT_EQ(ps.max_samples, cap);
        ASSERT_EQ(ps.first, rt::adaptive_first(8));
        rt::TraceCache cache;
        int at_cap = 0, early = 0, by_neighbours = 0;
        for (int y0 = 0; y0 < cam.height; y0 += rt::kAdaptiveRegion)
            for (int x0 = 0; x0 < cam.width; x0 += rt::kAdaptiveRegion) {
                const int w = std::min(rt::kAdaptiveRegion, cam.width - x0);
                const int h = std::min(rt::kAdaptiveRegion, cam.height - y0);
                std::vector<rt::PixelValue> v(static_cast<size_t>(w * h));
                rt::sample_region(s, cam, ps, x0, y0, x0 + w, y0 + h, {}, &cache, v.data());
                // Per-sample noise of every pixel at counts n.
                const auto noise_of = [&](const std::vector<int>& n) {
                    std::vector<double> noise;
                    for (int i = 0; i < w * h; ++i) {
                        rt::PixelSum acc;
                        rt::add_samples(s, cam, ps, x0 + i % w, y0 + i / w, 0, n[size_t(i)], {}, &cache, acc);
                        const double e = acc.standard_error(kind == SamplerKind::Sobol);
                        noise.push_back(e * e * acc.n);
                    }
                    return noise;
                };
                std::vector<int> n(static_cast<size_t>(w * h), ps.first);
                std::vector<double> noise;
                for (bool more = true; more;) {
                    noise = noise_of(n);
                    more = false;
                    for (int i = 0; i < w * h; ++i)
                        if (n[size_t(i)] < cap &&
                            rt::judged_noise(noise.data(), w, h, i % w, i / w) > target * target * n[size_t(i)]) {
                            n[size_t(i)] = std::min(cap, n[size_t(i)] + rt::kPacket);
                            more = true;
                        }
                }
                for (int i = 0; i < w * h; ++i) {
                    ASSERT_EQ(v[size_t(i)].samples, n[size_t(i)]) << rt::sampler_name(kind) << " pixel " << i;
                    if (n[size_t(i)] == cap) {
                        ++at_cap;
                        continue;
                    }
                    ++early;
                    EXPECT_LE(noise[size_t(i)], target * target * n[size_t(i)]);
                    if (n[size_t(i)] > ps.first &&
                        rt::judged_noise(noise.data(), w, h, i % w, i / w) > noise[size_t(i)])
                        ++by_neighbours;
                }
            }
        // The scene has both flat pixels and noisy ones: the test sees both ends, and
        // pixels whose neighbours' noise counted.
        EXPECT_GT(at_cap, 0) << rt::sampler_name(kind);
        EXPECT_GT(early, 0) << rt::sampler_name(kind);
        EXPECT_GT(by_neighbours, 0) << rt::sampler_name(kind);
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
    // A pixel alone (--trace) is its region's computation: the render's value and count.
    const rt::PixelSampling ps = rt::pixel_sampling(s, 0, o.sampling);
    const rt::Camera& cam = s.setup.cameras[0];
    rt::TraceCache cache;
    for (const auto& [x, y] : {std::pair{0, 0}, std::pair{cam.width - 1, cam.height - 1}, std::pair{17, 5}}) {
        const rt::PixelValue v = rt::sample_pixel_adaptive(s, cam, ps, x, y, {}, &cache);
        const size_t i = static_cast<size_t>(y) * cam.width + x;
        EXPECT_EQ(uint32_t(v.samples), one.pixel_samples[i]);
        EXPECT_EQ(rt::quantize(v.radiance.x, o.rounding), a.rgb[3 * i]);
    }
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
