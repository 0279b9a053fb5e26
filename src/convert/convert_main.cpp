// rtconvert: converts scenes between the course's XML format, our JSON format,
// Wavefront OBJ (+MTL), glTF 2.0 and binary PLY. See rt/convert/convert.h and the README.
#include <cmath>
#include <cstdio>
#include <new>
#include <string>
#include <vector>

#include "rt/cli/options.h"
#include "rt/convert/convert.h"
#include "rt/core/error.h"

namespace {

const rt::cli::Program kProgram{
    "rtconvert", "rtconvert 1.0",
    "usage: rtconvert [--shading auto|flat|smooth] [--size WxH] [--image NAME] [--camera N|all]\n"
    "                 [--bake-transforms] [--light-scale X] [--sphere-segments N] [-q] INPUT OUTPUT",
    "Converts INPUT to OUTPUT, the direction chosen by their extensions:\n"
    "  scene.xml  -> scene.json   the course's XML format to JSON (as the course converted its scenes)\n"
    "  scene.json -> scene.xml    and back; relative PLY paths follow the output to its folder\n"
    "  model.obj  -> scene.json   OBJ (+MTL) to a JSON scene and one binary PLY per mesh\n"
    "                             (scene_1.ply, ...) beside it, with a camera framing the model,\n"
    "                             an ambient and a point light (also -> scene.xml)\n"
    "  scene.json -> model.obj    a scene (JSON or XML) to OBJ + MTL (model.mtl) beside it\n"
    "  scene.gltf -> scene.json   glTF 2.0 (.gltf or .glb) to a JSON scene and one binary PLY per\n"
    "                             mesh beside it: nodes as transformations and instances, cameras,\n"
    "                             point lights, materials (docs/gltf.md)\n"
    "  scene.json -> scene.gltf   a scene to glTF 2.0 (+ scene.bin), or to one .glb file\n",
    "exit status: 0 converted, 1 bad input or an output could not be written, 2 usage error"};

}  // namespace

int main(int argc, char** argv) {
    namespace cli = rt::cli;
    rt::ConvertOptions options;
    bool quiet = false;
    std::vector<std::string> files;
    CLI::App app;
    cli::setup(app, kProgram);
    const std::string obj_import = "options (OBJ import)", model_import = "options (OBJ and glTF import)",
                      gltf_import = "options (glTF import)", gltf = "options (glTF import and export)",
                      obj_export = "options (OBJ and glTF export)";
    cli::add_choice(
        app, "--shading", "auto (default: smooth where the OBJ has normals or smoothing groups), flat or smooth",
        options.shading,
        {{"auto", rt::ObjShading::Auto}, {"flat", rt::ObjShading::Flat}, {"smooth", rt::ObjShading::Smooth}})
        ->group(obj_import);
    cli::add_value(app, "--size", "WxH", "the camera's image resolution (default 800x600)",
                   [&options](const std::string& v) {
                       const size_t x = v.find('x');
                       if (x == std::string::npos) cli::usage_error("--size takes WIDTHxHEIGHT, got '" + v + "'");
                       options.width = static_cast<int>(cli::whole_number("--size", v.substr(0, x), 1, 16384));
                       options.height = static_cast<int>(cli::whole_number("--size", v.substr(x + 1), 1, 16384));
                       options.size_given = true;
                   })
        ->group(model_import);
    cli::add_text(app, "--image", "NAME", "the camera's image name (default: OUTPUT's stem + .png)", options.image_name,
                  "a name")
        ->group(model_import);
    cli::add_value(app, "--camera", "N|all", "which glTF camera: the N-th of the file's cameras, or all (default 1)",
                   [&options](const std::string& v) {
                       options.camera = v == "all" ? 0 : static_cast<int>(cli::whole_number("--camera", v, 1, 1 << 20));
                   })
        ->group(gltf_import);
    app.add_flag("--bake-transforms", options.bake_transforms,
                 "apply node matrices to the vertices instead of writing Transformations and instances")
        ->group(gltf_import);
    cli::add_number(app, "--light-scale", "X",
                    "course Intensity per candela of a glTF point light (default 255/(683 pi), docs/gltf.md)",
                    options.light_scale, "a positive number", [](double x) { return x > 0 && std::isfinite(x); })
        ->group(gltf);
    cli::add_whole(app, "--sphere-segments", "N", "segments around each tessellated sphere (default 128)",
                   options.sphere_segments, 3, 4096)
        ->group(obj_export);
    app.add_flag("-q,--quiet", quiet, "print errors only");
    cli::add_two_files(app, files, "needs an INPUT and an OUTPUT file");
    if (const auto status = cli::parse(app, kProgram, argc, argv)) return *status;

    try {
        const rt::ConvertResult r = rt::convert_file(files[0], files[1], options);
        if (!quiet) {
            for (const std::string& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
            for (const std::string& n : r.notes) std::fprintf(stderr, "%s\n", n.c_str());
            for (const std::string& f : r.written) std::fprintf(stderr, "wrote %s\n", f.c_str());
        }
        return 0;
    } catch (const rt::InputError& e) {
        rt::cli::print_error(e.what());
    } catch (const std::bad_alloc&) {
        rt::cli::print_error(files[0] + ": out of memory");
    } catch (const std::exception& e) {
        // Not expected (every bad input is an InputError); still one line, no crash.
        rt::cli::print_error(files[0] + ": cannot convert: " + e.what());
    }
    return 1;
}
