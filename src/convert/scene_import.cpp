// What the importers share: number formatting, the default material, and the camera and
// lights a model without its own gets (scene_import.h).
#include "scene_import.h"

#include <charconv>
#include <cmath>
#include <cstdio>

#include "rt/core/math.h"

namespace rt {
namespace {

using ojson = nlohmann::ordered_json;
using V3 = std::array<double, 3>;

// 15 significant digits: enough for a computed placement, and short.
std::string num15(double d) {
    if (d == 0) return "0";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.15g", d);
    return buf;
}
std::string vec15(const V3& v) { return num15(v[0]) + " " + num15(v[1]) + " " + num15(v[2]); }

V3 add_scaled(const V3& a, const V3& d, double s) { return {a[0] + d[0] * s, a[1] + d[1] * s, a[2] + d[2] * s}; }
V3 normalized(const V3& a) {
    const double l = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    return {a[0] / l, a[1] / l, a[2] / l};
}

}  // namespace

std::string course_number(double d) {
    if (d == 0) return "0";
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, d);
    return std::string(buf, r.ptr);
}

std::string course_vec(const V3& v) {
    return course_number(v[0]) + " " + course_number(v[1]) + " " + course_number(v[2]);
}

ojson default_material(size_t id) {
    ojson j = ojson::object();
    j["_id"] = std::to_string(id);
    j["AmbientReflectance"] = "0.2 0.2 0.2";
    j["DiffuseReflectance"] = "0.7 0.7 0.7";
    j["SpecularReflectance"] = "0.25 0.25 0.25";
    j["PhongExponent"] = "32";
    return j;
}

ModelFrame frame_model(const V3& lo, const V3& hi, int width, int height, const std::string& image_name) {
    // Frame the bounding box: a lookAt camera in front of it, up and to the right
    // (OBJ and glTF models are Y-up), a light up and to the left.
    const V3 center{(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    ModelFrame f;
    f.radius = 0.5 * std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                               (hi[2] - lo[2]) * (hi[2] - lo[2]));
    if (!(f.radius > 0) || !std::isfinite(f.radius)) f.radius = 1;
    const double fovy = 40, pi = pi_v<double>;
    const double aspect = double(width) / double(height);
    // Fit the bounding sphere in the narrower of the two fields of view.
    const double half = std::atan(std::tan(fovy * pi / 360) * std::min(1.0, aspect));
    const double distance = 1.1 * f.radius / std::sin(half);
    const V3 eye = add_scaled(center, normalized({0.45, 0.35, 1.0}), distance);
    const V3 light = add_scaled(center, normalized({-0.6, 1.0, 0.8}), distance);
    const double intensity = 350 * distance * distance;

    f.camera = ojson::object();
    f.camera["_id"] = "1";
    f.camera["_type"] = "lookAt";
    f.camera["Position"] = vec15(eye);
    f.camera["GazePoint"] = vec15(center);
    f.camera["Up"] = "0 1 0";
    f.camera["FovY"] = num15(fovy);
    f.camera["NearDistance"] = "1";
    f.camera["ImageResolution"] = std::to_string(width) + " " + std::to_string(height);
    f.camera["ImageName"] = image_name;
    ojson point = ojson::object();
    point["_id"] = "1";
    point["Position"] = vec15(light);
    point["Intensity"] = vec15({intensity, intensity, intensity});
    f.lights = ojson::object();
    f.lights["AmbientLight"] = "25 25 25";
    f.lights["PointLight"] = point;
    return f;
}

}  // namespace rt
