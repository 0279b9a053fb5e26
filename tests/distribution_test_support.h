// Scenes of assignment 3's elements for the distribution tests (test_distribution.cpp,
// test_samplers.cpp).
#pragma once
#include <nlohmann/json.hpp>

#include "loader_test_support.h"
#include "rt/geometry/scene.h"
#include "rt/scene_build/build_scene.h"

namespace distribution_test {

using loader_test::json;

inline json area_light() {
    return json{{"_id", "1"}, {"Position", "0 5 0"}, {"Normal", "0 -1 0"}, {"Size", "2"}, {"Radiance", "10 10 10"}};
}

inline rt::Scene build(const json& j) { return rt::build_scene(loader_test::parse(j.dump())); }

// A scene that uses everything: an area light, a lens, a rough mirror, a moving sphere
// and a moving mesh, at 8 samples.
inline json everything() {
    json j = loader_test::sample();
    json& cam = j["Scene"]["Cameras"]["Camera"];
    cam["ImageResolution"] = "24 20";
    cam["NumSamples"] = "8";
    cam["FocusDistance"] = "2";
    cam["ApertureSize"] = "0.1";
    j["Scene"]["Lights"]["AreaLight"] = area_light();
    j["Scene"]["Lights"]["AreaLight"]["Position"] = "0 1 -1";
    j["Scene"]["Materials"]["Material"] =
        json::array({j["Scene"]["Materials"]["Material"],
                     {{"_id", "2"}, {"_type", "mirror"}, {"MirrorReflectance", "0.8 0.8 0.8"}, {"Roughness", "0.2"}}});
    j["Scene"]["Objects"]["Sphere"]["MotionBlur"] = "0.3 0 0";
    j["Scene"]["Objects"]["Plane"]["Material"] = "2";
    j["Scene"]["Objects"]["Mesh"]["MotionBlur"] = "0 0.2 0";
    return j;
}

}  // namespace distribution_test
