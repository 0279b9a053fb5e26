// gen_mesh: writes a large benchmark mesh (binary little-endian PLY) and three scenes
// in the course's JSON format that use it (diffuse, glass, gold), for `make bench`.
//
//   gen_mesh [--out-dir DIR] [--name NAME] [--seed N] TRIANGLES
//
// TRIANGLES is a count, optionally with a K or M suffix (1M, 4M, 16M). The surface is a
// closed, watertight tube around a trefoil knot, counter-clockwise seen from outside:
// a (u, v) grid of ~2 * Nu * Nv triangles, its radius displaced by deterministic
// multi-octave gradient noise (a fixed seed), with the geometric character of scanned
// models: dense, curved and bumpy, and a fraction of needle triangles, from two regions
// where the grid is deliberately anisotropic (rings bunched along the knot in one,
// vertices bunched around the tube in the other).
//
// Written: DIR/NAME.ply, DIR/NAME_plain.json, DIR/NAME_glass.json, DIR/NAME_gold.json
// (NAME defaults to knot_<count>, e.g. knot_1m). Each file is written under a temporary
// name and renamed, so an interrupted run leaves no half-written file. The output
// depends only on the arguments: same arguments, same bytes.
//
// Standalone C++17, no dependencies: g++ -O2 -std=c++17 -o gen_mesh gen_mesh.cpp
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
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

std::string scene_json(const std::string& ply, const std::string& image, const std::string& material) {
    return R"({
  "Scene": {
    "BackgroundColor": "0 0 0",
    "MaxRecursionDepth": "6",
    "ShadowRayEpsilon": "1e-3",
    "Cameras": {
      "Camera": {
        "_id": "1",
        "_type": "lookAt",
        "Position": "520 -120 150",
        "GazePoint": "0 100 5",
        "Up": "0 0 1",
        "FovY": "38",
        "NearDistance": "1",
        "ImageResolution": "800 480",
        "ImageName": ")" +
           image + R"("
      }
    },
    "Lights": {
      "AmbientLight": "25 25 25",
      "PointLight": [
        {
          "_id": "1",
          "Position": "400 100 200",
          "Intensity": "50000000 50000000 50000000"
        },
        {
          "_id": "2",
          "Position": "600 -200 200",
          "Intensity": "50000000 50000000 50000000"
        }
      ]
    },
    "VertexData": {
      "_data": "-1000 -1000 -100 1000 -1000 -100 1000 1000 -100 -1000 1000 -100",
      "_type": "xyz"
    },
    "Materials": {
      "Material": [
)" + material +
           R"(,
        {
          "_id": "2",
          "_type": "mirror",
          "AmbientReflectance": "0.1 0.1 0.1",
          "DiffuseReflectance": "0.5 0.5 0.5",
          "SpecularReflectance": "0 0 0",
          "PhongExponent": "1",
          "MirrorReflectance": "0.5 0.5 0.5"
        }
      ]
    },
    "Objects": {
      "Mesh": [
        {
          "_id": "1",
          "Material": "1",
          "_shadingMode": "smooth",
          "Faces": {
            "_plyFile": ")" +
           ply + R"("
          }
        },
        {
          "_id": "2",
          "Material": "2",
          "Faces": {
            "_data": "1 2 3 3 4 1",
            "_type": "triangle"
          }
        }
      ]
    }
  }
}
)";
}

const char* kPlain = R"(        {
          "_id": "1",
          "AmbientReflectance": "0.15 0.12 0.1",
          "DiffuseReflectance": "0.55 0.42 0.32",
          "SpecularReflectance": "0.5 0.5 0.5",
          "PhongExponent": "40"
        })";
const char* kGlass = R"(        {
          "_id": "1",
          "_type": "dielectric",
          "AmbientReflectance": "0 0 0",
          "DiffuseReflectance": "0 0 0",
          "SpecularReflectance": "0.5 0.5 0.5",
          "PhongExponent": "50",
          "MirrorReflectance": "1 1 1",
          "RefractionIndex": "1.5",
          "AbsorptionCoefficient": "0.004 0.002 0.006"
        })";
const char* kGold = R"(        {
          "_id": "1",
          "_type": "conductor",
          "AmbientReflectance": "0 0 0",
          "DiffuseReflectance": "0 0 0",
          "SpecularReflectance": "1 0.86 0.57",
          "PhongExponent": "5",
          "MirrorReflectance": "1 0.86 0.57",
          "RefractionIndex": "0.370",
          "AbsorptionIndex": "2.820"
        })";

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

}  // namespace

int main(int argc, char** argv) {
    std::string out_dir = ".", name, count_arg;
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
        else if (a == "-h" || a == "--help") {
            std::printf("usage: gen_mesh [--out-dir DIR] [--name NAME] [--seed N] TRIANGLES (e.g. 1M, 4M, 16M)\n");
            return 0;
        } else if (!a.empty() && a[0] == '-')
            die("unknown option " + a);
        else if (count_arg.empty())
            count_arg = a;
        else
            die("one triangle count only");
    }
    if (count_arg.empty()) die("usage: gen_mesh [--out-dir DIR] [--name NAME] [--seed N] TRIANGLES");
    const uint64_t target = parse_count(count_arg);
    if (name.empty()) name = "knot_" + count_name(target);
    const auto t0 = std::chrono::steady_clock::now();

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
    const uint64_t nverts = nu * nv, ntris = 2 * nu * nv;
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
    std::vector<float> pos(3 * nverts);
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
            const V3 w = to_world(c + r * o);
            float* dst = &pos[3 * (i * nv + j)];
            dst[0] = static_cast<float>(w.x);
            dst[1] = static_cast<float>(w.y);
            dst[2] = static_cast<float>(w.z);
        }
    }
    auto vid = [&](uint64_t i, uint64_t j) { return static_cast<uint32_t>((i % nu) * nv + (j % nv)); };
    // Every triangle, in file order. Quad (i, j)-(i+1, j)-(i+1, j+1)-(i, j+1): d/dv x d/du
    // points outwards, so each triangle goes along v first. The diagonal alternates in a
    // checkerboard, as meshers do.
    auto each_triangle = [&](auto&& f) {
        for (uint64_t i = 0; i < nu; ++i) {
            for (uint64_t j = 0; j < nv; ++j) {
                const uint32_t p00 = vid(i, j), p10 = vid(i + 1, j), p11 = vid(i + 1, j + 1), p01 = vid(i, j + 1);
                if ((i + j) & 1) {
                    f(p00, p01, p11);
                    f(p00, p11, p10);
                } else {
                    f(p00, p01, p10);
                    f(p01, p11, p10);
                }
            }
        }
    };

    // PLY.
    const std::string ply_name = name + ".ply";
    {
        Out out(out_dir + "/" + ply_name);
        char header[512];
        std::snprintf(header, sizeof header,
                      "ply\nformat binary_little_endian 1.0\n"
                      "comment raytracer tests/bench/gen_mesh: trefoil tube, %llu x %llu grid, seed %llu\n"
                      "element vertex %llu\nproperty float x\nproperty float y\nproperty float z\n"
                      "element face %llu\nproperty list uchar int vertex_indices\nend_header\n",
                      static_cast<unsigned long long>(nu), static_cast<unsigned long long>(nv),
                      static_cast<unsigned long long>(seed), static_cast<unsigned long long>(nverts),
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
        for (uint64_t k = 0; k < 3 * nverts; ++k) {
            unsigned char b4[4];
            put_f32(b4, pos[k]);
            buf.insert(buf.end(), b4, b4 + 4);
            flush(false);
        }
        auto tri = [&](uint32_t a, uint32_t b, uint32_t c) {
            unsigned char rec[13];
            rec[0] = 3;
            put_u32(rec + 1, a);
            put_u32(rec + 5, b);
            put_u32(rec + 9, c);
            buf.insert(buf.end(), rec, rec + 13);
            flush(false);
        };
        each_triangle(tri);
        flush(true);
        out.commit();
    }
    const double gen_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    // Statistics: enclosed volume (> 0 when the triangles face outwards), needles (longest
    // edge over shortest altitude above 10), the same loop as the faces.
    double volume = 0, area = 0;
    uint64_t needles = 0, worst_count = 0;
    double worst = 0;
    auto P = [&](uint32_t k) { return V3{pos[3 * k], pos[3 * k + 1], pos[3 * k + 2]}; };
    auto stat = [&](uint32_t a, uint32_t b, uint32_t c) {
        const V3 pa = P(a), pb = P(b), pc = P(c);
        const V3 cr = cross(pb - pa, pc - pa);
        volume += dot(pa, cross(pb, pc)) / 6;
        const double twice_area = length(cr);
        area += twice_area / 2;
        const double e = std::max({length(pb - pa), length(pc - pb), length(pa - pc)});
        const double aspect = twice_area > 0 ? e * e / twice_area : 1e30;  // longest edge / its altitude
        if (aspect > 10) ++needles;
        if (aspect > 50) ++worst_count;
        worst = std::max(worst, aspect);
    };
    each_triangle(stat);
    if (!(volume > 0)) die("internal error: the mesh faces inwards (signed volume " + std::to_string(volume) + ")");

    const std::string base = out_dir + "/" + name;
    const struct {
        const char* suffix;
        const char* material;
    } variants[] = {{"plain", kPlain}, {"glass", kGlass}, {"gold", kGold}};
    for (const auto& v : variants) {
        const std::string scene_name = name + "_" + v.suffix;
        Out out(base + "_" + v.suffix + ".json");
        out.write(scene_json(ply_name, scene_name + ".png", v.material));
        out.commit();
    }
    const double total_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf(
        "%s.ply: %llu triangles (%llu x %llu grid x 2), %llu vertices; %.1f%% needles "
        "(aspect > 10), %.2f%% above 50, worst %.0f; area %.4g, volume %.4g; "
        "written in %.2fs (%.2fs with checks), + _plain/_glass/_gold.json\n",
        base.c_str(), static_cast<unsigned long long>(ntris), static_cast<unsigned long long>(nu),
        static_cast<unsigned long long>(nv), static_cast<unsigned long long>(nverts),
        100.0 * static_cast<double>(needles) / static_cast<double>(ntris),
        100.0 * static_cast<double>(worst_count) / static_cast<double>(ntris), worst, area, volume, gen_s, total_s);
    return 0;
}
