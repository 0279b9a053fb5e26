#include "rt/cli/options.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <utility>
#include <vector>

namespace rtcli {

namespace {

// Lines of --help are at most this long (a terminal's width).
constexpr size_t kHelpWidth = 100;
// Option descriptions start in this column (the names' column, their two-space indent included).
constexpr size_t kNameColumn = 28;

// Breaks each line longer than kHelpWidth at its last space that fits, the rest indented
// to the descriptions' column.
std::string fold_lines(const std::string& text) {
    std::string out;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        std::string line = text.substr(start, end - start);
        while (line.size() > kHelpWidth) {
            const size_t cut = line.rfind(' ', kHelpWidth);
            if (cut == std::string::npos || cut <= kNameColumn) break;
            out += line.substr(0, cut) + "\n";
            line = std::string(kNameColumn, ' ') + line.substr(cut + 1);
        }
        out += line;
        if (end < text.size()) out += "\n";
        start = end + 1;
    }
    return out;
}

// --help: the usage line, the program's paragraph, the option groups, the footer.
// Options are named "-o, --output-dir" and "--cull, --no-cull".
class HelpLayout : public CLI::Formatter {
public:
    explicit HelpLayout(std::string usage) : usage_(std::move(usage)) { column_width(kNameColumn); }
    std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode mode) const override {
        std::string groups = make_groups(app, mode);  // one blank line between groups, not two
        for (size_t at; (at = groups.find("\n\n\n")) != std::string::npos;) groups.erase(at, 1);
        return usage_ + "\n\n" + app->get_description() + fold_lines(groups) + "\n" + app->get_footer() + "\n";
    }
    std::string make_option_name(const CLI::Option* opt, bool positional) const override {
        std::string name = CLI::Formatter::make_option_name(opt, positional);
        for (size_t at; (at = name.find("{false}")) != std::string::npos;) name.erase(at, 7);
        for (size_t at = 0; (at = name.find(',', at)) != std::string::npos; at += 2) name.insert(at + 1, " ");
        return name;
    }

private:
    std::string usage_;
};

}  // namespace

void setup(CLI::App& app, const Program& p) {
    app.name(p.name);
    app.description(p.about);
    app.footer(p.footer);
    app.formatter(std::make_shared<HelpLayout>(p.usage));
    // A repeated option: the last one counts.
    app.option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast)->group("options");
    app.set_help_flag("-h,--help", "show this help");
    app.set_version_flag("--version", p.version, "show the version");
    // Unknown options are collected, then reported in our words.
    app.allow_extras();
    app.parse_complete_callback([&app] {
        for (const std::string& a : app.remaining())
            if (a.size() > 1 && a[0] == '-' && a != "--") usage_error("unknown option '" + a + "'");
    });
}

void usage_error(const std::string& message) { throw CLI::ValidationError(message); }

long whole_number(const std::string& option, const std::string& text, long lo, long hi) {
    char* end = nullptr;
    errno = 0;
    const long n = std::strtol(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || errno != 0 || n < lo || n > hi)
        usage_error(option + " needs a whole number from " + std::to_string(lo) + " to " + std::to_string(hi) +
                    ", got '" + text + "'");
    return n;
}

double number(const std::string& option, const std::string& text, const std::string& what, bool (*ok)(double)) {
    char* end = nullptr;
    const double f = std::strtod(text.c_str(), &end);
    if (text.empty() || *end != '\0' || std::isnan(f) || !ok(f))
        usage_error(option + " needs " + what + ", got '" + text + "'");
    return f;
}

size_t one_of(const std::string& option, const std::string& text, const std::vector<std::string>& words) {
    std::string listed;
    for (size_t i = 0; i < words.size(); ++i) {
        if (text == words[i]) return i;
        listed += (i == 0 ? "" : i + 1 == words.size() ? " or " : ", ") + words[i];
    }
    usage_error(option + " takes " + listed + ", got '" + text + "'");
}

void print_error(const std::string& message) { std::fprintf(stderr, "error: %s\n", message.c_str()); }

int report_usage_error(const Program& p, const std::string& message) {
    print_error(message);
    std::fprintf(stderr, "%s\n", p.usage.c_str());
    return 2;
}

std::optional<int> parse(CLI::App& app, const Program& p, int argc, char** argv) {
    // "--opt=" is "--opt" with an empty value (CLI11 would take the next argument instead).
    std::vector<std::string> args;
    bool options_end = false;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        options_end = options_end || a == "--";
        if (!options_end && a.size() > 3 && a.compare(0, 2, "--") == 0 && a.back() == '=' &&
            a.find('=') == a.size() - 1) {
            a.pop_back();
            args.push_back(a);
            a.clear();
        }
        args.push_back(a);
    }
    std::reverse(args.begin(), args.end());  // App::parse takes them last first
    try {
        app.parse(args);
        return std::nullopt;
    } catch (const CLI::CallForHelp&) {
        std::fputs(app.help().c_str(), stdout);
        return 0;
    } catch (const CLI::CallForVersion& e) {
        std::printf("%s\n", e.what());
        return 0;
    } catch (const CLI::ParseError& e) {
        // CLI11 words a missing value "--opt: 1 required TYPE missing".
        std::string what = e.what();
        const size_t colon = what.find(": 1 required ");
        if (colon != std::string::npos && what.size() > 8 && what.compare(what.size() - 8, 8, " missing") == 0)
            what = "option " + what.substr(0, colon) + " needs a value";
        return report_usage_error(p, what);
    }
}

}  // namespace rtcli

namespace rtcli {

Parser::Parser(const Program& p) : program_(p), app_(std::make_unique<CLI::App>()) { setup(*app_, p); }

Parser::~Parser() = default;

void Parser::add_value(const std::string& names, const std::string& value, const std::string& help,
                       std::function<void(const std::string&)> set) {
    rtcli::add_value(*app_, names, value, help, std::move(set));
}

void Parser::add_flag(const std::string& names, bool& target, const std::string& help) {
    app_->add_flag(names, target, help);
}

void Parser::add_operands(const std::string& name, std::vector<std::string>& target) { app_->add_option(name, target); }

void Parser::group(const std::string& name) { app_->option_defaults()->group(name); }

void Parser::final_check(std::function<void()> check) { app_->final_callback(std::move(check)); }

std::optional<int> Parser::parse(int argc, char** argv) { return rtcli::parse(*app_, program_, argc, argv); }

}  // namespace rtcli
