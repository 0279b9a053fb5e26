// gen_mesh --shape soup: random triangles of random shape and orientation filling a ball,
// over a mirror floor. Scene: _plain.
#include <cmath>
#include <cstdint>
#include <string>

#include "gen_mesh.h"

namespace gen_mesh {

// Independent random triangles (three random directions around a random centre, edge
// scale log-uniform) filling a ball; scaled with the count so that the ball stays about
// equally transparent. Half of them face away from any given ray: culling matters.
Generated make_soup(uint64_t target, uint64_t seed, const std::string& name) {
    Generated g;
    g.closed = false;
    const uint64_t n = target;
    Rng rng{mix64(seed ^ 0x50bull)};
    constexpr double kBall = 70;
    const double scale = std::sqrt(1e6 / static_cast<double>(n));
    g.pos.reserve(9 * n);
    g.tri.reserve(3 * n);
    for (uint64_t t = 0; t < n; ++t) {
        V3 c;
        do c = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
        while (dot(c, c) > 1);
        c = kBall * c;
        const double e = scale * rng.log_uniform(0.015, 1.5);
        const uint32_t a = g.add(c + e * rng.unit()), b = g.add(c + e * rng.unit()), cc = g.add(c + e * rng.unit());
        g.face(a, b, cc);
    }
    g.comment = "random triangle soup in a ball, seed " + u64(seed);
    g.detail = "soup";

    SceneDesc d = over_mirror_floor(name + ".ply", false, {170, -230, 80}, {0, 0, -8}, "720 720", -kBall - 5);
    d.materials = {kPlain, kFloorMirror};
    g.variants.push_back({"plain", d});
    return g;
}

}  // namespace gen_mesh
