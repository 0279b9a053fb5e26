// JSON scene text -> tree, with the one mapping of nlohmann's exceptions to our
// messages (rt/loader/scene_tree.h).
#include <algorithm>
#include <string>

#include "rt/core/error.h"
#include "rt/loader/scene_tree.h"

namespace rt {
namespace {

// "<path>: <what>" for an exception thrown while parsing `json_text`.
std::string json_error_message(const nlohmann::json::exception& e, const std::string& json_text,
                               const std::string& path) {
    const std::string what = e.what();
    if (dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
        // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
        const size_t at = what.find("parse error");
        return path + ": " + (at == std::string::npos ? what : what.substr(at));
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
