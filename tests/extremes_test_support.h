// Shared by the numerical extremes tests (tests/test_extremes_*.cpp): numbers written into
// scene JSON, scenes built from JSON, rendering with a count of non-finite pixels, and the
// sample scene of spec section 7 as a base for the scenes of the tests.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/geometry/scene.h"
#include "rt/image/image.h"

namespace extremes_test {

// The numbers as a scene file writes them: space-separated, each to 17 digits.
std::string fmt(const std::vector<double>& xs);

inline std::string fmt3(double x, double y, double z) { return fmt({x, y, z}); }

// The scene of the JSON `j`, loaded as from `path` and built.
rt::Scene build(const nlohmann::ordered_json& j, const std::string& path = "/extremes/scene.json");

// ---- rendering with a NaN / inf count ----------------------------------------------------

struct Counted {
    rt::Image img;
    long nonfinite = 0;  // pixels whose radiance has a NaN or infinite channel
    long nan = 0;        // of which NaN
    double seconds = 0;
};

// Like rt::render, but every pixel's radiance is checked before quantisation.
Counted render_counted(const rt::Scene& s, size_t cam_index, bool cull = true, int threads = 2);

// ---- the sample scene of spec section 7, as a base for the NaN scenes ----------------

nlohmann::ordered_json base_scene(const std::string& res = "48 48");

}  // namespace extremes_test
