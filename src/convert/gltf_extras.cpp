// The tables of gltf_extras.h, and the import's checks of their values.
#include "gltf_extras.h"

#include <cmath>

#include "rt/core/error.h"
#include "scene_import.h"

namespace rt {
namespace {

using json = nlohmann::json;

json vec(const Vec3& v) { return json::array({double(v.x), double(v.y), double(v.z)}); }
// An optional value the file has when it is above zero.
json above_zero(Real x) { return x > 0 ? json(double(x)) : json(); }

bool in_range(const json& j, double lo, double hi) {
    return j.is_number() && j.get<double>() >= lo && j.get<double>() <= hi;
}

// Three numbers from `lo` to 1e30, or nothing.
bool three(const json& j, double lo) {
    return j.is_array() && j.size() == 3 && in_range(j[0], lo, kMaxMagnitude) && in_range(j[1], lo, kMaxMagnitude) &&
           in_range(j[2], lo, kMaxMagnitude);
}

std::array<double, 3> v3(const json& j) { return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()}; }

}  // namespace

const std::array<ExtraField<CameraDesc>, 3> kCameraExtras = {{
    {"numSamples", "NumSamples", ExtraValue::Samples,
     [](const CameraDesc& c) { return c.num_samples > 0 ? json(c.num_samples) : json(); }},
    {"focusDistance", "FocusDistance", ExtraValue::Positive,
     [](const CameraDesc& c) { return above_zero(c.focus_distance); }},
    {"apertureSize", "ApertureSize", ExtraValue::NonNegative,
     [](const CameraDesc& c) { return above_zero(c.aperture_size); }},
}};

const std::array<ExtraField<AreaLightDesc>, 4> kAreaLightExtras = {{
    {"position", "Position", ExtraValue::Vector, [](const AreaLightDesc& l) { return vec(l.position); }},
    {"normal", "Normal", ExtraValue::Direction, [](const AreaLightDesc& l) { return vec(l.normal); }},
    {"size", "Size", ExtraValue::Positive, [](const AreaLightDesc& l) { return json(double(l.size)); }},
    {"radiance", "Radiance", ExtraValue::Colour, [](const AreaLightDesc& l) { return vec(l.radiance); }},
}};

const std::array<ExtraField<Vec3>, 1> kMotionExtras = {{
    {"motionBlur", "MotionBlur", ExtraValue::Vector,
     [](const Vec3& motion) { return is_still(motion) ? json() : vec(motion); }},
}};

const std::array<ExtraField<MaterialDesc>, 1> kMaterialExtras = {{
    {"roughness", "Roughness", ExtraValue::NonNegative, [](const MaterialDesc& m) { return above_zero(m.roughness); }},
}};

void read_extra(const char* key, const char* course_key, ExtraValue value, const json& extras, const std::string& where,
                bool required, nlohmann::ordered_json& entry) {
    const auto it = extras.is_object() ? extras.find(key) : extras.end();
    if (!extras.is_object() || it == extras.end()) {
        if (required) throw InputError(where + ": has no " + key);
        return;
    }
    const json& j = *it;
    const double big = kMaxMagnitude;
    std::string text, expected;
    switch (value) {
        case ExtraValue::Samples:
            if (in_range(j, 1, kMaxSamples) && j.get<double>() == std::floor(j.get<double>()))
                text = std::to_string(static_cast<long>(j.get<double>()));
            expected = "a whole number from 1 to " + std::to_string(kMaxSamples);
            break;
        case ExtraValue::Positive:
            if (in_range(j, 0, big) && j.get<double>() > 0) text = course_number(j.get<double>());
            expected = "a number above 0, at most 1e30";
            break;
        case ExtraValue::NonNegative:
            if (in_range(j, 0, big)) text = course_number(j.get<double>());
            expected = "a number from 0 to 1e30";
            break;
        case ExtraValue::Vector:
            if (three(j, -big)) text = course_vec(v3(j));
            expected = "3 numbers from -1e30 to 1e30";
            break;
        case ExtraValue::Direction:
            if (three(j, -big) && (j[0] != 0 || j[1] != 0 || j[2] != 0)) text = course_vec(v3(j));
            expected = "3 numbers from -1e30 to 1e30, not all 0";
            break;
        case ExtraValue::Colour:
            if (three(j, 0)) text = course_vec(v3(j));
            expected = "3 numbers from 0 to 1e30";
            break;
    }
    if (text.empty()) {
        std::string got = j.dump();
        if (got.size() > 40) got = got.substr(0, 37) + "...";
        throw InputError(where + "/" + key + ": must be " + expected + ", got " + got);
    }
    entry[course_key] = text;
}

}  // namespace rt
