// gen_mesh --shape city: closed axis-aligned boxes of very different sizes in clusters,
// over a half-mirror ground. Scene: _plain.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include "gen_mesh.h"

namespace gen_mesh {

// Closed axis-aligned boxes (12 triangles each) in clusters: sizes log-uniform over three
// orders of magnitude, larger ones snapped to a unit grid (coplanar faces across boxes),
// some stacked on the previous box, some overlapping.
Generated make_city(uint64_t target, uint64_t seed, const std::string& name) {
    Generated g;
    const uint64_t boxes = std::max<uint64_t>(10, target / 12);
    if (8 * boxes > 0x7fffffffull) die("too many vertices for int indices");
    Rng rng{mix64(seed ^ 0xc17eull)};
    constexpr int kClusters = 7;
    struct Cluster {
        double x, y, sigma, tall;
    } cl[kClusters];
    for (auto& c : cl)
        c = {rng.uniform(-800, 800), rng.uniform(-800, 800), rng.log_uniform(60, 260), rng.uniform(1, 4)};
    g.pos.reserve(24 * boxes);
    g.tri.reserve(36 * boxes);
    V3 prev_lo{0, 0, 0}, prev_hi{0, 0, 0};
    auto snap = [](double v) { return std::round(v); };
    for (uint64_t b = 0; b < boxes; ++b) {
        const Cluster& c = cl[rng.next() % kClusters];
        const double kind = rng.uniform();
        double w, dep, h;   // footprint and height
        if (kind < 0.70) {  // street furniture: 0.1 .. 2 units
            w = rng.log_uniform(0.1, 2);
            dep = w * rng.log_uniform(0.5, 2);
            h = w * rng.log_uniform(0.3, 3);
        } else if (kind < 0.96) {  // houses
            w = rng.log_uniform(2, 20);
            dep = w * rng.log_uniform(0.5, 2);
            h = w * rng.log_uniform(0.3, 2);
        } else {  // towers
            w = rng.log_uniform(15, 70);
            dep = w * rng.log_uniform(0.6, 1.6);
            h = w * c.tall * rng.log_uniform(1, 5);
        }
        V3 lo{c.x + c.sigma * rng.gauss(), c.y + c.sigma * rng.gauss(), 0};
        if (b > 0 && rng.uniform() < 0.15 && prev_hi.x - prev_lo.x > 2 * w) {  // stacked, a setback
            lo = {prev_lo.x + rng.uniform(0, prev_hi.x - prev_lo.x - w), prev_lo.y, prev_hi.z};
            dep = std::min(dep, prev_hi.y - prev_lo.y);
        }
        V3 hi{lo.x + w, lo.y + dep, lo.z + h};
        if (w >= 2) {  // snapped: faces line up with neighbours'
            lo = {snap(lo.x), snap(lo.y), snap(lo.z)};
            hi = {std::max(lo.x + 1, snap(hi.x)), std::max(lo.y + 1, snap(hi.y)), std::max(lo.z + 1, snap(hi.z))};
        }
        prev_lo = lo;
        prev_hi = hi;
        uint32_t v[8];
        for (int k = 0; k < 8; ++k) v[k] = g.add({k & 1 ? hi.x : lo.x, k & 2 ? hi.y : lo.y, k & 4 ? hi.z : lo.z});
        // Face normal to axis a on side s: corners (0,0) (1,0) (1,1) (0,1) in the next two
        // axes (u, v), counter-clockwise about +a; reversed for the low side.
        for (int a = 0; a < 3; ++a)
            for (int s = 0; s < 2; ++s) {
                const int u = (a + 1) % 3, w3 = (a + 2) % 3;
                uint32_t qd[4];
                const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
                for (int k = 0; k < 4; ++k) qd[k] = v[(s << a) | (uv[k][0] << u) | (uv[k][1] << w3)];
                if (s) {
                    g.face(qd[0], qd[1], qd[2]);
                    g.face(qd[0], qd[2], qd[3]);
                } else {
                    g.face(qd[0], qd[2], qd[1]);
                    g.face(qd[0], qd[3], qd[2]);
                }
            }
    }
    g.comment = "city of " + u64(boxes) + " boxes, seed " + u64(seed);
    g.detail = u64(boxes) + " boxes x 12";

    SceneDesc d;
    d.background = "60 80 110";
    d.position = {1500, -1300, 800};
    d.gaze = {0, 0, 0};
    d.fovy = "45";
    d.resolution = "1024 768";
    d.lights = {{{2000, -1000, 3000}, 1.5e9}, {{-1500, -600, 900}, 3e8}};
    d.vertex_data = floor_vertices(3000, 0);
    const Fields concrete = phong("0.12 0.12 0.12", "0.5 0.5 0.52", "0.3 0.3 0.3", "20");
    d.materials = {concrete, kFloorMirror};
    d.meshes = {ply_mesh(name + ".ply", false), kFloorMesh};
    g.variants.push_back({"plain", d});
    return g;
}

}  // namespace gen_mesh
