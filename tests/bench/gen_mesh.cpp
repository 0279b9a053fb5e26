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
// Standalone C++17, no dependencies: g++ -O2 -std=c++17 -o gen_mesh gen_mesh.cpp
#include <algorithm>
#include <array>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace {

constexpr double kPi = 3.14159265358979323846;

struct V3 {
    double x, y, z;
};
V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double length(V3 a) { return std::sqrt(dot(a, a)); }
V3 normalize(V3 a) { return (1.0 / length(a)) * a; }

// ---- deterministic gradient noise ------------------------------------------------

uint64_t mix64(uint64_t x) {  // splitmix64 finaliser
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

struct Noise {
    uint64_t seed;

    // Gradient at a lattice point: one of the 12 cube-edge directions.
    double grad(int64_t ix, int64_t iy, int64_t iz, double fx, double fy, double fz) const {
        uint64_t h =
            mix64(seed ^ mix64(static_cast<uint64_t>(ix) * 0x8da6b343ull ^ static_cast<uint64_t>(iy) * 0xd8163841ull ^
                               static_cast<uint64_t>(iz) * 0xcb1ab31full));
        switch (h % 12) {
            case 0:
                return fx + fy;
            case 1:
                return -fx + fy;
            case 2:
                return fx - fy;
            case 3:
                return -fx - fy;
            case 4:
                return fx + fz;
            case 5:
                return -fx + fz;
            case 6:
                return fx - fz;
            case 7:
                return -fx - fz;
            case 8:
                return fy + fz;
            case 9:
                return -fy + fz;
            case 10:
                return fy - fz;
            default:
                return -fy - fz;
        }
    }
    static double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
    static double lerp(double a, double b, double t) { return a + t * (b - a); }

    // Perlin-style gradient noise, roughly in [-1, 1].
    double operator()(V3 p) const {
        const double flx = std::floor(p.x), fly = std::floor(p.y), flz = std::floor(p.z);
        const auto ix = static_cast<int64_t>(flx), iy = static_cast<int64_t>(fly), iz = static_cast<int64_t>(flz);
        const double fx = p.x - flx, fy = p.y - fly, fz = p.z - flz;
        const double u = fade(fx), v = fade(fy), w = fade(fz);
        const double x00 = lerp(grad(ix, iy, iz, fx, fy, fz), grad(ix + 1, iy, iz, fx - 1, fy, fz), u);
        const double x10 = lerp(grad(ix, iy + 1, iz, fx, fy - 1, fz), grad(ix + 1, iy + 1, iz, fx - 1, fy - 1, fz), u);
        const double x01 = lerp(grad(ix, iy, iz + 1, fx, fy, fz - 1), grad(ix + 1, iy, iz + 1, fx - 1, fy, fz - 1), u);
        const double x11 =
            lerp(grad(ix, iy + 1, iz + 1, fx, fy - 1, fz - 1), grad(ix + 1, iy + 1, iz + 1, fx - 1, fy - 1, fz - 1), u);
        return lerp(lerp(x00, x10, v), lerp(x01, x11, v), w);
    }

    // Fractal sum of `octaves` octaves (lacunarity 2, gain 0.5), normalised to ~[-1, 1].
    double fbm(V3 p, int octaves) const {
        double sum = 0, amp = 1, norm = 0;
        for (int o = 0; o < octaves; ++o) {
            sum += amp * (*this)(p);
            norm += amp;
            amp *= 0.5;
            p = 2.03 * p + V3{17.1, -3.7, 5.3};  // shift each octave off the previous lattice
        }
        return sum / norm;
    }
};

// ---- the knot ---------------------------------------------------------------------

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

// ---- output -----------------------------------------------------------------------

void die(const std::string& msg) {
    std::fprintf(stderr, "gen_mesh: %s\n", msg.c_str());
    std::exit(1);
}

struct Out {
    std::string path, tmp;
    FILE* f = nullptr;
    explicit Out(const std::string& p) : path(p), tmp(p + ".tmp") {
        f = std::fopen(tmp.c_str(), "wb");
        if (!f) die(tmp + ": cannot open: " + std::strerror(errno));
    }
    void write(const void* data, size_t n) {
        if (n && std::fwrite(data, 1, n, f) != n) die(tmp + ": write failed: " + std::strerror(errno));
    }
    void write(const std::string& s) { write(s.data(), s.size()); }
    void commit() {
        if (std::fclose(f) != 0) die(tmp + ": write failed: " + std::strerror(errno));
        f = nullptr;
        if (std::rename(tmp.c_str(), path.c_str()) != 0) die(path + ": cannot rename: " + std::strerror(errno));
    }
};

void put_u32(unsigned char* p, uint32_t v) {
    p[0] = static_cast<unsigned char>(v);
    p[1] = static_cast<unsigned char>(v >> 8);
    p[2] = static_cast<unsigned char>(v >> 16);
    p[3] = static_cast<unsigned char>(v >> 24);
}
void put_f32(unsigned char* p, float f) {
    uint32_t v;
    std::memcpy(&v, &f, 4);
    put_u32(p, v);
}

// ---- scene JSON ---------------------------------------------------------------------
// A tiny writer for the scene files: every value is a string or a nested object/array, two
// spaces per level, keys in the given order (the course's files and the knot's look so).

using Fields = std::vector<std::pair<std::string, std::string>>;  // key, JSON text of the value

std::string q(const std::string& s) { return "\"" + s + "\""; }
std::string pad(int n) { return std::string(static_cast<size_t>(n), ' '); }

std::string object(int indent, const Fields& fields) {
    std::string s = "{\n";
    for (size_t i = 0; i < fields.size(); ++i)
        s += pad(indent + 2) + q(fields[i].first) + ": " + fields[i].second + (i + 1 < fields.size() ? ",\n" : "\n");
    return s + pad(indent) + "}";
}
// An array of objects, each given as its fields (all string values).
std::string array(int indent, const std::vector<Fields>& items) {
    std::string s = "[\n";
    for (size_t i = 0; i < items.size(); ++i) {
        Fields quoted;
        for (const auto& [k, v] : items[i]) quoted.emplace_back(k, v.front() == '{' ? v : q(v));
        s += pad(indent + 2) + object(indent + 2, quoted) + (i + 1 < items.size() ? ",\n" : "\n");
    }
    return s + pad(indent) + "]";
}

std::string num(double x) {
    char b[32];
    std::snprintf(b, sizeof b, x == std::floor(x) && std::fabs(x) < 1e15 ? "%.0f" : "%.6g", x);
    return b;
}
std::string num3(V3 v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }

struct SceneDesc {
    std::string background = "0 0 0";
    V3 position, gaze;
    std::string fovy, resolution;
    std::string ambient = "25 25 25";
    std::vector<std::pair<V3, double>> lights;  // position, intensity (grey)
    std::string vertex_data;                    // "x y z ..." (ground corners, sphere centres)
    std::vector<Fields> materials;              // _id "1" is the mesh's
    std::vector<Fields> meshes, spheres;
};

std::string scene_json(const SceneDesc& d, const std::string& image) {
    std::vector<Fields> lights;
    for (size_t i = 0; i < d.lights.size(); ++i) {
        const std::string I = num(d.lights[i].second);
        lights.push_back({{"_id", std::to_string(i + 1)},
                          {"Position", num3(d.lights[i].first)},
                          {"Intensity", I + " " + I + " " + I}});
    }
    Fields objects{{"Mesh", array(6, d.meshes)}};
    if (!d.spheres.empty()) objects.emplace_back("Sphere", array(6, d.spheres));
    const Fields scene{
        {"BackgroundColor", q(d.background)},
        {"MaxRecursionDepth", q("6")},
        {"ShadowRayEpsilon", q("1e-3")},
        {"Cameras", object(4, {{"Camera", object(6, {{"_id", q("1")},
                                                     {"_type", q("lookAt")},
                                                     {"Position", q(num3(d.position))},
                                                     {"GazePoint", q(num3(d.gaze))},
                                                     {"Up", q("0 0 1")},
                                                     {"FovY", q(d.fovy)},
                                                     {"NearDistance", q("1")},
                                                     {"ImageResolution", q(d.resolution)},
                                                     {"ImageName", q(image)}})}})},
        {"Lights", object(4, {{"AmbientLight", q(d.ambient)}, {"PointLight", array(6, lights)}})},
        {"VertexData", object(4, {{"_data", q(d.vertex_data)}, {"_type", q("xyz")}})},
        {"Materials", object(4, {{"Material", array(6, d.materials)}})},
        {"Objects", object(4, objects)},
    };
    return object(0, {{"Scene", object(2, scene)}}) + "\n";
}

// A plain (Blinn-Phong only) material with _id 1.
Fields phong(const char* ambient, const char* diffuse, const char* specular, const char* exponent) {
    return {{"_id", "1"},
            {"AmbientReflectance", ambient},
            {"DiffuseReflectance", diffuse},
            {"SpecularReflectance", specular},
            {"PhongExponent", exponent}};
}
// A mirror material: a plain one plus MirrorReflectance, with the given _id.
Fields mirror(int id, const char* ambient, const char* diffuse, const char* specular, const char* exponent,
              const char* reflectance) {
    Fields f = phong(ambient, diffuse, specular, exponent);
    f[0].second = std::to_string(id);
    f.insert(f.begin() + 1, {"_type", "mirror"});
    f.emplace_back("MirrorReflectance", reflectance);
    return f;
}
const Fields kPlain = phong("0.15 0.12 0.1", "0.55 0.42 0.32", "0.5 0.5 0.5", "40");
const Fields kGlass{{"_id", "1"},
                    {"_type", "dielectric"},
                    {"AmbientReflectance", "0 0 0"},
                    {"DiffuseReflectance", "0 0 0"},
                    {"SpecularReflectance", "0.5 0.5 0.5"},
                    {"PhongExponent", "50"},
                    {"MirrorReflectance", "1 1 1"},
                    {"RefractionIndex", "1.5"},
                    {"AbsorptionCoefficient", "0.004 0.002 0.006"}};
const Fields kGold{{"_id", "1"},
                   {"_type", "conductor"},
                   {"AmbientReflectance", "0 0 0"},
                   {"DiffuseReflectance", "0 0 0"},
                   {"SpecularReflectance", "1 0.86 0.57"},
                   {"PhongExponent", "5"},
                   {"MirrorReflectance", "1 0.86 0.57"},
                   {"RefractionIndex", "0.370"},
                   {"AbsorptionIndex", "2.820"}};
// The floor's half mirror (material 2 of the knot's scenes).
const Fields kFloorMirror = mirror(2, "0.1 0.1 0.1", "0.5 0.5 0.5", "0 0 0", "1", "0.5 0.5 0.5");

Fields with_id(Fields f, int id) {
    f[0].second = std::to_string(id);
    return f;
}
Fields ply_mesh(const std::string& ply, bool smooth) {
    Fields m{{"_id", "1"}, {"Material", "1"}};
    if (smooth) m.emplace_back("_shadingMode", "smooth");
    m.emplace_back("Faces", "{\n            \"_plyFile\": " + q(ply) + "\n          }");
    return m;
}
// A square floor of two triangles at height z (vertices 1-4), material 2.
const Fields kFloorMesh{
    {"_id", "2"},
    {"Material", "2"},
    {"Faces", "{\n            \"_data\": \"1 2 3 3 4 1\",\n            \"_type\": \"triangle\"\n          }"}};
std::string floor_vertices(double half, double z) {
    const std::string h = num(half), m = num(-half), zs = num(z);
    return m + " " + m + " " + zs + " " + h + " " + m + " " + zs + " " + h + " " + h + " " + zs + " " + m + " " + h +
           " " + zs;
}

// An object of radius ~70 at the origin over the half-mirror floor at height floor_z, lit
// by two point lights from the camera's side (the blob's and the soup's scenes).
SceneDesc over_mirror_floor(const std::string& ply, bool smooth, V3 position, V3 gaze, const char* resolution,
                            double floor_z) {
    SceneDesc d;
    d.position = position;
    d.gaze = gaze;
    d.fovy = "42";
    d.resolution = resolution;
    d.lights = {{{250, -250, 250}, 4e7}, {{-320, -120, 180}, 2.5e7}};
    d.vertex_data = floor_vertices(1000, floor_z);
    d.meshes = {ply_mesh(ply, smooth), kFloorMesh};
    return d;
}

// ---- shapes -----------------------------------------------------------------------

struct Rng {  // splitmix64 stream
    uint64_t state;
    uint64_t next() { return mix64(state += 0x9e3779b97f4a7c15ull); }
    double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
    double uniform(double a, double b) { return a + (b - a) * uniform(); }
    double log_uniform(double a, double b) { return a * std::exp(std::log(b / a) * uniform()); }
    double gauss() {
        const double u = 1 - uniform(), v = uniform();
        return std::sqrt(-2 * std::log(u)) * std::cos(2 * kPi * v);
    }
    V3 unit() {
        const double z = uniform(-1, 1), a = uniform(0, 2 * kPi), r = std::sqrt(1 - z * z);
        return {r * std::cos(a), r * std::sin(a), z};
    }
};

struct Variant {
    std::string suffix;
    SceneDesc scene;
};

struct Generated {
    std::vector<float> pos;     // x y z per vertex, world space
    std::vector<uint32_t> tri;  // three vertex indices per triangle, in file order
    std::string comment;        // the PLY header's comment after "gen_mesh: "
    std::string detail;         // the summary line's parenthesis
    bool closed = true;         // closed, facing outwards: the signed volume must be > 0
    std::vector<Variant> variants;

    uint32_t add(V3 p) {
        pos.push_back(static_cast<float>(p.x));
        pos.push_back(static_cast<float>(p.y));
        pos.push_back(static_cast<float>(p.z));
        return static_cast<uint32_t>(pos.size() / 3 - 1);
    }
    void face(uint32_t a, uint32_t b, uint32_t c) { tri.insert(tri.end(), {a, b, c}); }
};

std::string u64(uint64_t v) { return std::to_string(v); }

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

    // PLY.
    const std::string ply_name = name + ".ply";
    {
        Out out(out_dir + "/" + ply_name);
        char header[512];
        std::snprintf(header, sizeof header,
                      "ply\nformat binary_little_endian 1.0\n"
                      "comment raytracer tests/bench/gen_mesh: %s\n"
                      "element vertex %llu\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face %llu\nproperty list uchar int vertex_indices\nend_header\n",
                      g.comment.c_str(), static_cast<unsigned long long>(nverts),
                      static_cast<unsigned long long>(ntris));
        out.write(std::string(header));
        std::vector<unsigned char> buf;
        buf.reserve(1 << 20);
        auto flush = [&](bool force) {
            if (force || buf.size() > (1u << 20) - 64) {
                out.write(buf.data(), buf.size());
                buf.clear();
            }
        };
        for (float x : g.pos) {
            unsigned char b4[4];
            put_f32(b4, x);
            buf.insert(buf.end(), b4, b4 + 4);
            flush(false);
        }
        for (uint64_t t = 0; t < ntris; ++t) {
            unsigned char rec[13];
            rec[0] = 3;
            put_u32(rec + 1, g.tri[3 * t]);
            put_u32(rec + 5, g.tri[3 * t + 1]);
            put_u32(rec + 9, g.tri[3 * t + 2]);
            buf.insert(buf.end(), rec, rec + 13);
            flush(false);
        }
        flush(true);
        out.commit();
    }
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
