// The renderer as the browser page drives it (src/web/, docs/web.md): one scene loaded and
// built once, then rendered in parts and traced pixel by pixel. Plain C++ with no
// browser in it, so that it is built and tested natively too; src/web/web_main.cpp
// exports it to JavaScript in both precisions.
#pragma once
#include <cstdint>
#include <string>

namespace rt::web {

// Loads and builds the scene file at `scene_path` (JSON; PLY files relative to it), with
// `options_json` ({"cull": true, "max_depth": -1, "epsilon_scale": 1, "min_weight":
// 1e-4, "rounding": "truncate", "samples": 0, "seed": 0, "sampler": "random"}, each key
// optional, "" for none; samples 0: each camera's NumSamples; seed: a whole number or a
// string of its digits; sampler: "random", "stratified" or "sobol", as --sampler).
// Returns "" or the command line's one-line error ("<file>: <place>: <what>"); the
// previous scene is released either way. Warnings are kept for scene_json.
std::string load(const std::string& scene_path, const std::string& options_json);

// The loaded scene's cameras and the warnings its loading raised, as JSON:
// {"cameras": [{"name": ImageName, "width": W, "height": H, "samples": N}, ...],
// "warnings": [...]}; samples per pixel as rendered (the options' samples, or NumSamples;
// 0: one ray through the centre).
std::string scene_json();

// Renders the tiles of part `part` of `parts` (rt/render/render.h, RenderOptions::part)
// of camera `camera` (0-based) into `rgba` (width x height x 4 bytes, row-major): their
// pixels with alpha 255, every other byte left as it was. Returns "" or an error.
std::string render_part(int camera, int part, int parts, uint8_t* rgba);

// Progressive rendering: adds samples [k0, k1) of each pixel of part `part` of `parts` of
// camera `camera` to the running sums the session keeps for that part's pixels, and writes
// their means over samples [0, k1) into `rgba` as render_part does (quantized with the
// options' rounding, alpha 255, every other byte left as it was). Sample k is the same
// sample of the same pattern as in a render of all the camera's N samples (max(1,
// samples)), so after [0, N) the part's bytes are render_part's. k0 must be the samples the
// part holds (0 starts it afresh); the sums are kept for one camera and part count at a
// time (a call with another drops them), a Real per channel per pixel.
std::string refine_part(int camera, int part, int parts, int k0, int k1, uint8_t* rgba);

// The ray tree of sample `sample` of pixel (x, y) of camera `camera` under the options'
// seed, as --trace-json writes it (--sample); on a bad camera, pixel or sample,
// {"error": "..."}.
std::string trace(int camera, int x, int y, int sample);

}  // namespace rt::web
