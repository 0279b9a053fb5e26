// A count with its noun, for messages: "1 sphere", "3 spheres", "1 mesh", "2 meshes".
#pragma once
#include <cstddef>
#include <string>

namespace rt {

// `plural` defaults to `noun` + "s".
inline std::string count_of(size_t n, const std::string& noun, const std::string& plural = "") {
    return std::to_string(n) + " " + (n == 1 ? noun : plural.empty() ? noun + "s" : plural);
}

}  // namespace rt
