// imgdiff: compares pairs of PNG images for `make report` (tests/report/report.py).
//
//   imgdiff < pairs      one pair per line: "A.png<TAB>B.png[<TAB>DIFF.png]"
//
// For each line it prints one JSON object on its own line (and flushes), comparing A
// (the variant) with B (the baseline or reference), 8-bit RGB:
//   {"width", "height", "pixels",
//    "changed":  pixels with any channel different,
//    "over1":    pixels with a channel off by more than 1 level (the conformance measure),
//    "darker":   of those, pixels whose channel sum is lower in A than in B,
//    "brighter": of those, the rest,
//    "max":      largest channel difference, "mean": mean absolute channel difference,
//    "psnr":     dB over all channels (null when identical)}
// or {"error": "..."} when an image cannot be read or the sizes differ. With DIFF.png,
// writes a picture of the differences: B in dim grey, pixels off by more than 1 level
// in red (darker in A) or green (brighter in A).
//
// Build: g++ -O2 -std=c++17 imgdiff.cpp -o imgdiff -lstb   (libstb-dev)
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace {

struct Rgb {
    int w = 0, h = 0;
    std::vector<unsigned char> px;
};

bool load(const std::string& path, Rgb& out) {
    int n = 0;
    unsigned char* data = stbi_load(path.c_str(), &out.w, &out.h, &n, 3);
    if (!data) return false;
    out.px.assign(data, data + size_t(out.w) * size_t(out.h) * 3);
    stbi_image_free(data);
    return true;
}

std::string escape(const std::string& s) {
    std::string o;
    for (char c : s) {
        if (c == '"' || c == '\\') o += '\\';
        if (static_cast<unsigned char>(c) < 0x20) continue;
        o += c;
    }
    return o;
}

std::string compare(const std::string& a_path, const std::string& b_path, const std::string& diff_path) {
    Rgb a, b;
    if (!load(a_path, a)) return "{\"error\": \"cannot read " + escape(a_path) + "\"}";
    if (!load(b_path, b)) return "{\"error\": \"cannot read " + escape(b_path) + "\"}";
    if (a.w != b.w || a.h != b.h)
        return "{\"error\": \"sizes differ: " + std::to_string(a.w) + "x" + std::to_string(a.h) + " and " +
               std::to_string(b.w) + "x" + std::to_string(b.h) + "\"}";
    const size_t pixels = size_t(a.w) * size_t(a.h);
    size_t changed = 0, over1 = 0, darker = 0, brighter = 0;
    int max_diff = 0;
    double sum = 0, sum_sq = 0;
    std::vector<unsigned char> vis(diff_path.empty() ? 0 : pixels * 3);
    for (size_t p = 0; p < pixels; ++p) {
        const unsigned char* x = &a.px[3 * p];
        const unsigned char* y = &b.px[3 * p];
        int worst = 0, sa = 0, sb = 0;
        for (int c = 0; c < 3; ++c) {
            const int d = std::abs(int(x[c]) - int(y[c]));
            worst = std::max(worst, d);
            sum += d;
            sum_sq += double(d) * d;
            sa += x[c];
            sb += y[c];
        }
        max_diff = std::max(max_diff, worst);
        if (worst > 0) ++changed;
        const bool off = worst > 1;
        if (off) {
            ++over1;
            if (sa < sb)
                ++darker;
            else
                ++brighter;
        }
        if (!vis.empty()) {
            unsigned char* v = &vis[3 * p];
            if (off && sa < sb) {
                v[0] = 255, v[1] = 0, v[2] = 0;
            } else if (off) {
                v[0] = 0, v[1] = 230, v[2] = 0;
            } else {
                const unsigned char g = static_cast<unsigned char>(40 + (sb / 3) * 100 / 255);
                v[0] = v[1] = v[2] = g;
            }
        }
    }
    if (!vis.empty() && !stbi_write_png(diff_path.c_str(), a.w, a.h, 3, vis.data(), a.w * 3))
        return "{\"error\": \"cannot write " + escape(diff_path) + "\"}";
    const double n = double(pixels) * 3;
    const double mse = n > 0 ? sum_sq / n : 0;
    char psnr[64];
    if (mse == 0)
        std::snprintf(psnr, sizeof psnr, "null");
    else
        std::snprintf(psnr, sizeof psnr, "%.3f", 10.0 * std::log10(255.0 * 255.0 / mse));
    char buf[512];
    std::snprintf(buf, sizeof buf,
                  "{\"width\": %d, \"height\": %d, \"pixels\": %zu, \"changed\": %zu, \"over1\": %zu, "
                  "\"darker\": %zu, \"brighter\": %zu, \"max\": %d, \"mean\": %.6f, \"psnr\": %s}",
                  a.w, a.h, pixels, changed, over1, darker, brighter, max_diff, n > 0 ? sum / n : 0.0, psnr);
    return buf;
}

}  // namespace

int main() {
    std::string line;
    while (std::getline(std::cin, line)) {
        if (line.empty()) continue;
        std::vector<std::string> f;
        size_t start = 0;
        for (size_t tab; (tab = line.find('\t', start)) != std::string::npos; start = tab + 1)
            f.push_back(line.substr(start, tab - start));
        f.push_back(line.substr(start));
        if (f.size() < 2 || f.size() > 3) {
            std::printf("{\"error\": \"expected A<TAB>B[<TAB>DIFF]\"}\n");
        } else {
            std::printf("%s\n", compare(f[0], f[1], f.size() == 3 ? f[2] : "").c_str());
        }
        std::fflush(stdout);
    }
    return 0;
}
