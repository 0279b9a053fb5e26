// Shared by the tests of ./raytracer's command line (tests/test_cli_*.cpp): the sample
// scene they render, edits to it through JSON pointers, scene files written into temporary
// folders, and checks on the output and the images.
#pragma once
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace cli_test {

// The sample scene of spec section 7, with a second material (a mirror) and a
// second sphere so that arrays appear in /Scene/Materials and /Scene/Objects/Sphere.
// ImageName `image`, ImageResolution `resolution`.
nlohmann::ordered_json sample_scene(const std::string& image = "simple.png", const std::string& resolution = "16 16");

// Replaces the single camera by one camera per (ImageName, resolution).
nlohmann::ordered_json with_cameras(nlohmann::ordered_json j,
                                    const std::vector<std::pair<std::string, std::string>>& cams);

// Sets, or erases, the value at a JSON pointer.
void set_at(nlohmann::ordered_json& j, const std::string& pointer, const nlohmann::ordered_json& value);
void erase_at(nlohmann::ordered_json& j, const std::string& pointer);

// Writes j to dir/name and returns that path.
std::string write_scene(const std::string& dir, const std::string& name, const nlohmann::ordered_json& j);

// How many lines of `text` contain `needle`.
int count_lines_containing(const std::string& text, const std::string& needle);

// A run's exit status, stderr and stdout, for failure messages.
std::string dump(const RunResult& r);

// The strings as "{a, b, c}", for failure messages.
std::string join(const std::vector<std::string>& v);

// Checks that `path` is a PNG of the given size.
::testing::AssertionResult is_png(const std::string& path, int width, int height);

}  // namespace cli_test
