// The numerical extremes tests' shared helpers (extremes_test_support.h).
#include "extremes_test_support.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/core/threads.h"
#include "rt/image/image.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/shading.h"

using json = nlohmann::ordered_json;

namespace extremes_test {

std::string fmt(const std::vector<double>& xs) {
    std::string s;
    char buf[40];
    for (double x : xs) {
        std::snprintf(buf, sizeof buf, "%.17g", x);
        s += (s.empty() ? "" : " ") + std::string(buf);
    }
    return s;
}

rt::Scene build(const json& j, const std::string& path) { return rt::build_scene(rt::parse_scene(j.dump(), path)); }

Counted render_counted(const rt::Scene& s, size_t cam_index, bool cull, int threads) {
    const rt::Camera& cam = s.setup.cameras.at(cam_index);
    Counted out;
    out.img.width = cam.width;
    out.img.height = cam.height;
    out.img.rgb.assign(size_t(cam.width) * cam.height * 3, 0);
    std::atomic<long> nonfinite{0}, nan{0};
    std::atomic<int> next_row{0};
    const rt::TraceOptions opt{cull};
    const auto t0 = std::chrono::steady_clock::now();
    auto work = [&] {
        for (int y; (y = next_row.fetch_add(1)) < cam.height;) {
            for (int x = 0; x < cam.width; ++x) {
                const rt::Vec3 c = rt::trace_primary(s, cam.primary_ray(x, y), opt);
                if (!rt::isfinite(c)) {
                    ++nonfinite;
                    if (std::isnan(c.x) || std::isnan(c.y) || std::isnan(c.z)) ++nan;
                }
                uint8_t* px = &out.img.rgb[(size_t(y) * cam.width + x) * 3];
                px[0] = rt::quantize(c.x, rt::Rounding::Truncate);
                px[1] = rt::quantize(c.y, rt::Rounding::Truncate);
                px[2] = rt::quantize(c.z, rt::Rounding::Truncate);
            }
        }
    };
    {
        std::vector<rt::HelperThread> pool;
        for (int i = 1; i < threads; ++i) pool.emplace_back(work);
        work();
    }  // joined
    out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    out.nonfinite = nonfinite;
    out.nan = nan;
    return out;
}

json base_scene(const std::string& res) {
    return json::parse(R"({"Scene": {
      "BackgroundColor": "0 0 0", "ShadowRayEpsilon": "1e-3", "MaxRecursionDepth": "6",
      "Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": ")" +
                       res + R"(", "ImageName": "x.png"}},
      "Lights": {"AmbientLight": "25 25 25",
        "PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "1000 1000 1000"}},
      "Materials": {"Material": [
        {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1", "SpecularReflectance": "1 1 1", "PhongExponent": "10"},
        {"_id": "2", "_type": "mirror", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.2 0.2 0.2",
         "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "10", "MirrorReflectance": "0.7 0.7 0.7"},
        {"_id": "3", "_type": "conductor", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0.1 0.1 0.1",
         "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "20", "MirrorReflectance": "1 0.86 0.57",
         "RefractionIndex": "0.37", "AbsorptionIndex": "2.82"},
        {"_id": "4", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
         "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "50", "MirrorReflectance": "1 1 1",
         "AbsorptionCoefficient": "0.01 0.02 0.03", "RefractionIndex": "1.5"}]},
      "VertexData": {"_data": "-0.5 0.5 -2 -0.5 -0.5 -2 0.5 -0.5 -2 0.5 0.5 -2 0 -0.5 0 -0.6 -0.3 -1.5 0.4 0.2 -1.2", "_type": "xyz"},
      "Objects": {
        "Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "3 1 2 1 3 4", "_type": "triangle"}},
        "Sphere": [{"_id": "1", "Material": "2", "Center": "6", "Radius": "0.3"},
                   {"_id": "2", "Material": "4", "Center": "7", "Radius": "0.25"}],
        "Plane": {"_id": "1", "Material": "1", "Point": "5", "Normal": "0 1 0"}}}})");
}

}  // namespace extremes_test
