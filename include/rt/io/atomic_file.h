// Writing a whole file so that readers never see it half-written.
#pragma once
#include <string>
#include <string_view>

namespace rt {

// Writes `bytes` to a temporary name beside `path` and renames it over `path`.
// Throws rt::InputError "<path>: cannot write: <reason>"; nothing is left behind on failure.
void write_file_atomic(const std::string& path, std::string_view bytes);

}  // namespace rt
