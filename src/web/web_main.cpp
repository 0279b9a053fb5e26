// The WebAssembly module's exports (docs/web.md): rt::web's session (rt/web/session.h) in
// the precision the last rtw_load asked for, and the page's image comparison (rtdiff's
// figures and heatmap, rt/image/image_diff.h). Strings returned stay valid until the
// next call; JavaScript copies them (UTF8ToString) at once.
#include <emscripten/emscripten.h>

#include <nlohmann/json.hpp>

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>

#include "rt/image/image_diff.h"
#include "rt/web/session.h"

namespace rt_float::web {
std::string load(const std::string& scene_path, const std::string& options_json);
std::string scene_json();
std::string render_part(int camera, int part, int parts, uint8_t* rgba);
std::string refine_part(int camera, int part, int parts, int k0, int k1, uint8_t* rgba);
std::string trace(int camera, int x, int y, int sample);
}  // namespace rt_float::web

namespace {

bool g_float = false;  // the precision of the loaded scene
std::string g_out;     // the last string returned

const char* out(std::string s) {
    g_out = std::move(s);
    return g_out.c_str();
}

rt::Image rgb_of(const uint8_t* rgba, int width, int height) {
    rt::Image img;
    img.width = width;
    img.height = height;
    img.rgb.resize(static_cast<size_t>(width) * height * 3);
    for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i) std::memcpy(&img.rgb[3 * i], &rgba[4 * i], 3);
    return img;
}

}  // namespace

extern "C" {

// precision: "double" or "float".
EMSCRIPTEN_KEEPALIVE const char* rtw_load(const char* scene_path, const char* options_json, const char* precision) {
    g_float = std::strcmp(precision, "float") == 0;
    return out(g_float ? rt_float::web::load(scene_path, options_json) : rt::web::load(scene_path, options_json));
}

EMSCRIPTEN_KEEPALIVE const char* rtw_scene() {
    return out(g_float ? rt_float::web::scene_json() : rt::web::scene_json());
}

EMSCRIPTEN_KEEPALIVE const char* rtw_render_part(int camera, int part, int parts, uint8_t* rgba) {
    return out(g_float ? rt_float::web::render_part(camera, part, parts, rgba)
                       : rt::web::render_part(camera, part, parts, rgba));
}

EMSCRIPTEN_KEEPALIVE const char* rtw_refine_part(int camera, int part, int parts, int k0, int k1, uint8_t* rgba) {
    return out(g_float ? rt_float::web::refine_part(camera, part, parts, k0, k1, rgba)
                       : rt::web::refine_part(camera, part, parts, k0, k1, rgba));
}

EMSCRIPTEN_KEEPALIVE const char* rtw_trace(int camera, int x, int y, int sample) {
    return out(g_float ? rt_float::web::trace(camera, x, y, sample) : rt::web::trace(camera, x, y, sample));
}

// Compares two RGBA images of one size as rtdiff does (alpha ignored); writes the heatmap
// (RGBA) into `heat` and returns the figures as JSON.
EMSCRIPTEN_KEEPALIVE const char* rtw_compare(const uint8_t* a_rgba, const uint8_t* b_rgba, int width, int height,
                                             int tolerance, uint8_t* heat) {
    const rt::Image a = rgb_of(a_rgba, width, height), b = rgb_of(b_rgba, width, height);
    const rt::ImageComparison c = rt::compare_images(a, b, tolerance);
    const rt::Image h = rt::diff_heatmap(a, b, tolerance);
    for (size_t i = 0; i < static_cast<size_t>(width) * height; ++i) {
        std::memcpy(&heat[4 * i], &h.rgb[3 * i], 3);
        heat[4 * i + 3] = 255;
    }
    nlohmann::json f = {{"max_diff", c.max_diff},
                        {"mean_diff", c.mean_diff},
                        {"pixels", c.pixels},
                        {"pixels_over", c.pixels_over},
                        {"pct_over", c.pct_over},
                        {"tolerance", c.tolerance},
                        {"psnr", c.psnr},  // identical images: +inf, which JSON writes as null
                        {"text", rt::psnr_text(c.psnr)}};
    f["box"] = c.box_empty() ? nlohmann::json() : nlohmann::json{c.box_x0, c.box_y0, c.box_x1, c.box_y1};
    return out(f.dump());
}

}  // extern "C"
