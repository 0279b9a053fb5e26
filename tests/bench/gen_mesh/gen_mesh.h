// gen_mesh's shared parts: vector arithmetic, the deterministic noise and random streams,
// the generated mesh with its scene variants, the scene JSON writer's types and the output
// file. One header for the generator's few translation units (tests/bench/gen_mesh/*.cpp,
// built by mk/bench.mk); nothing outside the generator includes it.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace gen_mesh {

constexpr double kPi = 3.14159265358979323846;

struct V3 {
    double x, y, z;
};
inline V3 operator+(V3 a, V3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V3 operator-(V3 a, V3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 operator*(double s, V3 a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(V3 a, V3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V3 cross(V3 a, V3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
inline double length(V3 a) { return std::sqrt(dot(a, a)); }
inline V3 normalize(V3 a) { return (1.0 / length(a)) * a; }

// Prints "gen_mesh: msg" to stderr and exits with status 1.
[[noreturn]] void die(const std::string& msg);

// ---- deterministic gradient noise and random numbers (noise.cpp) -------------------

uint64_t mix64(uint64_t x);  // splitmix64 finaliser

struct Noise {
    uint64_t seed;
    // Perlin-style gradient noise, roughly in [-1, 1].
    double operator()(V3 p) const;
    // Fractal sum of `octaves` octaves (lacunarity 2, gain 0.5), normalised to ~[-1, 1].
    double fbm(V3 p, int octaves) const;
};

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

// ---- scene JSON (scene_json.cpp) ------------------------------------------------------
// A tiny writer for the scene files: every value is a string or a nested object/array, two
// spaces per level, keys in the given order (the course's files and the knot's look so).

using Fields = std::vector<std::pair<std::string, std::string>>;  // key, JSON text of the value

std::string num(double x);
std::string num3(V3 v);

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

// The whole scene file, its one camera writing `image`.
std::string scene_json(const SceneDesc& d, const std::string& image);

// A plain (Blinn-Phong only) material with _id 1.
Fields phong(const char* ambient, const char* diffuse, const char* specular, const char* exponent);
// A mirror material: a plain one plus MirrorReflectance, with the given _id.
Fields mirror(int id, const char* ambient, const char* diffuse, const char* specular, const char* exponent,
              const char* reflectance);
extern const Fields kPlain, kGlass, kGold;  // mesh materials, _id 1
extern const Fields kFloorMirror;           // the floor's half mirror, _id 2
Fields with_id(Fields f, int id);
// Mesh 1 of material 1 read from the PLY file `ply`, smooth-shaded or not.
Fields ply_mesh(const std::string& ply, bool smooth);
// A square floor of two triangles (vertices 1-4), material 2; floor_vertices gives its corners.
extern const Fields kFloorMesh;
std::string floor_vertices(double half, double z);
// An object of radius ~70 at the origin over the half-mirror floor at height floor_z, lit
// by two point lights from the camera's side (the blob's and the soup's scenes).
SceneDesc over_mirror_floor(const std::string& ply, bool smooth, V3 position, V3 gaze, const char* resolution,
                            double floor_z);

// ---- the generated mesh ----------------------------------------------------------------

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

inline std::string u64(uint64_t v) { return std::to_string(v); }

// The shapes (one file each): about `target` triangles, the output a function of the
// arguments alone; `name` is the base name of the PLY file the scenes refer to.
Generated make_knot(uint64_t target, uint64_t seed, const std::string& name);
Generated make_blob(uint64_t target, uint64_t seed, const std::string& name);
Generated make_terrain(uint64_t target, uint64_t seed, const std::string& name);
Generated make_city(uint64_t target, uint64_t seed, const std::string& name);
Generated make_soup(uint64_t target, uint64_t seed, const std::string& name);

// ---- output (output.cpp) ---------------------------------------------------------------

// A file written under a temporary name (path + ".tmp") and renamed by commit(), so that an
// interrupted run leaves no half-written file; any failure ends the program (die).
struct Out {
    std::string path, tmp;
    FILE* f = nullptr;
    explicit Out(const std::string& p);
    void write(const void* data, size_t n);
    void write(const std::string& s) { write(s.data(), s.size()); }
    void commit();
};

// The mesh as a binary little-endian PLY file at `path`.
void write_ply(const std::string& path, const Generated& g);

}  // namespace gen_mesh
