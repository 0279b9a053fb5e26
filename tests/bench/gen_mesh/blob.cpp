// gen_mesh --shape blob: a smooth closed blob, a geodesic icosphere displaced by
// low-frequency noise, over a mirror floor. Scenes: _plain, _glass.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "gen_mesh.h"

namespace gen_mesh {

// Geodesic icosphere of frequency n (20 n^2 triangles, 10 n^2 + 2 vertices, shared along the
// icosahedron's edges so the surface is watertight), radially displaced by smooth noise.
Generated make_blob(uint64_t target, uint64_t seed, const std::string& name) {
    Generated g;
    const uint64_t n = std::max<uint64_t>(2, static_cast<uint64_t>(std::llround(std::sqrt(target / 20.0))));
    if (10 * n * n + 2 > 0x7fffffffull) die("too many vertices for int indices");
    const double phi = (1 + std::sqrt(5.0)) / 2;
    std::vector<V3> ico;
    for (double s1 : {-1.0, 1.0})
        for (double s2 : {-phi, phi}) {
            ico.push_back(normalize({0, s1, s2}));
            ico.push_back(normalize({s1, s2, 0}));
            ico.push_back(normalize({s2, 0, s1}));
        }
    // Faces: the vertex triples that are mutually neighbours, counter-clockwise from outside.
    const double edge2 = 4 / (1 + phi * phi);  // squared edge of the unit icosahedron
    auto near_edge = [&](int a, int b) { return std::fabs(dot(ico[a] - ico[b], ico[a] - ico[b]) - edge2) < 1e-9; };
    std::vector<std::array<int, 3>> faces;
    for (int a = 0; a < 12; ++a)
        for (int b = a + 1; b < 12; ++b)
            for (int c = b + 1; c < 12; ++c)
                if (near_edge(a, b) && near_edge(b, c) && near_edge(a, c)) {
                    if (dot(cross(ico[b] - ico[a], ico[c] - ico[a]), ico[a]) > 0)
                        faces.push_back({a, b, c});
                    else
                        faces.push_back({a, c, b});
                }
    if (faces.size() != 20) die("internal error: icosahedron has " + std::to_string(faces.size()) + " faces");
    std::map<std::pair<int, int>, uint32_t> edges;  // (a < b) -> edge number
    for (const auto& f : faces)
        for (int k = 0; k < 3; ++k) {
            const int a = std::min(f[k], f[(k + 1) % 3]), b = std::max(f[k], f[(k + 1) % 3]);
            edges.emplace(std::pair{a, b}, static_cast<uint32_t>(edges.size()));
        }

    const Noise noise{mix64(seed ^ 0xb10bull)};
    constexpr double kRadius = 55, kAmp = 0.32, kFreq = 1.2;
    const V3 centre{0, 0, 0};
    auto place = [&](V3 dir) {
        const V3 u = normalize(dir);
        return centre + kRadius * (1 + kAmp * noise.fbm(kFreq * u, 3)) * u;
    };
    const double nd = static_cast<double>(n);
    for (int v = 0; v < 12; ++v) g.add(place(ico[v]));
    std::vector<std::pair<int, int>> edge_of(edges.size());
    for (const auto& [ab, e] : edges) edge_of[e] = ab;
    for (const auto& [a, b] : edge_of)
        for (uint64_t t = 1; t < n; ++t)
            g.add(place((nd - static_cast<double>(t)) * ico[a] + static_cast<double>(t) * ico[b]));
    // Grid point (i, j) of face (A, B, C) is A + i/n (B - A) + j/n (C - A).
    std::vector<uint32_t> id((n + 1) * (n + 1));
    for (const auto& f : faces) {
        for (uint64_t i = 0; i <= n; ++i)
            for (uint64_t j = 0; i + j <= n; ++j) {
                const uint64_t w[3] = {n - i - j, i, j};
                int nonzero = 0, k0 = -1, k1 = -1;
                for (int k = 0; k < 3; ++k)
                    if (w[k]) {
                        ++nonzero;
                        (k0 < 0 ? k0 : k1) = k;
                    }
                uint32_t v;
                if (nonzero == 1) {
                    v = static_cast<uint32_t>(f[k0]);
                } else if (nonzero == 2) {
                    const int a = std::min(f[k0], f[k1]), b = std::max(f[k0], f[k1]);
                    const uint64_t t = f[k0] == b ? w[k0] : w[k1];  // steps from a towards b
                    v = static_cast<uint32_t>(12 + edges.at({a, b}) * (n - 1) + (t - 1));
                } else {
                    v = g.add(place(static_cast<double>(w[0]) * ico[f[0]] + static_cast<double>(w[1]) * ico[f[1]] +
                                    static_cast<double>(w[2]) * ico[f[2]]));
                }
                id[i * (n + 1) + j] = v;
            }
        auto at = [&](uint64_t i, uint64_t j) { return id[i * (n + 1) + j]; };
        for (uint64_t i = 0; i < n; ++i)
            for (uint64_t j = 0; i + j < n; ++j) {
                g.face(at(i, j), at(i + 1, j), at(i, j + 1));
                if (i + j + 1 < n) g.face(at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            }
    }
    g.comment = "noisy geodesic icosphere, frequency " + u64(n) + ", seed " + u64(seed);
    g.detail = "icosphere, 20 x " + u64(n) + "^2";

    SceneDesc d =
        over_mirror_floor(name + ".ply", true, {190, -250, 95}, {0, 0, -12}, "1024 1024", -kRadius * (1 + kAmp) - 3);
    for (const auto& [suffix, material] : {std::pair{"plain", kPlain}, {"glass", kGlass}}) {
        d.materials = {material, kFloorMirror};
        g.variants.push_back({suffix, d});
    }
    return g;
}

}  // namespace gen_mesh
