// rtconvert: converts scenes between the course's XML format, our JSON format,
// Wavefront OBJ (+MTL) and binary PLY. See rt/convert.h and the README.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>
#include <vector>

#include "rt/convert.h"
#include "rt/error.h"

namespace {

const char* kVersion = "rtconvert 1.0";
const char* kUsage =
    "usage: rtconvert [--shading auto|flat|smooth] [--size WxH] [--image NAME] [--sphere-segments N] [-q] INPUT OUTPUT";

void print_help() {
    std::printf(
        "%s\n\n"
        "Converts INPUT to OUTPUT, the direction chosen by their extensions:\n"
        "  scene.xml  -> scene.json   the course's XML format to JSON (as the course converted its scenes)\n"
        "  scene.json -> scene.xml    and back; relative PLY paths follow the output to its folder\n"
        "  model.obj  -> scene.json   OBJ (+MTL) to a JSON scene and one binary PLY per mesh\n"
        "                             (scene_1.ply, ...) beside it, with a camera framing the model,\n"
        "                             an ambient and a point light (also -> scene.xml)\n"
        "  scene.json -> model.obj    a scene (JSON or XML) to OBJ + MTL (model.mtl) beside it\n\n"
        "options (OBJ import):\n"
        "      --shading MODE       auto (default: smooth where the OBJ has normals or smoothing\n"
        "                           groups), flat or smooth\n"
        "      --size WxH           the camera's image resolution (default 800x600)\n"
        "      --image NAME         the camera's image name (default: OUTPUT's stem + .png)\n"
        "options (OBJ export):\n"
        "      --sphere-segments N  segments around each tessellated sphere (default 48)\n"
        "  -q, --quiet              print errors only\n"
        "  -h, --help               show this help\n"
        "      --version            show the version\n\n"
        "exit status: 0 converted, 1 bad input or an output could not be written, 2 usage error\n",
        kUsage);
}

[[noreturn]] void usage_error(const std::string& msg) {
    std::fprintf(stderr, "rtconvert: %s\n%s\n", msg.c_str(), kUsage);
    std::exit(2);
}

long whole_number(const std::string& text, const std::string& what, long lo, long hi) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || n < lo || n > hi)
        usage_error(what + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                    ", got '" + text + "'");
    return n;
}

}  // namespace

int main(int argc, char** argv) {
    rt::ConvertOptions options;
    bool quiet = false, only_files = false;
    std::vector<std::string> files;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&](const std::string& name) -> std::string {
            const size_t eq = a.find('=');
            if (eq != std::string::npos) return a.substr(eq + 1);
            if (i + 1 >= argc) usage_error("option " + name + " needs a value");
            return argv[++i];
        };
        auto is = [&](const char* name) { return a == name || a.rfind(std::string(name) + "=", 0) == 0; };
        if (only_files || a.empty() || a[0] != '-' || a == "-") {
            files.push_back(a);
        } else if (a == "--") {
            only_files = true;
        } else if (a == "-h" || a == "--help") {
            print_help();
            return 0;
        } else if (a == "--version") {
            std::printf("%s\n", kVersion);
            return 0;
        } else if (a == "-q" || a == "--quiet") {
            quiet = true;
        } else if (is("--shading")) {
            const std::string v = value("--shading");
            if (v == "auto") options.shading = rt::ObjShading::Auto;
            else if (v == "flat") options.shading = rt::ObjShading::Flat;
            else if (v == "smooth") options.shading = rt::ObjShading::Smooth;
            else usage_error("--shading takes auto, flat or smooth, got '" + v + "'");
        } else if (is("--size")) {
            const std::string v = value("--size");
            const size_t x = v.find('x');
            if (x == std::string::npos) usage_error("--size takes WIDTHxHEIGHT, got '" + v + "'");
            options.width = static_cast<int>(whole_number(v.substr(0, x), "--size", 1, 16384));
            options.height = static_cast<int>(whole_number(v.substr(x + 1), "--size", 1, 16384));
        } else if (is("--image")) {
            options.image_name = value("--image");
            if (options.image_name.empty()) usage_error("--image needs a name");
        } else if (is("--sphere-segments")) {
            options.sphere_segments = static_cast<int>(whole_number(value("--sphere-segments"), "--sphere-segments", 3, 4096));
        } else {
            usage_error("unknown option '" + a + "'");
        }
    }
    if (files.size() != 2) usage_error(files.size() < 2 ? "needs an INPUT and an OUTPUT file" : "too many files");

    try {
        const rt::ConvertResult r = rt::convert_file(files[0], files[1], options);
        if (!quiet) {
            for (const std::string& w : r.warnings) std::fprintf(stderr, "warning: %s\n", w.c_str());
            for (const std::string& n : r.notes) std::fprintf(stderr, "%s\n", n.c_str());
            for (const std::string& f : r.written) std::fprintf(stderr, "wrote %s\n", f.c_str());
        }
        return 0;
    } catch (const rt::InputError& e) {
        std::fprintf(stderr, "%s\n", e.what());
    } catch (const std::bad_alloc&) {
        std::fprintf(stderr, "%s: out of memory\n", files[0].c_str());
    } catch (const std::exception& e) {
        // Not expected (every bad input is an InputError); still one line, no crash.
        std::fprintf(stderr, "%s: cannot convert: %s\n", files[0].c_str(), e.what());
    }
    return 1;
}
