// JSON scene text -> tree, with the one mapping of nlohmann's exceptions to our
// messages (rt/loader/scene_tree.h).
#include <algorithm>
#include <string>
#include <string_view>

#include "rt/core/error.h"
#include "rt/loader/scene_tree.h"

namespace rt {
namespace {

// A parse error where the parser, after a complete value, expected ',' or the closing
// bracket and met the start of another value is most likely a missing comma; nlohmann
// reports the place of the value that follows. Returns the 1-based line where the value
// before it ends, or 0 when the error is not that. `end` is nlohmann's byte: the
// unexpected token is json_text[..end).
size_t missing_comma_line(const std::string& what, const std::string& json_text, size_t end) {
    const bool after_value =
        (what.find("while parsing object - ") != std::string::npos &&
         what.find("; expected '}'") != std::string::npos) ||
        (what.find("while parsing array - ") != std::string::npos && what.find("; expected ']'") != std::string::npos);
    if (!after_value || end == 0 || end > json_text.size()) return 0;
    // The start of the unexpected token, by its kind.
    size_t start = end - 1;
    if (what.find("unexpected string literal") != std::string::npos) {
        if (json_text[start] != '"') return 0;
        const auto escaped = [&](size_t q) {  // an odd run of backslashes before q
            size_t n = 0;
            while (q > n && json_text[q - n - 1] == '\\') ++n;
            return n % 2 == 1;
        };
        do {
            if (start == 0) return 0;
            --start;
        } while (json_text[start] != '"' || escaped(start));
    } else if (what.find("unexpected number literal") != std::string::npos) {
        while (start > 0 && std::string_view("0123456789+-.eE").find(json_text[start - 1]) != std::string_view::npos)
            --start;
    } else if (what.find("unexpected true literal") != std::string::npos ||
               what.find("unexpected null literal") != std::string::npos) {
        start = end >= 4 ? end - 4 : 0;
    } else if (what.find("unexpected false literal") != std::string::npos) {
        start = end >= 5 ? end - 5 : 0;
    } else if (what.find("unexpected '{'") == std::string::npos && what.find("unexpected '['") == std::string::npos) {
        return 0;  // not the start of a value
    }
    size_t prev = start;
    do {
        if (prev == 0) return 0;
        --prev;
    } while (std::string_view(" \t\r\n").find(json_text[prev]) != std::string_view::npos);
    return 1 + static_cast<size_t>(std::count(json_text.begin(), json_text.begin() + prev, '\n'));
}

// "<path>: <what>" for an exception thrown while parsing `json_text`.
std::string json_error_message(const nlohmann::json::exception& e, const std::string& json_text,
                               const std::string& path) {
    const std::string what = e.what();
    if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
        // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
        const size_t at = what.find("parse error");
        const size_t comma_line = missing_comma_line(what, json_text, pe->byte);
        return path + ": " + (at == std::string::npos ? what : what.substr(at)) +
               (comma_line == 0 ? "" : " (missing ',' after line " + std::to_string(comma_line) + "?)");
    }
    const size_t overflow = what.find("number overflow");
    if (dynamic_cast<const nlohmann::json::out_of_range*>(&e) && overflow != std::string::npos) {
        // A number literal beyond the double range ("1e999"): nlohmann reports
        // "[json.exception.out_of_range.406] number overflow parsing '1e999'" with no
        // place, so the place is where that literal first occurs in the text.
        const size_t q0 = what.find('\''), q1 = what.rfind('\'');
        std::string place;
        if (q0 != std::string::npos && q1 > q0) {
            const size_t at = json_text.find(what.substr(q0 + 1, q1 - q0 - 1));
            if (at != std::string::npos) {
                const size_t line =
                    1 + static_cast<size_t>(std::count(json_text.begin(), json_text.begin() + at, '\n'));
                const size_t nl = json_text.rfind('\n', at);
                place = "line " + std::to_string(line) + ", column " +
                        std::to_string(at - (nl == std::string::npos ? 0 : nl + 1) + 1) + ": ";
            }
        }
        return path + ": " + place + what.substr(overflow) + " (not a finite number)";
    }
    // Anything else: drop the "[json.exception...] " tag.
    const size_t tag = what.find("] ");
    return path + ": " + (tag == std::string::npos ? what : what.substr(tag + 2));
}

}  // namespace

template <class Tree>
Tree parse_json_tree(const std::string& json_text, const std::string& path) {
    try {
        return Tree::parse(json_text);
    } catch (const nlohmann::json::exception& e) {  // the same exception types for both trees
        throw InputError(json_error_message(e, json_text, path));
    }
}

template nlohmann::json parse_json_tree<nlohmann::json>(const std::string&, const std::string&);
template nlohmann::ordered_json parse_json_tree<nlohmann::ordered_json>(const std::string&, const std::string&);

}  // namespace rt
