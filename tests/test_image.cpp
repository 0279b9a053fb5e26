// PNG writing (src/image/): every image rt::write_png writes decodes (stb_image, as
// load_png reads the renders) to exactly the pixels it was given, whatever compresses
// its zlib stream (libdeflate, or stb's own with RT_NO_LIBDEFLATE).
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <thread>

#include "rt/image/image.h"
#include "test_support.h"

namespace {

rt::Image blank(int width, int height) {
    rt::Image img;
    img.width = width;
    img.height = height;
    img.rgb.assign(size_t(width) * size_t(height) * 3, 0);
    return img;
}

rt::Image random_pixels(int width, int height, uint32_t seed) {
    rt::Image img = blank(width, height);
    std::mt19937 rng(seed);
    for (uint8_t& v : img.rgb) v = static_cast<uint8_t>(rng() >> 24);
    return img;
}

rt::Image flat(int width, int height, uint8_t r, uint8_t g, uint8_t b) {
    rt::Image img = blank(width, height);
    for (size_t i = 0; i < img.rgb.size(); i += 3) {
        img.rgb[i] = r;
        img.rgb[i + 1] = g;
        img.rgb[i + 2] = b;
    }
    return img;
}

// Red along x, green along y, blue along the diagonal: every row differs from the last.
rt::Image gradient(int width, int height) {
    rt::Image img = blank(width, height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            uint8_t* p = &img.rgb[(size_t(y) * size_t(width) + size_t(x)) * 3];
            p[0] = static_cast<uint8_t>(x * 255 / (width > 1 ? width - 1 : 1));
            p[1] = static_cast<uint8_t>(y * 255 / (height > 1 ? height - 1 : 1));
            p[2] = static_cast<uint8_t>((x + y) & 0xff);
        }
    return img;
}

// Writes `img` as PNG into `dir` and reads it back; the pixels must come back unchanged.
void expect_round_trip(const rt::Image& img, const TempDir& dir, const std::string& name) {
    const std::string path = dir / (name + ".png");
    rt::write_png(img, path);
    const std::string bytes = read_text(path);
    ASSERT_GE(bytes.size(), 8u) << name;
    EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << name;
    rt::Image back;
    ASSERT_TRUE(load_png(path, back)) << name;
    EXPECT_EQ(back.width, img.width) << name;
    EXPECT_EQ(back.height, img.height) << name;
    EXPECT_TRUE(back.rgb == img.rgb) << name << ": the decoded pixels differ";
}

}  // namespace

TEST(PngWriter, RandomPixelsRoundTrip) {
    TempDir dir;
    const int sizes[][2] = {{1, 1}, {1, 17}, {23, 1}, {37, 19}, {101, 63}, {256, 255}};
    uint32_t seed = 1;
    for (const auto& s : sizes)
        expect_round_trip(random_pixels(s[0], s[1], seed++), dir,
                          "random_" + std::to_string(s[0]) + "x" + std::to_string(s[1]));
}

TEST(PngWriter, FlatColourRoundTrip) {
    TempDir dir;
    expect_round_trip(flat(1, 1, 0, 0, 0), dir, "flat_black_1x1");
    expect_round_trip(flat(1, 300, 255, 255, 255), dir, "flat_white_1x300");
    expect_round_trip(flat(333, 3, 12, 200, 77), dir, "flat_333x3");
    expect_round_trip(flat(640, 480, 128, 64, 255), dir, "flat_640x480");
}

TEST(PngWriter, GradientRoundTrip) {
    TempDir dir;
    expect_round_trip(gradient(1, 255), dir, "gradient_1x255");
    expect_round_trip(gradient(255, 1), dir, "gradient_255x1");
    expect_round_trip(gradient(99, 77), dir, "gradient_99x77");
    expect_round_trip(gradient(800, 600), dir, "gradient_800x600");
}

// Images written one after another from different threads (the compressor may be kept
// per thread between images): each still decodes to its own pixels.
TEST(PngWriter, SuccessiveImagesAndThreads) {
    TempDir dir;
    expect_round_trip(gradient(64, 48), dir, "a");
    expect_round_trip(random_pixels(65, 49, 7), dir, "b");
    std::thread other([&dir] { expect_round_trip(random_pixels(31, 33, 8), dir, "c"); });
    other.join();
    expect_round_trip(flat(17, 5, 1, 2, 3), dir, "d");
}
