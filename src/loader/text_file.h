// Whole-file reading and path helpers shared by the scene loaders and rtconvert.
#pragma once
#include <string>

namespace rt {

// The whole file. Folders and devices are refused up front (reading /dev/zero would
// never end); pipes are read. Throws rt::InputError
// "<path>: cannot open: <reason>" or "<path>: cannot read: <reason>".
std::string read_text_file(const std::string& path);

// The folder part of `path` with its trailing '/', or "" for a bare file name:
// relative paths inside a file (PLY, MTL) are resolved by prefixing it.
std::string dirname_of(const std::string& path);

}  // namespace rt
