// gen_mesh's scene files: the JSON writer (values are strings or nested objects and arrays,
// two spaces per level, keys in the given order), the materials, the mirror floor and the
// camera-and-lights set-up the shapes' scenes share.
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include "gen_mesh.h"

namespace gen_mesh {

namespace {

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

}  // namespace

std::string num(double x) {
    char b[32];
    std::snprintf(b, sizeof b, x == std::floor(x) && std::fabs(x) < 1e15 ? "%.0f" : "%.6g", x);
    return b;
}
std::string num3(V3 v) { return num(v.x) + " " + num(v.y) + " " + num(v.z); }

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

Fields phong(const char* ambient, const char* diffuse, const char* specular, const char* exponent) {
    return {{"_id", "1"},
            {"AmbientReflectance", ambient},
            {"DiffuseReflectance", diffuse},
            {"SpecularReflectance", specular},
            {"PhongExponent", exponent}};
}
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
const Fields kFloorMesh{
    {"_id", "2"},
    {"Material", "2"},
    {"Faces", "{\n            \"_data\": \"1 2 3 3 4 1\",\n            \"_type\": \"triangle\"\n          }"}};
std::string floor_vertices(double half, double z) {
    const std::string h = num(half), m = num(-half), zs = num(z);
    return m + " " + m + " " + zs + " " + h + " " + m + " " + zs + " " + h + " " + h + " " + zs + " " + m + " " + h +
           " " + zs;
}

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

}  // namespace gen_mesh
