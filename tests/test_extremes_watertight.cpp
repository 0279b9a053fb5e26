// Numerical extremes, watertightness: dense triangle grids at grazing and head-on angles,
// and camera rays exactly through vertices and edge midpoints, show no background pixel
// inside the grid; a concave edge between two walls shows no shadow speckles along it.
//
// Lines starting "[extremes]" on stdout carry the figures (for the CI log and reports).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "extremes_test_support.h"
#include "rt/geometry/scene.h"
#include "rt/shading/shading.h"

using json = nlohmann::ordered_json;
using namespace extremes_test;

// ---- watertightness ---------------------------------------------------------------------

namespace {

// A deterministic value in [-0.5, 0.5) from two integers.
double jitter(int i, int j, int k) {
    uint32_t h = uint32_t(i) * 73856093u ^ uint32_t(j) * 19349663u ^ uint32_t(k) * 83492791u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return double(h & 0xffff) / 65536.0 - 0.5;
}

// The n x n quad grid over [-1, 1]^2 in the plane y = 0, front face +y. Interior
// vertices are moved in the plane by up to 0.35 cells; diagonals alternate.
std::pair<std::string, std::string> grid_y0(int n) {
    std::vector<double> v;
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) {
            double x = -1 + 2.0 * i / n, z = -1 + 2.0 * j / n;
            if (i > 0 && i < n && j > 0 && j < n) {
                x += 0.7 / n * jitter(i, j, 1);
                z += 0.7 / n * jitter(i, j, 2);
            }
            v.insert(v.end(), {x, 0, z});
        }
    std::string faces;
    auto id = [n](int i, int j) { return std::to_string(j * (n + 1) + i + 1); };
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            // (i, j) -> (x, z): a = (i, j), b = (i, j+1), c = (i+1, j) runs counter-clockwise seen from +y.
            if ((i + j) % 2 == 0)
                faces += id(i, j) + " " + id(i, j + 1) + " " + id(i + 1, j) + " " + id(i + 1, j) + " " + id(i, j + 1) +
                         " " + id(i + 1, j + 1) + " ";
            else
                faces += id(i, j) + " " + id(i + 1, j + 1) + " " + id(i + 1, j) + " " + id(i, j) + " " + id(i, j + 1) +
                         " " + id(i + 1, j + 1) + " ";
        }
    return {fmt(v), faces};
}

// A scene holding one grid mesh lit by ambient light only (every grid pixel is
// 100 100 100) over a background used nowhere else.
json grid_scene(const std::string& vertices, const std::string& faces) {
    json j = json::parse(R"({"Scene": {
      "BackgroundColor": "0 0 255",
      "Cameras": {"Camera": []},
      "Lights": {"AmbientLight": "100 100 100"},
      "Materials": {"Material": {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "0 0 0",
                                 "SpecularReflectance": "0 0 0"}},
      "Objects": {"Mesh": {"_id": "1", "Material": "1", "Faces": {"_type": "triangle"}}}}})");
    j["Scene"]["VertexData"] = vertices;
    j["Scene"]["Objects"]["Mesh"]["Faces"]["_data"] = faces;
    return j;
}

struct V3 {
    double x, y, z;
};
V3 sub(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
double dot3(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross3(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
V3 unit(V3 a) {
    const double l = std::sqrt(dot3(a, a));
    return {a.x / l, a.y / l, a.z / l};
}

// A camera at `pos` looking at the origin whose near plane just frames the square
// [-1, 1]^2 of the plane y = 0 (so that most pixels see the grid, even at grazing angles).
json framing_camera(V3 pos, V3 up, int res, int id) {
    const V3 w = unit({-(-pos.x), -(-pos.y), -(-pos.z)});  // w = -gaze, gaze = -pos
    const V3 v0 = unit(up);
    const V3 u = unit(cross3(v0, w));
    const V3 v = cross3(w, u);
    double l = 1e300, r = -1e300, b = 1e300, t = -1e300;
    for (double cx : {-1.0, 1.0})
        for (double cz : {-1.0, 1.0}) {
            const V3 d = sub({cx, 0, cz}, pos);
            const double depth = -dot3(d, w);
            const double su = dot3(d, u) / depth, sv = dot3(d, v) / depth;
            l = std::min(l, su), r = std::max(r, su), b = std::min(b, sv), t = std::max(t, sv);
        }
    const double mu = 0.05 * (r - l), mv = 0.05 * (t - b);
    json c;
    c["_id"] = std::to_string(id);
    c["Position"] = fmt3(pos.x, pos.y, pos.z);
    c["Gaze"] = fmt3(-pos.x, -pos.y, -pos.z);
    c["Up"] = fmt3(up.x, up.y, up.z);
    c["NearPlane"] = fmt({l - mu, r + mu, b - mv, t + mv});
    c["NearDistance"] = "1";
    c["ImageResolution"] = std::to_string(res) + " " + std::to_string(res);
    c["ImageName"] = "grid" + std::to_string(id) + ".png";
    return c;
}

}  // namespace

TEST(ExtremesWatertight, DenseGridAtGrazingAndHeadOnAngles) {
    const int n = 96;  // 18432 triangles
    const auto [vertices, faces] = grid_y0(n);
    json j = grid_scene(vertices, faces);
    struct View {
        double elevation_deg, azimuth_deg;
    };
    const std::vector<View> views = {{90, 0}, {60, 17}, {30, 45},  {10, 0},   {5, 33},
                                     {1, 0},  {1, 71},  {0.1, 12}, {0.01, 40}};
    const double dist = 4;
    int id = 1;
    for (const View& vw : views) {
        const double el = vw.elevation_deg * rt::pi_v<double> / 180, az = vw.azimuth_deg * rt::pi_v<double> / 180;
        const V3 pos = {dist * std::cos(el) * std::sin(az), dist * std::sin(el), dist * std::cos(el) * std::cos(az)};
        const V3 up = vw.elevation_deg == 90 ? V3{0, 0, -1} : V3{0, 1, 0};
        j["Scene"]["Cameras"]["Camera"].push_back(framing_camera(pos, up, 128, id++));
    }
    const rt::Scene s = build(j);
    ASSERT_EQ(s.geometry.triangles.size(), size_t(2 * n * n));
    const rt::TraceOptions opt{true};
    for (size_t c = 0; c < s.setup.cameras.size(); ++c) {
        const rt::Camera& cam = s.setup.cameras[c];
        long inside = 0, holes = 0, nonfinite = 0;
        for (int y = 0; y < cam.height; ++y)
            for (int x = 0; x < cam.width; ++x) {
                const rt::Ray ray = cam.primary_ray(x, y);
                if (ray.dir.y == 0) continue;
                const double t = -double(ray.org.y) / double(ray.dir.y);
                if (!(t > 0)) continue;
                const double px = ray.org.x + t * ray.dir.x, pz = ray.org.z + t * ray.dir.z;
                const double m = 1e-6;  // stay clear of the grid's outer boundary
                if (!(std::fabs(px) < 1 - m && std::fabs(pz) < 1 - m)) continue;
                ++inside;
                const rt::Vec3 col = rt::trace_primary(s, ray, opt);
                if (!rt::isfinite(col)) ++nonfinite;
                if (col.x == s.setup.background.x && col.y == s.setup.background.y && col.z == s.setup.background.z)
                    ++holes;
            }
        std::printf(
            "[extremes] watertight grid, elevation %5g deg azimuth %3g deg: %6ld pixels inside the grid, "
            "%ld show the background, non-finite %ld\n",
            views[c].elevation_deg, views[c].azimuth_deg, inside, holes, nonfinite);
        EXPECT_GT(inside, 1000) << "camera " << c + 1 << " sees too little of the grid to test anything";
        EXPECT_EQ(holes, 0) << "camera " << c + 1 << ": background seen through the grid";
        EXPECT_EQ(nonfinite, 0);
    }
}

// Camera rays aimed exactly at the grid's vertices, edge midpoints and diagonal
// midpoints (in exact arithmetic): the worst case for a non-watertight test.
TEST(ExtremesWatertight, RaysThroughVerticesAndAlongEdges) {
    const int w = 64;             // grid vertices at the pixel centres of a w x w image
    const double step = 2.0 / w;  // at distance 1: NearPlane -1 1 -1 1
    std::vector<double> v;
    for (int j = 0; j < w; ++j)
        for (int i = 0; i < w; ++i) v.insert(v.end(), {-1 + (i + 0.5) * step, -1 + (j + 0.5) * step, -1});
    std::string faces;
    auto id = [w](int i, int j) { return std::to_string(j * w + i + 1); };
    for (int j = 0; j + 1 < w; ++j)
        for (int i = 0; i + 1 < w; ++i) {
            // Counter-clockwise seen from +z (the camera at the origin looks down -z).
            if ((i + j) % 2 == 0)
                faces += id(i, j) + " " + id(i + 1, j) + " " + id(i + 1, j + 1) + " " + id(i, j) + " " +
                         id(i + 1, j + 1) + " " + id(i, j + 1) + " ";
            else
                faces += id(i, j) + " " + id(i + 1, j) + " " + id(i, j + 1) + " " + id(i + 1, j) + " " +
                         id(i + 1, j + 1) + " " + id(i, j + 1) + " ";
        }
    json j = grid_scene(fmt(v), faces);
    const double lo = -1 + 0.5 * step, hi = 1 - 0.5 * step;
    // Camera 1: a pixel centre on every vertex. Camera 2 (2w - 1 pixels over the same
    // span): pixel centres on every vertex and every edge midpoint, diagonals included.
    // Camera 3: camera 2 moved off-axis, the rays oblique to the grid.
    const double half = step / 4;
    const std::vector<std::tuple<std::string, std::vector<double>, int>> cams = {
        {"0 0 0", {-1, 1, -1, 1}, w},
        {"0 0 0", {lo - half, hi + half, lo - half, hi + half}, 2 * w - 1},
        {"0.3 -0.2 0", {lo - 0.3 - half, hi - 0.3 + half, lo + 0.2 - half, hi + 0.2 + half}, 2 * w - 1},
    };
    int k = 1;
    for (const auto& [pos, np, res] : cams) {
        json c;
        c["_id"] = std::to_string(k);
        c["Position"] = pos;
        c["Gaze"] = "0 0 -1";
        c["Up"] = "0 1 0";
        c["NearPlane"] = fmt(np);
        c["NearDistance"] = "1";
        c["ImageResolution"] = std::to_string(res) + " " + std::to_string(res);
        c["ImageName"] = "v" + std::to_string(k++) + ".png";
        j["Scene"]["Cameras"]["Camera"].push_back(c);
    }
    const rt::Scene s = build(j);
    for (size_t c = 0; c < s.setup.cameras.size(); ++c) {
        const Counted r = render_counted(s, c);
        long holes = 0, inside = 0;
        // The outermost ring of pixels sits exactly on the grid's outer boundary; skip it.
        for (int y = 1; y + 1 < r.img.height; ++y)
            for (int x = 1; x + 1 < r.img.width; ++x) {
                const uint8_t* p = &r.img.rgb[(size_t(y) * r.img.width + x) * 3];
                ++inside;
                holes += (p[0] == 0 && p[1] == 0 && p[2] == 255);
            }
        std::printf(
            "[extremes] rays through vertices/edges, camera %zu: %ld pixels, %ld show the background, "
            "non-finite %ld\n",
            c + 1, inside, holes, r.nonfinite);
        EXPECT_EQ(holes, 0) << "camera " << c + 1;
        EXPECT_EQ(r.nonfinite, 0) << "camera " << c + 1;
    }
}

// ---- concave edges ---------------------------------------------------------------------------

// A floor (y = -1) meeting a back wall (z = -2) at a right angle, lit from inside the
// corner. With 30 rows over NearPlane -1..1, row 22's rays (s_v = -0.5) pass exactly
// through the shared edge. That row must be lit like the rows on either side.
TEST(ExtremesEdges, ConcaveEdgeHasNoShadowSpeckles) {
    json j = base_scene("40 30");
    j["Scene"]["VertexData"]["_data"] = "-3 -1 -0.5 3 -1 -0.5 3 -1 -2 -3 -1 -2 -3 -1 -2 3 -1 -2 3 2 -2 -3 2 -2";
    j["Scene"]["Lights"]["PointLight"] =
        json::parse(R"({"_id": "1", "Position": "0.3 0.2 -1.2", "Intensity": "300 300 300"})");
    j["Scene"]["Materials"]["Material"][0]["SpecularReflectance"] = "0 0 0";
    j["Scene"]["Objects"] = json::parse(R"({"Mesh": [
        {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3 1 3 4"}},
        {"_id": "2", "Material": "1", "Faces": {"_data": "5 6 7 5 7 8"}}]})");
    const Counted r = render_counted(build(j), 0);
    auto lit = [&](int x, int y) {
        const uint8_t* p = &r.img.rgb[(size_t(y) * r.img.width + x) * 3];
        return int(std::max({p[0], p[1], p[2]}));
    };
    long dark = 0;
    for (int x = 0; x < r.img.width; ++x) dark += 2 * lit(x, 22) < std::min(lit(x, 21), lit(x, 23));
    std::printf(
        "[extremes] concave edge: %ld of %d pixels on the edge row are dark speckles (row 21: %d, row 22: %d, "
        "row 23: %d at the centre column)\n",
        dark, r.img.width, lit(20, 21), lit(20, 22), lit(20, 23));
    EXPECT_EQ(r.nonfinite, 0);
    // The shadow ray starts at p + n * ShadowRayEpsilon with n the normal of the face
    // that was hit; at a point on a concave edge that start lies in the plane of the
    // other face, which a naive triangle test puts at t = +-1e-16 at random (dark
    // pixels along the edge row). For shadow rays intersect_triangle rejects a t within
    // the rounding error of t and of the origin (intersect.h). The alternative,
    // ignoring every occluder within ShadowRayEpsilon, is wrong the other way: it lets
    // light through thin geometry (tower_smooth and raven move away from their
    // references).
    EXPECT_EQ(dark, 0);
}
