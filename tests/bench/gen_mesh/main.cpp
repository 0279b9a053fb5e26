// gen_mesh: writes a large benchmark mesh (binary little-endian PLY) and the scenes in the
// course's JSON format that use it, for `make bench` (docs/bench-scenes.md).
//
//   gen_mesh [--shape SHAPE] [--out-dir DIR] [--name NAME] [--seed N] TRIANGLES
//
// TRIANGLES is a count, optionally with a K or M suffix (1M, 4M, 16M); each shape comes as
// close to it as its grid allows. SHAPE picks the surface and so the triangle distribution:
//   knot     (default) a closed, watertight tube around a trefoil knot, counter-clockwise
//            seen from outside: a (u, v) grid of ~2 * Nu * Nv triangles, its radius displaced
//            by deterministic multi-octave gradient noise (a fixed seed), with the geometric
//            character of scanned models: dense, curved and bumpy, and a fraction of needle
//            triangles, from two regions where the grid is deliberately anisotropic (rings
//            bunched along the knot in one, vertices bunched around the tube in the other).
//            Scenes: _plain, _glass, _gold.
//   blob     a smooth closed blob: a geodesic icosphere (each icosahedron face cut into n^2
//            triangles) displaced by low-frequency noise; near-uniform, well-shaped
//            triangles, over a mirror floor at 1024x1024. Scenes: _plain, _glass.
//   terrain  a heightfield on a regular grid three times longer than wide, seen from just
//            above the ground along its length (grazing rays, a far horizon), with a few
//            spheres of mirror, glass, gold and plain material. Scene: _plain.
//   city     many closed axis-aligned boxes of very different sizes (tiny to huge, snapped
//            to a grid so that many faces are coplanar, some stacked) in clusters with empty
//            space between, over a half-mirror ground. Scene: _plain.
//   soup     random triangles of random shape and orientation (log-uniform sizes) filling
//            a ball, a cloud that rays enter some way before they hit, over a mirror
//            floor. Scene: _plain.
//
// Written: DIR/NAME.ply and DIR/NAME_<variant>.json (NAME defaults to <shape>_<count>, e.g.
// knot_1m, blob_1m). Each file is written under a temporary name and renamed, so an
// interrupted run leaves no half-written file. The output depends only on the arguments:
// same arguments, same bytes.
//
// Standalone C++17, no dependencies; mk/bench.mk builds it from tests/bench/gen_mesh/*.cpp:
//   g++ -O2 -std=c++17 -ffp-contract=off -o gen_mesh tests/bench/gen_mesh/*.cpp
// This file: the command line, the checks and the summary line; the shapes are knot.cpp,
// blob.cpp, terrain.cpp, city.cpp and soup.cpp, their scene files scene_json.cpp.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "gen_mesh.h"

using namespace gen_mesh;

namespace {

uint64_t parse_count(const std::string& s) {
    if (s.empty()) die("empty triangle count");
    char* end = nullptr;
    const double v = std::strtod(s.c_str(), &end);
    double mul = 1;
    const std::string suffix(end);
    if (suffix == "k" || suffix == "K")
        mul = 1e3;
    else if (suffix == "m" || suffix == "M")
        mul = 1e6;
    else if (!suffix.empty())
        die("bad triangle count '" + s + "' (use e.g. 1000000, 500K, 4M)");
    const double n = v * mul;
    if (!(n >= 1000) || n > 1.0e9) die("triangle count must be between 1000 and 1e9");
    return static_cast<uint64_t>(std::llround(n));
}

std::string count_name(uint64_t n) {
    if (n % 1000000 == 0) return std::to_string(n / 1000000) + "m";
    if (n % 1000 == 0) return std::to_string(n / 1000) + "k";
    return std::to_string(n);
}

const struct {
    const char* name;
    Generated (*make)(uint64_t target, uint64_t seed, const std::string& name);
} kShapes[] = {
    {"knot", make_knot}, {"blob", make_blob}, {"terrain", make_terrain}, {"city", make_city}, {"soup", make_soup}};

}  // namespace

int main(int argc, char** argv) {
    const char* usage =
        "usage: gen_mesh [--shape knot|blob|terrain|city|soup] [--out-dir DIR] [--name NAME] [--seed N] TRIANGLES";
    std::string out_dir = ".", name, count_arg, shape = "knot";
    uint64_t seed = 795;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) die(a + " needs a value");
            return argv[++i];
        };
        if (a == "--out-dir" || a == "-o")
            out_dir = value();
        else if (a == "--name")
            name = value();
        else if (a == "--seed")
            seed = std::strtoull(value().c_str(), nullptr, 10);
        else if (a == "--shape")
            shape = value();
        else if (a == "-h" || a == "--help") {
            std::printf("%s (e.g. 1M, 4M, 16M)\n", usage);
            return 0;
        } else if (!a.empty() && a[0] == '-')
            die("unknown option " + a);
        else if (count_arg.empty())
            count_arg = a;
        else
            die("one triangle count only");
    }
    if (count_arg.empty()) die(usage);
    const uint64_t target = parse_count(count_arg);
    Generated (*make)(uint64_t, uint64_t, const std::string&) = nullptr;
    for (const auto& s : kShapes)
        if (shape == s.name) make = s.make;
    if (!make) die("unknown shape '" + shape + "' (knot, blob, terrain, city, soup)");
    if (name.empty()) name = shape + "_" + count_name(target);
    const auto t0 = std::chrono::steady_clock::now();

    const Generated g = make(target, seed, name);
    const uint64_t nverts = g.pos.size() / 3, ntris = g.tri.size() / 3;
    if (nverts > 0x7fffffffull) die("too many vertices for int indices");

    write_ply(out_dir + "/" + name + ".ply", g);
    const double gen_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Statistics: enclosed volume (> 0 when a closed mesh's triangles face outwards),
    // needles (longest edge over shortest altitude above 10), triangle areas.
    double volume = 0, area = 0, min_area = 1e300, max_area = 0;
    uint64_t needles = 0, worst_count = 0;
    double worst = 0;
    auto P = [&](uint32_t k) { return V3{g.pos[3 * k], g.pos[3 * k + 1], g.pos[3 * k + 2]}; };
    for (uint64_t t = 0; t < ntris; ++t) {
        const V3 pa = P(g.tri[3 * t]), pb = P(g.tri[3 * t + 1]), pc = P(g.tri[3 * t + 2]);
        const V3 cr = cross(pb - pa, pc - pa);
        volume += dot(pa, cross(pb, pc)) / 6;
        const double twice_area = length(cr);
        area += twice_area / 2;
        min_area = std::min(min_area, twice_area / 2);
        max_area = std::max(max_area, twice_area / 2);
        const double e = std::max({length(pb - pa), length(pc - pb), length(pa - pc)});
        const double aspect = twice_area > 0 ? e * e / twice_area : 1e30;  // longest edge / its altitude
        if (aspect > 10) ++needles;
        if (aspect > 50) ++worst_count;
        worst = std::max(worst, aspect);
    }
    if (g.closed && !(volume > 0))
        die("internal error: the mesh faces inwards (signed volume " + std::to_string(volume) + ")");

    const std::string base = out_dir + "/" + name;
    std::string suffixes;
    for (const auto& v : g.variants) {
        Out out(base + "_" + v.suffix + ".json");
        out.write(scene_json(v.scene, name + "_" + v.suffix + ".png"));
        out.commit();
        suffixes += (suffixes.empty() ? "_" : "/_") + v.suffix;
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf(
        "%s.ply: %llu triangles (%s), %llu vertices; %.1f%% needles (aspect > 10), %.2f%% above 50, "
        "worst %.0f; area %.4g (triangles %.3g to %.3g), volume %.4g; written in %.2fs (%.2fs with checks), "
        "+ %s.json\n",
        base.c_str(), static_cast<unsigned long long>(ntris), g.detail.c_str(), static_cast<unsigned long long>(nverts),
        100.0 * static_cast<double>(needles) / static_cast<double>(ntris),
        100.0 * static_cast<double>(worst_count) / static_cast<double>(ntris), worst, area, min_area, max_area, volume,
        gen_s, total_s, suffixes.c_str());
    return 0;
}
