// The course's previous XML scene format: XML <-> the JSON tree of the JSON format
// (pugixml, Debian libpugixml-dev), and XML scenes loaded through the JSON loader.
#ifndef RT_NO_XML  // built without pugixml (mk/convert.mk): XML is refused with an error
#include <pugixml.hpp>
#endif

#include <algorithm>
#include <cctype>
#include <cstddef>
#include <cstring>
#include <sstream>

#include "json_scene.h"
#include "rt/error.h"
#include "rt/loader.h"
#include "xml_json.h"

namespace rt {
namespace {

using ojson = nlohmann::ordered_json;

#ifndef RT_NO_XML
// Deeper documents are refused rather than risking the stack (scenes nest 5 deep).
constexpr int kMaxDepth = 256;

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
        if (depth > kMaxDepth)
            throw InputError(path_ + ": elements nested more than " + std::to_string(kMaxDepth) + " deep");
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

bool is_name_start(unsigned char c) { return std::isalpha(c) || c == '_' || c == ':' || c >= 0x80; }
bool is_name_char(unsigned char c) { return is_name_start(c) || std::isdigit(c) || c == '-' || c == '.'; }

bool is_xml_name(const std::string& s) {
    if (s.empty() || !is_name_start(static_cast<unsigned char>(s[0]))) return false;
    for (char c : s)
        if (!is_name_char(static_cast<unsigned char>(c))) return false;
    return true;
}

// JSON pointer escaping of one key (RFC 6901).
std::string escape_key(const std::string& key) {
    std::string out;
    for (char c : key) {
        if (c == '~') out += "~0";
        else if (c == '/') out += "~1";
        else out += c;
    }
    return out;
}

class JsonToXml {
public:
    explicit JsonToXml(const std::string& path) : path_(path) {}

    // Appends `value` under `parent` as element(s) called `name`.
    void member(pugi::xml_node parent, const std::string& name, const ojson& value, const std::string& ptr,
                int depth) const {
        if (depth > kMaxDepth) fail(ptr, "nested more than " + std::to_string(kMaxDepth) + " deep");
        if (!is_xml_name(name)) fail(ptr, "key '" + name + "' is not an XML element name");
        if (value.is_array()) {
            for (size_t i = 0; i < value.size(); ++i) {
                const std::string ep = ptr + "/" + std::to_string(i);
                if (value[i].is_array()) fail(ep, "an array inside an array has no XML form");
                fill(parent.append_child(name.c_str()), value[i], ep, depth + 1);
            }
        } else {
            fill(parent.append_child(name.c_str()), value, ptr, depth + 1);
        }
    }

private:
    std::string path_;

    [[noreturn]] void fail(const std::string& ptr, const std::string& what) const {
        throw InputError(path_ + ": " + (ptr.empty() ? "/" : ptr) + ": " + what);
    }

    // A string, number or boolean as text; anything else fails.
    std::string scalar(const ojson& v, const std::string& ptr, const char* what) const {
        if (v.is_string()) return v.get<std::string>();
        if (v.is_number() || v.is_boolean()) return v.dump();
        fail(ptr, std::string(what) + " must be a string or a number, got " +
                      (v.is_null() ? "null" : v.is_object() ? "an object" : "an array"));
    }

    void fill(pugi::xml_node e, const ojson& v, const std::string& ptr, int depth) const {
        if (v.is_null()) return;
        if (!v.is_object()) {
            e.append_child(pugi::node_pcdata).set_value(scalar(v, ptr, "a value").c_str());
            return;
        }
        for (auto it = v.begin(); it != v.end(); ++it) {
            const std::string& key = it.key();
            const std::string kp = ptr + "/" + escape_key(key);
            if (key == "_data") {
                e.prepend_child(pugi::node_pcdata).set_value(scalar(*it, kp, "_data").c_str());
            } else if (key.size() > 1 && key[0] == '_') {
                const std::string name = key.substr(1);
                if (!is_xml_name(name)) fail(kp, "key '" + key + "' is not an XML attribute name");
                if (e.attribute(name.c_str())) fail(kp, "attribute '" + name + "' given twice");
                e.append_attribute(name.c_str()).set_value(scalar(*it, kp, "an attribute").c_str());
            } else {
                member(e, key, *it, kp, depth);
            }
        }
    }
};
#endif  // RT_NO_XML

}  // namespace

bool is_xml_path(const std::string& path) {
    if (path.size() < 4) return false;
    std::string ext = path.substr(path.size() - 4);
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext == ".xml";
}

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
        if (root) throw InputError(path + ": more than one top-level element (<" + std::string(root.name()) +
                                   "> and <" + c.name() + ">)");
        root = c;
    }
    if (!root) throw InputError(path + ": no XML element found");
    ojson out = ojson::object();
    out[root.name()] = XmlToJson(path, xml_text).element(root, 1);
    return out;
}

std::string json_tree_to_xml(const ojson& root, const std::string& path) {
    if (!root.is_object() || root.size() != 1)
        throw InputError(path + ": /: an XML document needs a JSON object with exactly one key (\"Scene\")");
    pugi::xml_document doc;
    const std::string key = root.begin().key();
    if (root.begin().value().is_array())
        throw InputError(path + ": /" + escape_key(key) + ": an XML document has one root element, not an array");
    JsonToXml(path).member(doc, key, root.begin().value(), "/" + escape_key(key), 1);
    std::ostringstream out;
    doc.save(out, "    ", pugi::format_indent | pugi::format_no_declaration, pugi::encoding_utf8);
    return out.str();
}
#else
// This build has no XML support: pugixml's headers were not found (make dist on a
// machine with only g++). Everything else works; XML input is one error line.
ojson xml_to_json_tree(const std::string&, const std::string& path) {
    throw InputError(path + ": XML scenes are not supported by this build (it was made without pugixml, "
                            "libpugixml-dev); use the JSON scene");
}

std::string json_tree_to_xml(const ojson&, const std::string& path) {
    throw InputError(path + ": cannot write XML: this build was made without pugixml (libpugixml-dev)");
}
#endif  // RT_NO_XML

ojson parse_json_tree(const std::string& json_text, const std::string& path) {
    try {
        return ojson::parse(json_text);
    } catch (const ojson::parse_error& e) {
        // nlohmann's message reads "[json.exception.parse_error.101] parse error at line 3, column 5: ..."
        const std::string what = e.what();
        const size_t at = what.find("parse error");
        throw InputError(path + ": " + (at == std::string::npos ? what : what.substr(at)));
    } catch (const ojson::exception& e) {
        // E.g. out_of_range.406 "number overflow parsing '1e999'"; drop the "[json.exception...] " tag.
        const std::string what = e.what();
        const size_t tag = what.find("] ");
        throw InputError(path + ": " + (tag == std::string::npos ? what : what.substr(tag + 2)));
    }
}

SceneDesc parse_scene_xml(const std::string& xml_text, const std::string& path) {
    const nlohmann::json tree(xml_to_json_tree(xml_text, path));
    return scene_from_json(tree, path);
}

}  // namespace rt
