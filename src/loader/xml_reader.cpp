// The course's previous XML scene format read into the JSON tree of the JSON format
// (rt/loader/scene_tree.h), through pugixml (Debian libpugixml-dev).
#ifndef RT_NO_XML  // built without pugixml (mk/convert.mk): XML is refused with an error
#include <pugixml.hpp>
#endif

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstring>

#include "rt/core/error.h"
#include "rt/loader/scene_tree.h"

namespace rt {
namespace {

using ojson = nlohmann::ordered_json;

#ifndef RT_NO_XML
bool is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\f' || c == '\v'; }

// Leading and trailing whitespace dropped, inner runs made one space.
std::string collapse(const char* s) {
    std::string out;
    bool pending_space = false;
    for (; *s; ++s) {
        if (is_space(*s)) {
            pending_space = !out.empty();
        } else {
            if (pending_space) out += ' ';
            pending_space = false;
            out += *s;
        }
    }
    return out;
}

// "line L, column C" of a byte offset into `text` (negative offsets: the start).
std::string line_and_column(const std::string& text, ptrdiff_t offset) {
    const size_t end = std::min(static_cast<size_t>(std::max<ptrdiff_t>(offset, 0)), text.size());
    size_t line = 1, column = 1;
    for (size_t i = 0; i < end; ++i) {
        if (text[i] == '\n') {
            ++line;
            column = 1;
        } else {
            ++column;
        }
    }
    return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Adds a member; a key seen before turns into an array of its values, in order.
// Element values are never arrays themselves, so an array here is such a list.
void add_member(ojson& obj, const std::string& key, ojson value) {
    auto it = obj.find(key);
    if (it == obj.end()) {
        obj[key] = std::move(value);
    } else if (it->is_array()) {
        it->push_back(std::move(value));
    } else {
        ojson list = ojson::array();
        list.push_back(std::move(*it));
        list.push_back(std::move(value));
        *it = std::move(list);
    }
}

class XmlToJson {
public:
    XmlToJson(const std::string& path, const std::string& text) : path_(path), text_(text) {}

    ojson element(const pugi::xml_node& e, int depth) const {
        if (depth > kMaxXmlDepth)
            throw InputError(path_ + ": elements nested more than " + std::to_string(kMaxXmlDepth) + " deep");
        std::string text;
        for (const pugi::xml_node& c : e.children())
            if (c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) text += c.value();
        text = collapse(text.c_str());

        ojson obj = ojson::object();
        bool members = false;
        for (const pugi::xml_attribute& a : e.attributes()) {
            // Not well-formed XML, but pugixml accepts it.
            for (pugi::xml_attribute b = a.next_attribute(); b; b = b.next_attribute())
                if (std::strcmp(a.name(), b.name()) == 0)
                    throw InputError(path_ + ": " + line_column(e.offset_debug()) + ": attribute '" + a.name() +
                                     "' given twice");
            add_member(obj, std::string("_") + a.name(), collapse(a.value()));
            members = true;
        }
        for (const pugi::xml_node& c : e.children()) {
            if (c.type() != pugi::node_element) continue;
            add_member(obj, c.name(), element(c, depth + 1));
            members = true;
        }
        if (!members) return text.empty() ? ojson(nullptr) : ojson(text);
        if (text.empty()) return obj;
        // The course's files put "_data" first ({"_data": "...", "_type": "xyz"}).
        ojson out = ojson::object();
        out["_data"] = text;
        for (auto it = obj.begin(); it != obj.end(); ++it) out[it.key()] = std::move(*it);
        return out;
    }

private:
    const std::string& path_;
    const std::string& text_;

    std::string line_column(ptrdiff_t offset) const { return line_and_column(text_, offset); }
};
#endif  // RT_NO_XML

}  // namespace

#ifndef RT_NO_XML
ojson xml_to_json_tree(const std::string& xml_text, const std::string& path) {
    pugi::xml_document doc;
    const pugi::xml_parse_result r =
        doc.load_buffer(xml_text.data(), xml_text.size(), pugi::parse_default, pugi::encoding_auto);
    if (!r) {
        std::string what = r.description();
        if (!what.empty()) what[0] = static_cast<char>(std::tolower(static_cast<unsigned char>(what[0])));
        throw InputError(path + ": " + line_and_column(xml_text, r.offset) + ": " + what);
    }
    pugi::xml_node root;
    for (const pugi::xml_node& c : doc.children()) {
        if (c.type() != pugi::node_element) continue;
        if (root)
            throw InputError(path + ": more than one top-level element (<" + std::string(root.name()) + "> and <" +
                             c.name() + ">)");
        root = c;
    }
    if (!root) throw InputError(path + ": no XML element found");
    ojson out = ojson::object();
    out[root.name()] = XmlToJson(path, xml_text).element(root, 1);
    return out;
}
#else
// This build has no XML support: pugixml's headers were not found (make dist on a
// machine with only g++). Everything else works; XML input is one error line.
ojson xml_to_json_tree(const std::string&, const std::string& path) {
    throw InputError(path +
                     ": XML scenes are not supported by this build (it was made without pugixml, "
                     "libpugixml-dev); use the JSON scene");
}
#endif  // RT_NO_XML

}  // namespace rt
