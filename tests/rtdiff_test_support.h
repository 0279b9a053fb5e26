// Shared by the tests of rt/image/image_diff.h and ./rtdiff (tests/test_rtdiff*.cpp):
// hand-made images, pixel access, the --html page's links, a course-like tree for --manifest,
// and a fixture that runs ./rtdiff in a temporary folder holding two images one pixel apart.
#pragma once
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "rt/image/image.h"
#include "test_support.h"

namespace rtdiff_test {

inline rt::Image gradient(int w, int h) {
    rt::Image img;
    img.width = w;
    img.height = h;
    img.rgb.resize(size_t(w) * size_t(h) * 3);
    for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = uint8_t(40 + i % 150);
    return img;
}

inline void create_dirs(const std::string& dir) { std::filesystem::create_directories(dir); }

inline uint8_t& at(rt::Image& img, int x, int y, int c) {
    return img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3 + size_t(c)];
}

inline uint8_t px(const rt::Image& img, int x, int y, int c) {
    return img.rgb[(size_t(y) * size_t(img.width) + size_t(x)) * 3 + size_t(c)];
}

// The %XX escapes of a URL path decoded.
inline std::string url_decode(const std::string& u) {
    std::string out;
    for (size_t i = 0; i < u.size(); ++i) {
        if (u[i] == '%' && i + 2 < u.size()) {
            out += char(std::stoi(u.substr(i + 1, 2), nullptr, 16));
            i += 2;
        } else {
            out += u[i];
        }
    }
    return out;
}

// Every value of attribute `attr` ("src", "href") in `page`.
inline std::vector<std::string> attributes(const std::string& page, const std::string& attr) {
    std::vector<std::string> out;
    const std::string key = attr + "=\"";
    for (size_t at = page.find(key); at != std::string::npos; at = page.find(key, at + 1)) {
        const size_t begin = at + key.size();
        out.push_back(page.substr(begin, page.find('"', begin) - begin));
    }
    return out;
}

// A course-like tree under `root`: shared/scenes/hw9/MANIFEST.tsv (lines `manifest`),
// a scene cams.json of two cameras (the second writes second.png), and references in
// shared/references/hw9/.
struct ManifestTree {
    explicit ManifestTree(const std::string& root)
        : shared(root + "/shared"), scenes(shared + "/scenes/hw9"), refs(shared + "/references/hw9") {
        create_dirs(scenes);
        create_dirs(refs + "/sub");
        write_text(scenes + "/cams.json", R"({"Scene": {"Cameras": {"Camera": [{"_id": "1", "ImageName": "first.png"},)"
                                          R"( {"_id": "2", "ImageName": "second.png"}]}}})");
    }
    std::string manifest(const std::vector<std::string>& lines) const {
        std::string text = "# scene\timage\treference\tinputs\n";
        for (const std::string& l : lines) text += l + "\n";
        write_text(scenes + "/MANIFEST.tsv", text);
        return scenes + "/MANIFEST.tsv";
    }
    std::string shared, scenes, refs;
};

// ./rtdiff run in tmp_, which holds a.png, its copy b.png with pixel 13,7 off by 2, and a.ppm.
class RtdiffTool : public ::testing::Test {
protected:
    void SetUp() override {
        a_ = gradient(20, 10);
        b_ = a_;
        at(b_, 13, 7, 0) += 2;
        rt::write_png(a_, tmp_ / "a.png");
        rt::write_png(b_, tmp_ / "b.png");
        rt::write_ppm(a_, tmp_ / "a.ppm");
    }
    RunResult run(const std::vector<std::string>& args) { return run_program(rtdiff_path(), args, tmp_.path(), 60); }
    TempDir tmp_;
    rt::Image a_, b_;
};

}  // namespace rtdiff_test
