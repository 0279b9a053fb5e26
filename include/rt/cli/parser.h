// What the programs share in reading their command lines, without CLI11: the value checks
// and their messages, the error lines, and Parser, CLI11 behind a wall. Every option takes
// "--opt value" and "--opt=value" (short ones "-j 2" and "-j2"). Every error line on stderr
// starts "error: " (as warnings start "warning: "); a usage error prints "error: <what>"
// and the usage line, exit status 2; --help and --version print on stdout, exit status 0.
//
// The raytracer's copies of the library (one per precision and instruction-set level,
// docs/performance.md) include this header, not CLI11: CLI11's header defines objects
// that are constructed at start, and a copy built for AVX-512 must run no instruction
// before main() has chosen it. Parser's code, with CLI11's, is compiled once (options.cpp).
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace CLI {
class App;
}  // namespace CLI

// Outside namespace rt: nothing here depends on the precision or the level, so one copy
// (in the primary double library) serves every copy, as rt::cli (the copies' -Drt=...
// renames namespace rt, not rtcli).
namespace rtcli {

// A program's fixed texts.
struct Program {
    std::string name;     // the program's name (help, version)
    std::string version;  // what --version prints
    std::string usage;    // "usage: <name> [options] ...": after each usage error and atop --help
    std::string about;    // --help: the paragraph between the usage line and the options
    std::string footer;   // --help: the lines after the options
};

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

// Prints "error: <message>" on stderr: every error line of the programs goes through it.
void print_error(const std::string& message);

// Prints a usage error found after parsing ("error: <message>" and the usage line,
// as parse() does) and returns its exit status, 2.
int report_usage_error(const Program& p, const std::string& message);

// A command line's options, read by CLI11 (rt/cli/options.h has the CLI::App form that
// rtconvert and rtdiff use; the helpers below serve both).
class Parser {
public:
    explicit Parser(const Program& p);
    ~Parser();
    Parser(const Parser&) = delete;
    Parser& operator=(const Parser&) = delete;

    // An option with one value (`value` names it in --help), handed to `set` once parsing
    // is done (set may call usage_error).
    void add_value(const std::string& names, const std::string& value, const std::string& help,
                   std::function<void(const std::string&)> set);
    // A flag: "-q,--quiet" sets `target`; "--cull,!--no-cull" sets or clears it.
    void add_flag(const std::string& names, bool& target, const std::string& help);
    // The operands (arguments that are not options), `name` in --help.
    void add_operands(const std::string& name, std::vector<std::string>& target);
    // The --help group of the options added after it.
    void group(const std::string& name);
    // Runs after every option was set: cross-option checks (usage_error).
    void final_check(std::function<void()> check);
    // nullopt: the program goes on; otherwise --help, --version or a usage error has been
    // printed and this is the exit status.
    std::optional<int> parse(int argc, char** argv);

private:
    const Program& program_;
    std::unique_ptr<CLI::App> app_;
};

// An option with one value, handed to `set` once parsing is done (the Parser form of
// rt/cli/options.h's add_value).
template <class F>
void add_value(Parser& parser, const std::string& names, const std::string& value, const std::string& help, F set) {
    parser.add_value(names, value, help, std::move(set));
}

// An option taking a text into `target`; an empty one is a usage error "<option> needs <what>".
template <class App>
auto add_text(App& app, const std::string& names, const std::string& value, const std::string& help,
              std::string& target, const std::string& what) {
    return add_value(app, names, value, help, [option = long_name(names), &target, what](const std::string& v) {
        if (v.empty()) usage_error(option + " needs " + what);
        target = v;
    });
}

// An option taking a whole number in [lo, hi] into `target`.
template <class App, class T>
auto add_whole(App& app, const std::string& names, const std::string& value, const std::string& help, T& target,
               long lo, long hi) {
    return add_value(app, names, value, help, [option = long_name(names), &target, lo, hi](const std::string& v) {
        target = static_cast<T>(whole_number(option, v, lo, hi));
    });
}

// An option taking a number for which `ok` holds into `target` (see number()).
template <class App, class T>
auto add_number(App& app, const std::string& names, const std::string& value, const std::string& help, T& target,
                const std::string& what, bool (*ok)(double)) {
    return add_value(app, names, value, help, [option = long_name(names), &target, what, ok](const std::string& v) {
        target = static_cast<T>(number(option, v, what, ok));
    });
}

// An option taking one of the words of `choices` (MODE in --help); `target` gets its value.
template <class App, class T>
auto add_choice(App& app, const std::string& names, const std::string& help, T& target,
                const std::vector<std::pair<std::string, T>>& choices) {
    std::vector<std::string> words;
    for (const auto& c : choices) words.push_back(c.first);
    return add_value(app, names, "MODE", help,
                     [option = long_name(names), &target, choices, words](const std::string& v) {
                         target = choices[one_of(option, v, words)].second;
                     });
}

}  // namespace rtcli

namespace rt {
namespace cli = ::rtcli;
}  // namespace rt
