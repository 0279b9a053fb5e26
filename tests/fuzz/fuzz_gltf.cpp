// libFuzzer target for the glTF import (rtconvert scene.gltf|glb scene.json): the input
// is a whole .glb or .gltf in memory (buffers inside it, or data URIs). Any outcome but a
// scene tree or an rt::InputError is a finding (a crash, a sanitizer report, a hang, an
// allocation beyond -rss_limit_mb). A tree that comes out must load as a scene, or fail to
// with an rt::InputError, which rtconvert reports instead of writing it.
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <string>

#include "rt/convert/convert.h"
#include "rt/core/error.h"
#include "rt/loader/scene_tree.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    try {
        rt::ConvertOptions o;
        o.camera = 0;  // every camera
        const std::string text =
            rt::gltf_to_json_text(std::string(reinterpret_cast<const char*>(data), size), "/nonexistent/fuzz.gltf", o);
        (void)rt::describe_scene(nlohmann::json::parse(text), "fuzz.json");
    } catch (const rt::InputError&) {
        // The expected answer to bad input.
    }
    return 0;
}
