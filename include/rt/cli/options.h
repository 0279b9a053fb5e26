// What the raytracer and rtconvert commands share in reading their command lines with
// CLI11: the value checks and their messages, the help layout, the exit statuses.
//
// Every option takes "--opt value" and "--opt=value" (short ones "-j 2" and "-j2").
// Every error line on stderr starts "error: " (as warnings start "warning: "); a usage
// error prints "error: <what>" and the usage line, exit status 2;
// --help and --version print on stdout, exit status 0.
#pragma once
#include <CLI/CLI.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

// Outside namespace rt: nothing here depends on the precision, so one copy (in the double
// library) serves both, as rt::cli (FLOAT_CPPFLAGS renames namespace rt, not rtcli).
namespace rtcli {

// A program's fixed texts.
struct Program {
    std::string name;     // the program's name (help, version)
    std::string version;  // what --version prints
    std::string usage;    // "usage: <name> [options] ...": after each usage error and atop --help
    std::string about;    // --help: the paragraph between the usage line and the options
    std::string footer;   // --help: the lines after the options
};

// Sets up `app` for `p`: -h/--help, --version, the help layout, unknown options
// reported as usage errors.
void setup(CLI::App& app, const Program& p);

// A usage error: throws what parse() reports as "<program>: <message>".
[[noreturn]] void usage_error(const std::string& message);

// The whole of `text` as a whole number in [lo, hi]; otherwise a usage error
// "<option> needs a whole number from <lo> to <hi>, got '<text>'".
long whole_number(const std::string& option, const std::string& text, long lo, long hi);

// The whole of `text` as a number for which `ok` holds; otherwise a usage error
// "<option> needs <what>, got '<text>'".
double number(const std::string& option, const std::string& text, const std::string& what, bool (*ok)(double));

// The position of `text` in `words`; otherwise a usage error "<option> takes a, b or c, got '<text>'".
size_t one_of(const std::string& option, const std::string& text, const std::vector<std::string>& words);

// The long name of option `names` as CLI11 takes them: "--threads" of "-j,--threads".
inline std::string long_name(const std::string& names) { return names.substr(names.rfind(',') + 1); }

// An option with one value, handed to `set` once parsing is done (set may call usage_error).
// `names` as CLI11 takes them ("-j,--threads"); `value` names the value in --help.
template <class F>
CLI::Option* add_value(CLI::App& app, const std::string& names, const std::string& value, const std::string& help,
                       F set) {
    return app.add_option_function<std::string>(names, set, help)->type_name(value);
}

// An option taking a text into `target`; an empty one is a usage error "<option> needs <what>".
inline CLI::Option* add_text(CLI::App& app, const std::string& names, const std::string& value, const std::string& help,
                             std::string& target, const std::string& what) {
    return add_value(app, names, value, help, [option = long_name(names), &target, what](const std::string& v) {
        if (v.empty()) usage_error(option + " needs " + what);
        target = v;
    });
}

// An option taking a whole number in [lo, hi] into `target`.
template <class T>
CLI::Option* add_whole(CLI::App& app, const std::string& names, const std::string& value, const std::string& help,
                       T& target, long lo, long hi) {
    return add_value(app, names, value, help, [option = long_name(names), &target, lo, hi](const std::string& v) {
        target = static_cast<T>(whole_number(option, v, lo, hi));
    });
}

// An option taking a number for which `ok` holds into `target` (see number()).
template <class T>
CLI::Option* add_number(CLI::App& app, const std::string& names, const std::string& value, const std::string& help,
                        T& target, const std::string& what, bool (*ok)(double)) {
    return add_value(app, names, value, help, [option = long_name(names), &target, what, ok](const std::string& v) {
        target = static_cast<T>(number(option, v, what, ok));
    });
}

// An option taking one of the words of `choices` (MODE in --help); `target` gets its value.
template <class T>
CLI::Option* add_choice(CLI::App& app, const std::string& names, const std::string& help, T& target,
                        const std::vector<std::pair<std::string, T>>& choices) {
    std::vector<std::string> words;
    for (const auto& c : choices) words.push_back(c.first);
    return add_value(app, names, "MODE", help,
                     [option = long_name(names), &target, choices, words](const std::string& v) {
                         target = choices[one_of(option, v, words)].second;
                     });
}

// Two file operands into `files`; fewer is the usage error `fewer`, more "too many files".
inline void add_two_files(CLI::App& app, std::vector<std::string>& files, const std::string& fewer) {
    app.add_option("files", files);
    app.final_callback([&files, fewer] {
        if (files.size() != 2) usage_error(files.size() < 2 ? fewer : "too many files");
    });
}

// Prints "error: <message>" on stderr: every error line of the programs goes through it.
void print_error(const std::string& message);

// Prints a usage error found after parsing ("error: <message>" and the usage line,
// as parse() does) and returns its exit status, 2.
int report_usage_error(const Program& p, const std::string& message);

// Parses the command line into `app`. nullopt: the program goes on; otherwise --help,
// --version or a usage error has been printed and this is the exit status.
std::optional<int> parse(CLI::App& app, const Program& p, int argc, char** argv);

}  // namespace rtcli

namespace rt {
namespace cli = ::rtcli;
}  // namespace rt
