// gen_mesh --shape terrain: a noise heightfield seen from just above the ground along its
// length (grazing rays, a far horizon), with a few spheres. Scene: _plain.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "gen_mesh.h"

namespace gen_mesh {

// Heightfield on an nx x ny grid (y three times x): grazing camera rays along y. Two
// triangles per cell, counter-clockwise seen from above.
Generated make_terrain(uint64_t target, uint64_t seed, const std::string& name) {
    Generated g;
    g.closed = false;
    const uint64_t cx = std::max<uint64_t>(4, static_cast<uint64_t>(std::llround(std::sqrt(target / 6.0))));
    const uint64_t cy = std::max<uint64_t>(4, target / (2 * cx));  // cells along y
    const uint64_t nx = cx + 1, ny = cy + 1;
    if (nx * ny > 0x7fffffffull) die("too many vertices for int indices");
    constexpr double kHalfWidth = 1000, kLength = 6000, kRelief = 160;
    const Noise noise{mix64(seed ^ 0x7e44a1ull)};
    auto height = [&](double x, double y) {
        const double h = noise.fbm(V3{x / 700, y / 700, 0.5}, 9);
        const double valley = 1 - std::exp(-x * x / (2 * 250.0 * 250.0));  // a valley along y at x = 0
        return kRelief * (h + 0.6 * valley);
    };
    auto x_of = [&](uint64_t i) {
        return -kHalfWidth + 2 * kHalfWidth * static_cast<double>(i) / static_cast<double>(cx);
    };
    auto y_of = [&](uint64_t j) { return kLength * static_cast<double>(j) / static_cast<double>(cy) - 200; };
    g.pos.reserve(3 * nx * ny);
    for (uint64_t j = 0; j < ny; ++j)
        for (uint64_t i = 0; i < nx; ++i) g.add({x_of(i), y_of(j), height(x_of(i), y_of(j))});
    g.tri.reserve(6 * cx * cy);
    for (uint64_t j = 0; j < cy; ++j)
        for (uint64_t i = 0; i < cx; ++i) {
            const auto p00 = static_cast<uint32_t>(j * nx + i), p10 = p00 + 1;
            const auto p01 = static_cast<uint32_t>(p00 + nx), p11 = p01 + 1;
            g.face(p00, p10, p11);
            g.face(p00, p11, p01);
        }
    g.comment = "noise heightfield, " + u64(nx) + " x " + u64(ny) + " vertices, seed " + u64(seed);
    g.detail = "heightfield, " + u64(cx) + " x " + u64(cy) + " cells x 2";

    SceneDesc d;
    d.background = "70 100 150";
    const double h0 = height(0, -180);
    d.position = {0, -180, h0 + 45};
    d.gaze = {0, 1200, h0 - 10};
    d.fovy = "20";
    d.resolution = "1280 400";
    d.ambient = "30 30 30";
    d.lights = {{{-3000, -1500, 4000}, 9e9}, {{1500, 2500, 1200}, 1e9}};
    // Spheres resting in the valley: (y, radius, material).
    const struct {
        double x, y, r;
        int material;
    } spheres[] = {{-20, 150, 22, 2}, {35, 320, 30, 3}, {-60, 600, 45, 4}, {90, 1000, 60, 2}, {-150, 1700, 90, 5}};
    std::string vd;
    for (const auto& s : spheres) {
        vd += (vd.empty() ? "" : " ") + num3({s.x, s.y, height(s.x, s.y) + 0.7 * s.r});
        d.spheres.push_back({{"_id", std::to_string(d.spheres.size() + 1)},
                             {"Material", std::to_string(s.material)},
                             {"Center", std::to_string(d.spheres.size() + 1)},
                             {"Radius", num(s.r)}});
    }
    d.vertex_data = vd;
    const Fields ground = phong("0.12 0.12 0.1", "0.42 0.45 0.3", "0.1 0.1 0.1", "8");
    d.materials = {ground, mirror(2, "0 0 0", "0.05 0.05 0.05", "0.5 0.5 0.5", "100", "0.9 0.9 0.9"),
                   with_id(kGlass, 3), with_id(kGold, 4), with_id(kPlain, 5)};
    d.meshes = {ply_mesh(name + ".ply", true)};
    g.variants.push_back({"plain", d});
    return g;
}

}  // namespace gen_mesh
