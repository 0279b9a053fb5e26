// gen_mesh --shape knot: a closed, watertight tube around a trefoil knot, its radius
// displaced by multi-octave noise, with two needle regions where the (u, v) grid is
// deliberately anisotropic. Scenes: _plain, _glass, _gold.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "gen_mesh.h"

namespace gen_mesh {

namespace {

// Trefoil, the (2, 3) torus knot: winds twice around the z axis, three times around the torus.
V3 knot(double phi) {
    const double rho = 2 + std::cos(3 * phi);
    return {rho * std::cos(2 * phi), rho * std::sin(2 * phi), -std::sin(3 * phi)};
}
V3 knot_tangent(double phi) {
    const double rho = 2 + std::cos(3 * phi), drho = -3 * std::sin(3 * phi);
    return {drho * std::cos(2 * phi) - 2 * rho * std::sin(2 * phi),
            drho * std::sin(2 * phi) + 2 * rho * std::cos(2 * phi), -3 * std::cos(3 * phi)};
}

constexpr double kTubeRadius = 0.38;  // strands are >= 1.66 apart, curvature radius >= 1.43
constexpr double kDisplace = 0.35;    // radius varies within ~(1 -/+ 0.3) * kTubeRadius
constexpr double kNoiseFreq = 1.1;    // lowest octave: lumps ~1 unit across
constexpr int kOctaves = 7;           // highest: ~0.01 units, a few triangles wide at 16M

// Needle region 1: three short stretches of the knot where rings are kBunchUAmp + 1 times
// closer than elsewhere: thin triangles across the knot. s is the ring index over the ring
// count; each stretch holds 2 * kBunchUHalf of the rings (~8% of all triangles together)
// but only ~0.1% of the knot's length.
constexpr double kBunchUCentres[] = {0.11, 0.43, 0.81};
constexpr double kBunchUAmp = 26, kBunchUHalf = 0.0125;
// Needle region 2: vertices bunched around the tube (theta = t - beta sin t, bunched at
// t = 0) along a stretch around s = kBunchV: thin triangles along the knot.
constexpr double kBunchV = 0.62, kBunchVBeta = 0.97, kBunchVKappa = 60;

double wrap_dist(double s, double centre) {  // distance on the unit circle of s
    double d = std::fabs(s - centre);
    d -= std::floor(d);
    return std::min(d, 1 - d);
}
double bump(double s, double centre, double kappa) { return std::exp(kappa * (std::cos(2 * kPi * (s - centre)) - 1)); }
// 1 within half-width w of centre, falling smoothly to 0 at 1.5 w.
double box(double s, double centre, double w) {
    const double d = wrap_dist(s, centre);
    if (d <= w) return 1;
    if (d >= 1.5 * w) return 0;
    const double x = 1 - (d - w) / (0.5 * w);
    return x * x * (3 - 2 * x);
}
// Spacing from ring s to the next, relative to unbunched rings.
double ring_step(double s) {
    double d = 1;
    for (double c : kBunchUCentres) d += kBunchUAmp * box(s, c, kBunchUHalf);
    return 1 / d;
}

// Object to world: scale, tilt towards the camera, place above the ground (z = -100),
// where the course's dragon scenes keep their model.
constexpr double kScale = 45;
const V3 kCentre{0, 100, 42};
V3 to_world(V3 p) {
    // rotate about x by 55 degrees, then about z by -25 degrees
    const double a = 55 * kPi / 180, g = -25 * kPi / 180;
    const V3 q{p.x, std::cos(a) * p.y - std::sin(a) * p.z, std::sin(a) * p.y + std::cos(a) * p.z};
    const V3 r{std::cos(g) * q.x - std::sin(g) * q.y, std::sin(g) * q.x + std::cos(g) * q.y, q.z};
    return kCentre + kScale * r;
}

}  // namespace

Generated make_knot(uint64_t target, uint64_t seed, const std::string& name) {
    Generated g;
    // Knot length and the mean stretch of ring spacing outside the bunched region, to make
    // the ordinary triangles roughly isosceles right triangles.
    double knot_len = 0;
    {
        const int n = 100000;
        for (int i = 0; i < n; ++i) knot_len += length(knot_tangent(2 * kPi * (i + 0.5) / n)) * 2 * kPi / n;
    }
    double mean_step = 0;  // unbunched rings are 1 / mean_step times sparser than uniform ones
    {
        const int n = 1000000;
        for (int i = 0; i < n; ++i) mean_step += ring_step((i + 0.5) / n) / n;
    }
    const double stretch = 1 / mean_step;
    // T = 2 Nu Nv and knot_len * stretch / Nu = 2 pi r / Nv.
    const double nv_real = std::sqrt(static_cast<double>(target) * 2 * kPi * kTubeRadius / (2 * knot_len * stretch));
    const uint64_t nv = std::max<uint64_t>(8, static_cast<uint64_t>(std::llround(nv_real)));
    const uint64_t nu = std::max<uint64_t>(8, (target + nv) / (2 * nv));
    const uint64_t nverts = nu * nv;
    if (nverts > 0x7fffffffull) die("too many vertices for int indices");

    // Ring parameters: phi advances by ring_step, so rings bunch in the needle regions.
    std::vector<double> phi(nu);
    {
        std::vector<double> step(nu);
        double total = 0;
        for (uint64_t i = 0; i < nu; ++i) {
            const double s = (i + 0.5) / static_cast<double>(nu);
            step[i] = ring_step(s);
            total += step[i];
        }
        double acc = 0;
        for (uint64_t i = 0; i < nu; ++i) {
            phi[i] = 2 * kPi * acc / total;
            acc += step[i];
        }
    }
    std::vector<double> cos_t(nv), sin_t(nv);
    for (uint64_t j = 0; j < nv; ++j) {
        const double t = 2 * kPi * static_cast<double>(j) / static_cast<double>(nv);
        cos_t[j] = std::cos(t);
        sin_t[j] = std::sin(t);
    }

    const Noise noise{mix64(seed)};
    g.pos.reserve(3 * nverts);
    for (uint64_t i = 0; i < nu; ++i) {
        const V3 c = knot(phi[i]);
        const V3 t = normalize(knot_tangent(phi[i]));
        const V3 n = normalize(cross(V3{0, 0, 1}, t));  // t is never vertical on this knot
        const V3 b = cross(t, n);                       // (t, n, b) right-handed
        const double beta = kBunchVBeta * bump(static_cast<double>(i) / static_cast<double>(nu), kBunchV, kBunchVKappa);
        for (uint64_t j = 0; j < nv; ++j) {
            double ct = cos_t[j], st = sin_t[j];
            if (beta > 1e-6) {  // theta = t - beta sin t: monotone for beta < 1, bunched at t = 0
                const double t0j = 2 * kPi * static_cast<double>(j) / static_cast<double>(nv);
                const double th = t0j - beta * std::sin(t0j);
                ct = std::cos(th);
                st = std::sin(th);
            }
            const V3 o = ct * n + st * b;  // outward, unit
            const V3 p0 = c + kTubeRadius * o;
            const double r = kTubeRadius * (1 + kDisplace * noise.fbm(kNoiseFreq * p0, kOctaves));
            g.add(to_world(c + r * o));
        }
    }
    auto vid = [&](uint64_t i, uint64_t j) { return static_cast<uint32_t>((i % nu) * nv + (j % nv)); };
    // Quad (i, j)-(i+1, j)-(i+1, j+1)-(i, j+1): d/dv x d/du points outwards, so each triangle
    // goes along v first. The diagonal alternates in a checkerboard, as meshers do.
    g.tri.reserve(6 * nu * nv);
    for (uint64_t i = 0; i < nu; ++i) {
        for (uint64_t j = 0; j < nv; ++j) {
            const uint32_t p00 = vid(i, j), p10 = vid(i + 1, j), p11 = vid(i + 1, j + 1), p01 = vid(i, j + 1);
            if ((i + j) & 1) {
                g.face(p00, p01, p11);
                g.face(p00, p11, p10);
            } else {
                g.face(p00, p01, p10);
                g.face(p01, p11, p10);
            }
        }
    }
    g.comment = "trefoil tube, " + u64(nu) + " x " + u64(nv) + " grid, seed " + u64(seed);
    g.detail = u64(nu) + " x " + u64(nv) + " grid x 2";

    SceneDesc d;
    d.position = {520, -120, 150};
    d.gaze = {0, 100, 5};
    d.fovy = "38";
    d.resolution = "800 480";
    d.lights = {{{400, 100, 200}, 5e7}, {{600, -200, 200}, 5e7}};
    d.vertex_data = floor_vertices(1000, -100);
    d.meshes = {ply_mesh(name + ".ply", true), kFloorMesh};
    for (const auto& [suffix, material] : {std::pair{"plain", kPlain}, {"glass", kGlass}, {"gold", kGold}}) {
        d.materials = {material, kFloorMirror};
        g.variants.push_back({suffix, d});
    }
    return g;
}

}  // namespace gen_mesh
