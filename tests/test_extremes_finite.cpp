// Numerical extremes, no NaN / inf: total internal reflection, a camera inside a sphere,
// lights on surfaces, facing mirrors at depth 0 and 50, facing dielectrics whose ray tree
// pruning must bound, intensities of 1e12, degenerate and needle triangles: every pixel's
// radiance is checked (trace_primary per pixel), black speckles are counted.
//
// Lines starting "[extremes]" on stdout carry the figures (for the CI log and reports).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "extremes_test_support.h"
#include "rt/geometry/scene.h"
#include "rt/image/image.h"
#include "rt/render/render.h"
#include "test_support.h"

using json = nlohmann::ordered_json;
using namespace extremes_test;

namespace {

// Dark speckles: pixels less than half as bright as both neighbours on a line through
// them (left and right, or above and below), the neighbours clearly lit (brightest
// channel >= 30). Catches dark dots and one-pixel dark lines in any direction.
long speckles(const rt::Image& img, std::vector<std::pair<int, int>>* where = nullptr) {
    auto lit = [&](int x, int y) {
        const uint8_t* p = &img.rgb[(size_t(y) * img.width + x) * 3];
        return int(std::max({p[0], p[1], p[2]}));
    };
    long n = 0;
    for (int y = 1; y + 1 < img.height; ++y)
        for (int x = 1; x + 1 < img.width; ++x) {
            const int h = std::min(lit(x - 1, y), lit(x + 1, y)), v = std::min(lit(x, y - 1), lit(x, y + 1));
            const int c = 2 * lit(x, y);
            if ((h >= 30 && c < h) || (v >= 30 && c < v)) {
                ++n;
                if (where) where->push_back({x, y});
            }
        }
    return n;
}

// Where the speckles are, for failure messages: "(x, y) = v among a b | c d" for the first few.
std::string speckle_text(const rt::Image& img) {
    std::vector<std::pair<int, int>> where;
    speckles(img, &where);
    auto lit = [&](int x, int y) {
        const uint8_t* p = &img.rgb[(size_t(y) * img.width + x) * 3];
        return std::to_string(p[0]) + "/" + std::to_string(p[1]) + "/" + std::to_string(p[2]);
    };
    std::string s;
    for (size_t i = 0; i < where.size() && i < 8; ++i) {
        const auto [x, y] = where[i];
        s += " (" + std::to_string(x) + ", " + std::to_string(y) + ") = " + lit(x, y) + " between " + lit(x - 1, y) +
             " and " + lit(x + 1, y) + ", " + lit(x, y - 1) + " and " + lit(x, y + 1) + ";";
    }
    return s;
}

void report(const std::string& what, const Counted& r) {
    const long n = speckles(r.img);
    std::printf("[extremes] %-44s %4dx%-4d %6.3fs  non-finite %ld (NaN %ld)  dark speckles %ld%s\n", what.c_str(),
                r.img.width, r.img.height, r.seconds, r.nonfinite, r.nan, n,
                n ? (":" + speckle_text(r.img)).c_str() : "");
}

}  // namespace

// ---- no NaN, no infinity, no black speckles ---------------------------------------------------

TEST(ExtremesFinite, TotalInternalReflection) {
    // A diamond-like glass box (index 2.4) seen edge-on, and a glass sphere behind it:
    // most rays inside the box are totally reflected.
    json j = base_scene("64 64");
    j["Scene"]["Materials"]["Material"][3]["RefractionIndex"] = "2.4";
    std::string vd = j["Scene"]["VertexData"]["_data"];
    // A tetrahedron of glass in front of the camera (vertices 8..11), faces outward.
    vd += " 0 0.4 -1.2  -0.4 -0.3 -1.0  0.4 -0.3 -1.0  0 -0.1 -1.6";
    j["Scene"]["VertexData"]["_data"] = vd;
    j["Scene"]["Objects"]["Mesh"] = json::array(
        {j["Scene"]["Objects"]["Mesh"],
         json::parse(R"({"_id": "2", "Material": "4", "Faces": {"_data": "8 9 10 8 11 9 8 10 11 9 11 10"}})")});
    const rt::Scene s = build(j);
    const Counted r = render_counted(s, 0);
    report("total internal reflection (index 2.4)", r);
    EXPECT_EQ(r.nonfinite, 0);
}

TEST(ExtremesFinite, CameraInsideSpheres) {
    for (const char* material : {"1", "2", "3", "4"}) {
        // The camera (and the light) at the centre of a sphere of each material type.
        json j = base_scene("48 48");
        j["Scene"]["VertexData"]["_data"] = "0 0 0 0 -0.5 0";
        j["Scene"]["Objects"] = json::parse(R"({"Sphere": {"_id": "1", "Center": "1", "Radius": "5"}})");
        j["Scene"]["Objects"]["Sphere"]["Material"] = material;
        const Counted r = render_counted(build(j), 0);
        report(std::string("camera inside a sphere, material ") + material, r);
        EXPECT_EQ(r.nonfinite, 0) << "material " << material;
        EXPECT_EQ(speckles(r.img), 0) << "material " << material << speckle_text(r.img);
    }
}

TEST(ExtremesFinite, LightsOnSurfaces) {
    // One light at a time, exactly on the plane (where the centre pixel's ray meets it:
    // odd resolution, so that ray is exactly (0, 0, -1)), on a sphere's surface, inside a
    // triangle and on a triangle's vertex. Shadow rays reach as far as the light is from
    // the shaded point itself, which is past the light (docs/conventions.md, "Shadow
    // rays", read from mirror_room's reference): a surface the light lies on hides it
    // from every point whose shadow ray meets that surface at the light, which is every
    // point it could light but those of the surface itself (n.l = 0 there). So the image
    // must match (>= 99.5% of pixels within one level) the scene without that light, not a
    // noisy mixture of lit and shadowed pixels, and have no more dark speckles.
    //
    // On a vertex a shadow ray meets the triangle exactly at its corner, where the
    // watertight test's edge functions are zero up to rounding: whether it blocks is
    // decided by the last bit, for us as for the references. That case is rendered and
    // reported; what is asserted there is that every value is finite.
    struct Light {
        std::string name;
        double p[3];
        bool decided;  // false: shadow rays pass exactly through a vertex
    };
    const std::vector<Light> lights = {
        {"on the plane", {0, 0, -4}, true},
        {"on the sphere", {0.6, 0.5, -2.5}, true},
        {"inside a triangle", {0, 0, -3}, true},
        {"on a triangle's vertex", {-1, -1, -3}, false},
    };
    auto scene_with = [](const double* p) {
        json j = base_scene("49 49");
        j["Scene"]["VertexData"]["_data"] = "-1 -1 -3 1 -1 -3 0 1 -3 0 0 -4 0.6 0.3 -2.5";
        j["Scene"]["Objects"] = json::parse(R"({
            "Triangle": {"_id": "1", "Material": "1", "Indices": "1 2 3"},
            "Sphere": {"_id": "1", "Material": "1", "Center": "5", "Radius": "0.2"},
            "Plane": {"_id": "1", "Material": "1", "Point": "4", "Normal": "0 0 1"}})");
        if (p) {
            j["Scene"]["Lights"]["PointLight"] = json::parse(R"({"_id": "1", "Intensity": "500 500 500"})");
            j["Scene"]["Lights"]["PointLight"]["Position"] = fmt3(p[0], p[1], p[2]);
        } else {
            j["Scene"]["Lights"].erase("PointLight");
        }
        return render_counted(build(j), 0);
    };
    const Counted dark = scene_with(nullptr);
    for (const Light& l : lights) {
        const Counted r = scene_with(l.p);
        report("light " + l.name, r);
        EXPECT_EQ(r.nonfinite, 0) << l.name;
        const double match = 100 - compare(r.img, dark.img).pct_over_1;
        std::printf("[extremes]   light %s: %.2f%% of pixels match the scene without it\n", l.name.c_str(), match);
        if (!l.decided) continue;
        EXPECT_GE(match, 99.5) << "light " << l.name << ": not hidden by the surface it lies on";
        EXPECT_LE(speckles(r.img), speckles(dark.img)) << "light " << l.name << ":" << speckle_text(r.img);
    }
}

TEST(ExtremesFinite, FacingMirrorsAtDepthZeroAndFifty) {
    // A mirror tunnel: two facing mirrors (x = -1 and x = 1) and a mirror floor and
    // ceiling (y = -1, y = 1), a diffuse wall far down the tunnel (z = -60), the camera
    // inside looking down it at a slant: most rays bounce until MaxRecursionDepth.
    for (const char* depth : {"0", "50"}) {
        json j = base_scene("48 48");
        j["Scene"]["MaxRecursionDepth"] = depth;
        j["Scene"]["Cameras"]["Camera"]["Gaze"] = "0.4 0.25 -1";
        j["Scene"]["Cameras"]["Camera"]["Up"] = "0 1 0";
        j["Scene"]["VertexData"]["_data"] = "-1 0 0 1 0 0 0 0 -30 0 -1 0 0 1 0 0 0 -60";
        j["Scene"]["Materials"]["Material"][1]["MirrorReflectance"] = "0.95 0.95 0.95";
        j["Scene"]["Objects"] = json::parse(R"({
            "Plane": [{"_id": "1", "Material": "2", "Point": "1", "Normal": "1 0 0"},
                      {"_id": "2", "Material": "2", "Point": "2", "Normal": "-1 0 0"},
                      {"_id": "3", "Material": "2", "Point": "4", "Normal": "0 1 0"},
                      {"_id": "4", "Material": "2", "Point": "5", "Normal": "0 -1 0"},
                      {"_id": "5", "Material": "1", "Point": "6", "Normal": "0 0 1"}],
            "Sphere": {"_id": "1", "Material": "3", "Center": "3", "Radius": "0.8"}})");
        const Counted r = render_counted(build(j), 0);
        report(std::string("facing mirrors, MaxRecursionDepth ") + depth, r);
        EXPECT_EQ(r.nonfinite, 0) << "depth " << depth;
        // Mirrors and conductors spawn one ray per hit: at most MaxRecursionDepth per pixel.
        rt::RenderStats stats;
        const rt::Image img = rt::render(build(j), 0, rt::RenderOptions{}, &stats);
        EXPECT_LE(stats.rays.reflection + stats.rays.refraction,
                  uint64_t(img.width) * uint64_t(img.height) * uint64_t(std::stoi(depth)))
            << "depth " << depth;
    }
}

// Two facing glass spheres inside a closed mirror box, at MaxRecursionDepth 50: each
// hit on glass spawns a reflected and a refracted ray and in the box both keep hitting
// things, so the ray tree grows geometrically with the depth unless weak branches are
// pruned (TraceOptions::min_weight, rt/shading/shading.h). Pruning bounds the work:
// at each level of a pixel's ray tree the weights of the rays traced add up to at most
// 1 (a ray's children share its weight: MirrorReflectance x Fresnel, 1 - Fresnel and
// Beer's law are all <= 1) and each is at least min_weight, so a level holds at most
// 1 / min_weight rays, and a pixel's tree at most MaxRecursionDepth / min_weight
// reflection and refraction rays. The ray counts are asserted, depth after depth, so
// that a renderer that stops pruning fails (at 8 x 8 pixels, in seconds) instead of
// running for ever.
TEST(ExtremesFinite, FacingDielectricsAtDepthFiftyTerminate) {
    json j = base_scene("8 8");
    j["Scene"]["Lights"]["PointLight"]["Position"] = "0 3 0";
    std::string vd = "-1 0 -3 1 0 -3";  // the spheres' centres, then the box's corners (vertices 3..10)
    for (int i = 0; i < 8; ++i) vd += " " + fmt3(i & 1 ? 4 : -4, i & 2 ? 4 : -4, i & 4 ? 4 : -4);
    j["Scene"]["VertexData"]["_data"] = vd;
    // The cube's faces, counter-clockwise seen from inside.
    const int quads[6][4] = {{1, 3, 2, 0}, {6, 7, 5, 4}, {4, 5, 1, 0}, {3, 7, 6, 2}, {2, 6, 4, 0}, {5, 7, 3, 1}};
    std::string box;
    for (const auto& q : quads) {
        auto v = [&](int c) { return std::to_string(3 + q[c]) + " "; };
        box += v(0) + v(1) + v(2) + v(0) + v(2) + v(3);
    }
    j["Scene"]["Objects"] = json::parse(R"({
        "Sphere": [{"_id": "1", "Material": "4", "Center": "1", "Radius": "0.95"},
                   {"_id": "2", "Material": "4", "Center": "2", "Radius": "0.95"}],
        "Mesh": {"_id": "1", "Material": "2", "Faces": {"_type": "triangle"}}})");
    j["Scene"]["Objects"]["Mesh"]["Faces"]["_data"] = box;
    j["Scene"]["Materials"]["Material"][1]["MirrorReflectance"] = "0.9 0.9 0.9";
    rt::RenderOptions o;
    o.threads = 2;
    for (int depth : {5, 10, 20, 30, 40, 50}) {
        j["Scene"]["MaxRecursionDepth"] = std::to_string(depth);
        const rt::Scene s = build(j);
        rt::RenderStats stats;
        const rt::Image img = rt::render(s, 0, o, &stats);
        const uint64_t pixels = uint64_t(img.width) * uint64_t(img.height);
        const uint64_t secondary = stats.rays.reflection + stats.rays.refraction;
        const double bound = double(pixels) * depth / o.trace.min_weight;
        std::printf(
            "[extremes] facing dielectrics in a mirror box, MaxRecursionDepth %2d, 8x8 pixels: %llu reflection and "
            "refraction rays (bound %.3g), %llu shadow rays\n",
            depth, static_cast<unsigned long long>(secondary), bound,
            static_cast<unsigned long long>(stats.rays.shadow));
        EXPECT_EQ(stats.rays.camera, pixels);
        // Every shaded point sends at most one shadow ray per light (one light here).
        EXPECT_LE(stats.rays.shadow, stats.rays.camera + secondary);
        ASSERT_LE(double(secondary), bound) << "MaxRecursionDepth " << depth << ": weak rays are not pruned";
    }
}

TEST(ExtremesFinite, IntensitiesOf1e12) {
    json j = base_scene("48 48");
    j["Scene"]["Lights"]["PointLight"] = json::parse(R"([
        {"_id": "1", "Position": "0 0 0", "Intensity": "1e12 1e12 1e12"},
        {"_id": "2", "Position": "0.3 0.4 -1.9", "Intensity": "1e12 0 1e12"}])");
    j["Scene"]["Lights"]["AmbientLight"] = "1e12 1e12 1e12";
    // Everything inside a large diffuse sphere, so that no ray leaves the scene (rays
    // that miss would be black by convention): every pixel should be bright.
    j["Scene"]["VertexData"]["_data"] = j["Scene"]["VertexData"]["_data"].get<std::string>() + " 0 0 0";
    j["Scene"]["Objects"]["Sphere"].push_back(
        json::parse(R"({"_id": "3", "Material": "1", "Center": "8", "Radius": "50"})"));
    const Counted r = render_counted(build(j), 0);
    report("intensities of 1e12", r);
    EXPECT_EQ(r.nonfinite, 0);
    EXPECT_EQ(speckles(r.img), 0) << speckle_text(r.img);
}

TEST(ExtremesFinite, DegenerateAndNeedleTriangles) {
    // A smooth mesh mixing ordinary, needle (1e-12 wide) and degenerate (collinear,
    // repeated vertex) triangles, a flat fan of slivers, and a needle in front of it all.
    json j = base_scene("64 64");
    std::vector<double> v = {
        -1,   -1,   -3,   1,   -1,          -3,         1,     1,     -3,   -1, 1, -3,  // 1-4: a quad
        0,    0,    -3,   0,   0,           -3 + 1e-12, 1e-12, 1e-12, -3,               // 5-7: needle near the centre
        -0.5, -0.5, -2.5, 0.5, 0.5,         -2.5,       0,     0,     -2.5,             // 8-10: collinear
        -0.8, 0.6,  -2.2, 0.8, 0.6 + 1e-13, -2.2,       0,     0.6,   -2.21};           // 11-13: needle across the view
    for (int k = 0; k < 40; ++k)  // 14-53: a fan of slivers around (0.5, -0.5, -2.8)
        v.insert(v.end(), {0.5 + 0.4 * std::cos(k * 1e-7), -0.5 + 0.4 * std::sin(k * 1e-7), -2.8});
    v.insert(v.end(), {0.5, -0.5, -2.8});  // 54: the fan's centre
    j["Scene"]["VertexData"]["_data"] = fmt(v);
    std::string faces = "1 2 5 2 3 5 3 4 5 4 1 5 5 6 7 5 7 6 8 9 10 8 8 9 11 12 13 13 12 11 ";
    for (int k = 0; k + 1 < 40; ++k) faces += "54 " + std::to_string(14 + k) + " " + std::to_string(15 + k) + " ";
    j["Scene"]["Objects"] = json::parse(R"({"Mesh": [
        {"_id": "1", "Material": "1", "_shadingMode": "smooth", "Faces": {"_type": "triangle"}},
        {"_id": "2", "Material": "2", "Faces": {"_type": "triangle"}}]})");
    j["Scene"]["Objects"]["Mesh"][0]["Faces"]["_data"] = faces;
    j["Scene"]["Objects"]["Mesh"][1]["Faces"]["_data"] = faces;
    const rt::Scene s = build(j);
    std::printf("[extremes] needle scene: %zu triangles kept, %zu degenerate skipped\n", s.geometry.triangles.size(),
                s.report.degenerate_triangles);
    for (bool cull : {true, false}) {
        const Counted r = render_counted(s, 0, cull);
        report(std::string("degenerate and needle triangles, cull ") + (cull ? "on" : "off"), r);
        EXPECT_EQ(r.nonfinite, 0);
    }
}
