// Shared by the converters' tests (tests/test_convert_*.cpp).
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "rt/convert/convert.h"
#include "rt/core/error.h"
#include "rt/core/math.h"
#include "rt/loader/scene_desc.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "test_support.h"

namespace convert_test {

// Whether two vectors are equal, exactly.
inline bool same(const rt::Vec3& a, const rt::Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// A vector as text, for failure messages.
inline std::string str(const rt::Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
}

// What differs, exactly, between two scenes in assignment 3's elements: each camera's
// NumSamples and lens, the area lights, each material's Roughness, the MotionBlur of every
// object of every kind. Empty when nothing does.
inline std::string distribution_differences(const rt::SceneDesc& a, const rt::SceneDesc& b) {
    std::string why;
    auto differ = [&](const std::string& what) { why += what + "; "; };
    if (a.cameras.size() != b.cameras.size()) differ("camera count");
    for (size_t i = 0; i < std::min(a.cameras.size(), b.cameras.size()); ++i) {
        const rt::CameraDesc &x = a.cameras[i], &y = b.cameras[i];
        if (x.num_samples != y.num_samples || x.aperture_size != y.aperture_size ||
            x.focus_distance != y.focus_distance)
            differ("camera " + std::to_string(i) + " samples or lens");
    }
    if (a.area_lights.size() != b.area_lights.size()) differ("area light count");
    for (size_t i = 0; i < std::min(a.area_lights.size(), b.area_lights.size()); ++i) {
        const rt::AreaLightDesc &x = a.area_lights[i], &y = b.area_lights[i];
        if (!same(x.position, y.position) || !same(x.normal, y.normal) || x.size != y.size ||
            !same(x.radiance, y.radiance))
            differ("area light " + std::to_string(i) + ": normal " + str(x.normal) + " vs " + str(y.normal));
    }
    if (a.materials.size() != b.materials.size()) differ("material count");
    for (size_t i = 0; i < std::min(a.materials.size(), b.materials.size()); ++i)
        if (a.materials[i].roughness != b.materials[i].roughness)
            differ("material " + std::to_string(i) + " roughness");
    if (a.meshes.size() != b.meshes.size()) differ("mesh count");
    for (size_t i = 0; i < std::min(a.meshes.size(), b.meshes.size()); ++i)
        if (!same(a.meshes[i].motion, b.meshes[i].motion)) differ("mesh " + std::to_string(i) + " motion");
    rt::for_each_shape_desc([&](auto k) {
        using D = decltype(k);
        const std::vector<D>&x = a.all<D>(), &y = b.all<D>();
        if (x.size() != y.size()) differ(std::string(D::kNoun) + " count");
        for (size_t i = 0; i < std::min(x.size(), y.size()); ++i)
            if (!same(x[i].motion, y[i].motion))
                differ(std::string(D::kNoun) + " " + std::to_string(i) + " motion: " + str(x[i].motion) + " vs " +
                       str(y[i].motion));
    });
    return why;
}

// Every camera's image of a scene, at most 96 pixels a side, at `samples` a pixel (0: each
// camera's NumSamples).
inline std::vector<rt::Image> small_renders(rt::SceneDesc d, int samples) {
    for (rt::CameraDesc& c : d.cameras) {
        const int longest = std::max(c.width, c.height);
        if (longest <= 96) continue;
        c.width = std::max(1, c.width * 96 / longest);
        c.height = std::max(1, c.height * 96 / longest);
    }
    rt::Scene s = rt::build_scene(std::move(d));
    rt::RenderOptions o;
    o.samples = samples;
    rt::apply_overrides(s, o);
    std::vector<rt::Image> images;
    for (size_t c = 0; c < s.setup.cameras.size(); ++c) images.push_back(rt::render(s, c, o));
    return images;
}

// Whether two scenes render alike (small_renders), byte for byte, and not black.
inline ::testing::AssertionResult same_images(const rt::SceneDesc& a, const rt::SceneDesc& b, int samples) {
    const std::vector<rt::Image> x = small_renders(a, samples), y = small_renders(b, samples);
    if (x.size() != y.size()) return ::testing::AssertionFailure() << x.size() << " vs " << y.size() << " images";
    for (size_t i = 0; i < x.size(); ++i) {
        if (x[i].rgb != y[i].rgb)
            return ::testing::AssertionFailure() << "image " << i << " differs: " << compare(x[i], y[i]).pct_over_1
                                                 << "% of pixels off by more than 1";
        if (*std::max_element(x[i].rgb.begin(), x[i].rgb.end()) == 0)
            return ::testing::AssertionFailure() << "image " << i << " is black: nothing to compare";
    }
    return ::testing::AssertionSuccess();
}

// The error of converting `in` to `out`; empty when it converts.
inline std::string error_of(const std::string& in, const std::string& out, const rt::ConvertOptions& o = {}) {
    try {
        rt::convert_file(in, out, o);
    } catch (const rt::InputError& e) {
        return e.what();
    }
    return "";
}

inline bool any_contains(const std::vector<std::string>& lines, const std::string& part) {
    for (const std::string& l : lines)
        if (contains(l, part)) return true;
    return false;
}

}  // namespace convert_test
