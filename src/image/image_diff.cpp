// Image comparison (rt/image/image_diff.h): one measure for ./rtdiff and the conformance tests.
#include "rt/image/image_diff.h"

#include <stb/stb_image.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>

#include "rt/core/error.h"

namespace rt {

namespace {

bool well_formed(const Image& img) {
    return img.width >= 0 && img.height >= 0 && img.rgb.size() == size_t(img.width) * size_t(img.height) * 3;
}

int channel_diff(const Image& a, const Image& b, size_t i) { return std::abs(int(a.rgb[i]) - int(b.rgb[i])); }

}  // namespace

std::string psnr_text(double psnr) {
    if (std::isinf(psnr)) return "inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.2f dB", psnr);
    return buf;
}

std::string box_text(const ImageComparison& c) {
    if (c.box_empty()) return "none";
    char buf[96];
    std::snprintf(buf, sizeof buf, "x %d..%d y %d..%d", c.box_x0, c.box_x1, c.box_y0, c.box_y1);
    return buf;
}

ImageComparison compare_images(const Image& a, const Image& b, int tolerance) {
    ImageComparison d;
    d.width = a.width;
    d.height = a.height;
    d.tolerance = tolerance;
    d.pixels = size_t(std::max(a.width, 0)) * size_t(std::max(a.height, 0));
    if (a.width != b.width || a.height != b.height || !well_formed(a) || !well_formed(b)) {
        d.same_size = false;
        d.max_diff = 256;
        d.mean_diff = 255;
        d.pixels_over = d.pixels;
        d.pct_over = 100;
        d.psnr = 0;
        d.box_x0 = d.box_y0 = 0;
        d.box_x1 = a.width - 1;
        d.box_y1 = a.height - 1;
        return d;
    }
    if (d.pixels == 0) {
        d.psnr = std::numeric_limits<double>::infinity();
        return d;
    }
    double sum = 0, sum_sq = 0;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            const size_t p = (size_t(y) * size_t(a.width) + size_t(x)) * 3;
            bool over = false;
            for (size_t c = 0; c < 3; ++c) {
                const int diff = channel_diff(a, b, p + c);
                d.max_diff = std::max(d.max_diff, diff);
                sum += diff;
                sum_sq += double(diff) * diff;
                if (diff > tolerance) over = true;
            }
            if (!over) continue;
            if (d.pixels_over++ == 0) {
                d.box_x0 = d.box_x1 = x;
                d.box_y0 = d.box_y1 = y;
            } else {
                d.box_x0 = std::min(d.box_x0, x);
                d.box_x1 = std::max(d.box_x1, x);
                d.box_y1 = y;  // rows are visited in order
            }
        }
    }
    const double n = double(d.pixels) * 3;
    d.mean_diff = sum / n;
    d.pct_over = 100.0 * double(d.pixels_over) / double(d.pixels);
    const double mse = sum_sq / n;
    d.psnr = mse == 0 ? std::numeric_limits<double>::infinity() : 10.0 * std::log10(255.0 * 255.0 / mse);
    return d;
}

std::vector<PixelDiff> worst_pixels(const Image& a, const Image& b, size_t count) {
    std::vector<PixelDiff> worst;
    if (count == 0 || !compare_images(a, b).same_size) return worst;
    for (int y = 0; y < a.height; ++y) {
        for (int x = 0; x < a.width; ++x) {
            const size_t p = (size_t(y) * size_t(a.width) + size_t(x)) * 3;
            int d = 0;
            for (size_t c = 0; c < 3; ++c) d = std::max(d, channel_diff(a, b, p + c));
            // Pixels come in reading order, so one that only ties the last kept loses.
            if (d == 0 || (worst.size() == count && d <= worst.back().diff)) continue;
            PixelDiff px;
            px.x = x;
            px.y = y;
            px.diff = d;
            for (size_t c = 0; c < 3; ++c) {
                px.a[c] = a.rgb[p + c];
                px.b[c] = b.rgb[p + c];
            }
            if (worst.size() == count) worst.pop_back();
            // After every kept pixel of the same or a larger difference (they came earlier).
            const auto at = std::upper_bound(worst.begin(), worst.end(), d,
                                             [](int diff, const PixelDiff& w) { return diff > w.diff; });
            worst.insert(at, px);
        }
    }
    return worst;
}

std::string pixel_text(const PixelDiff& p) {
    char buf[128];
    std::snprintf(buf, sizeof buf, "%d,%d off by %d: A %d %d %d, B %d %d %d", p.x, p.y, p.diff, p.a[0], p.a[1], p.a[2],
                  p.b[0], p.b[1], p.b[2]);
    return buf;
}

Image read_image(const std::string& path) {
    std::error_code ec;
    const auto status = std::filesystem::status(path, ec);
    if (!std::filesystem::exists(status)) throw InputError(path + ": no such file");
    if (std::filesystem::is_directory(status)) throw InputError(path + ": is a folder, not an image");
    FILE* f = std::fopen(path.c_str(), "rb");
    if (!f) throw InputError(path + ": cannot open: " + std::strerror(errno));
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load_from_file(f, &w, &h, &n, 3);
    std::fclose(f);
    if (!data) {
        const char* why = stbi_failure_reason();
        throw InputError(path + ": not a PNG or PPM image we can read" + (why ? std::string(" (") + why + ")" : ""));
    }
    Image img;
    img.width = w;
    img.height = h;
    img.rgb.assign(data, data + size_t(w) * size_t(h) * 3);
    stbi_image_free(data);
    return img;
}

}  // namespace rt
