// Whole-file reading and file-name helpers, shared by the scene loaders, the image
// writer and rtconvert.
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

// The file name's extension from its last '.', lower-cased (".xml" for "a/B.XML"),
// or "" when the name has no '.'. Formats are chosen by extension in any case.
std::string lower_extension(const std::string& path);

}  // namespace rt
