// The CLI::App form of rt/cli/parser.h, for the helper programs (rtconvert, rtdiff),
// compiled once: CLI11's header must stay out of the raytracer's copies (parser.h says why).
#pragma once
#include <CLI/CLI.hpp>

#include <optional>
#include <string>
#include <vector>

#include "rt/cli/parser.h"

namespace rtcli {

// Sets up `app` for `p`: -h/--help, --version, the help layout, unknown options
// reported as usage errors.
void setup(CLI::App& app, const Program& p);

// An option with one value, handed to `set` once parsing is done (set may call usage_error).
// `names` as CLI11 takes them ("-j,--threads"); `value` names the value in --help.
template <class F>
CLI::Option* add_value(CLI::App& app, const std::string& names, const std::string& value, const std::string& help,
                       F set) {
    return app.add_option_function<std::string>(names, set, help)->type_name(value);
}

// Two file operands into `files`; fewer is the usage error `fewer`, more "too many files".
inline void add_two_files(CLI::App& app, std::vector<std::string>& files, const std::string& fewer) {
    app.add_option("files", files);
    app.final_callback([&files, fewer] {
        if (files.size() != 2) usage_error(files.size() < 2 ? fewer : "too many files");
    });
}

// Parses the command line into `app`. nullopt: the program goes on; otherwise --help,
// --version or a usage error has been printed and this is the exit status.
std::optional<int> parse(CLI::App& app, const Program& p, int argc, char** argv);

}  // namespace rtcli
