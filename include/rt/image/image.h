// 8-bit RGB images and how floating-point radiance becomes one.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "rt/core/math.h"

namespace rt {

// spec 2.7 says "clamp, then round"; the reference images truncate
// (reference-conventions.md, "Output"), so truncation is the default.
enum class Rounding { Truncate, Nearest };

struct Image {
    int width = 0, height = 0;
    std::vector<uint8_t> rgb;  // row-major, top row first, 3 bytes per pixel
};

// A channel clamped to [0, 255]; NaN becomes 0.
inline Real clamp_channel(Real value) {
    if (!(value > 0)) return 0;  // negative and NaN
    return value >= 255 ? Real(255) : value;
}

// clamp_channel, then to an integer as `rounding` says: the one conversion of radiance
// to an 8-bit channel (images and --trace). Inline: three per pixel.
inline uint8_t quantize(Real value, Rounding rounding) {
    const Real c = clamp_channel(value);
    return static_cast<uint8_t>(rounding == Rounding::Nearest ? std::floor(c + Real(0.5)) : c);
}

// Writes a PNG atomically (write_file_atomic, rt/io/atomic_file.h): to a temporary name
// beside `path`, then renamed over it, so a failure never leaves a half-written image. Throws rt::InputError naming
// `path`.
void write_png(const Image& image, const std::string& path);

// Binary PPM (P6, maxval 255), written atomically like write_png.
void write_ppm(const Image& image, const std::string& path);

enum class ImageFormat { Png, Ppm, Unknown };

// The format an image name asks for, by its extension (case-insensitive):
// ".png" or ".ppm"; anything else is Unknown.
ImageFormat image_format_of(const std::string& path);

// write_png or write_ppm as the name's extension asks; throws rt::InputError
// naming `path` for any other extension.
void write_image(const Image& image, const std::string& path);

}  // namespace rt
