// libFuzzer target for the JSON scene loader, the scene builder and a few camera
// rays: the input is the text of a scene file. The scene "lives" in a scratch
// folder holding two small PLY files (mesh.ply, ascii; bin.ply, binary), so
// "_plyFile" references can resolve. Any outcome but a scene or an rt::InputError
// is a finding. NaN radiance from a scene that loaded is counted and reported at
// exit (RT_FUZZ_NAN_ABORT=1 makes it a finding): scenes with values near the
// double range can make NaN in the renderer, whose files the fuzzer does not own.
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/shading.h"

namespace {

std::string g_scene_path;
long g_nan_inputs = 0;
bool g_nan_abort = false;

void report_nans() { std::fprintf(stderr, "fuzz_scene: %ld input(s) gave NaN radiance\n", g_nan_inputs); }

void write_file(const std::string& path, const std::string& bytes) {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (!f) std::abort();
    std::fwrite(bytes.data(), 1, bytes.size(), f);
    std::fclose(f);
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    std::string tmpl = std::filesystem::temp_directory_path().string() + "/rt_fuzz_scene_XXXXXX";
    if (!mkdtemp(tmpl.data())) std::abort();
    const std::string dir = tmpl;
    write_file(dir + "/mesh.ply",
               "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
               "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n"
               "-1 -1 -2\n1 -1 -2\n1 1 -2\n-1 1 -2\n3 0 1 2\n3 0 2 3\n");
    std::string bin =
        "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
    const float v[9] = {-1, -1, -3, 1, -1, -3, 0, 1, -3};
    bin.append(reinterpret_cast<const char*>(v), sizeof v);
    const unsigned char face[13] = {3, 0, 0, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0};
    bin.append(reinterpret_cast<const char*>(face), sizeof face);
    write_file(dir + "/bin.ply", bin);
    g_scene_path = dir + "/scene.json";
    const char* e = std::getenv("RT_FUZZ_NAN_ABORT");
    g_nan_abort = e && *e == '1';
    std::atexit(report_nans);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    rt::SceneDesc desc;
    try {
        desc = rt::parse_scene(std::string(reinterpret_cast<const char*>(data), size), g_scene_path);
    } catch (const rt::InputError&) {
        return 0;  // the expected answer to bad input
    }
    // A loaded scene must build and render. Keep the work per input small: a few
    // rays per camera, a bounded recursion depth, a bounded primitive count.
    size_t tris = 0;
    for (const rt::MeshDesc& m : desc.meshes) tris += m.indices.size() / 3;
    if (tris + desc.all<rt::SphereDesc>().size() > 5000) return 0;
    if (desc.max_recursion_depth > 8) desc.max_recursion_depth = 8;
    const rt::Scene scene = rt::build_scene(desc);
    const rt::TraceOptions opt{true};
    bool nan = false;
    for (size_t c = 0; c < scene.setup.cameras.size() && c < 2; ++c) {
        const rt::Camera& cam = scene.setup.cameras[c];
        const int xs[3] = {0, cam.width / 2, cam.width - 1};
        const int ys[3] = {0, cam.height / 2, cam.height - 1};
        for (int yi = 0; yi < 3; ++yi)
            for (int xi = 0; xi < 3; ++xi) {
                const rt::Vec3 col = rt::trace_primary(scene, cam.primary_ray(xs[xi], ys[yi]), opt);
                // NaN radiance is a finding; +inf (from huge intensities) is clamped
                // to 255 by quantize and is not an error.
                if (std::isnan(col.x) || std::isnan(col.y) || std::isnan(col.z)) {
                    if (g_nan_abort) {
                        std::fprintf(stderr, "NaN radiance at camera %zu pixel (%d, %d)\n", c, xs[xi], ys[yi]);
                        std::abort();
                    }
                    nan = true;
                }
            }
    }
    g_nan_inputs += nan;
    return 0;
}
