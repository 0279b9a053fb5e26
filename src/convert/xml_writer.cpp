// JSON tree -> the course's XML format (xml_writer.h), through pugixml (Debian
// libpugixml-dev).
#ifndef RT_NO_XML  // built without pugixml (mk/convert.mk): writing XML is refused with an error
#include <pugixml.hpp>
#endif

#include <cctype>
#include <sstream>

#include "rt/core/error.h"
#include "rt/loader/scene_tree.h"
#include "xml_writer.h"

namespace rt {

using ojson = nlohmann::ordered_json;

#ifndef RT_NO_XML
namespace {

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
        if (c == '~')
            out += "~0";
        else if (c == '/')
            out += "~1";
        else
            out += c;
    }
    return out;
}

class JsonToXml {
public:
    explicit JsonToXml(const std::string& path) : path_(path) {}

    // Appends `value` under `parent` as element(s) called `name`.
    void member(pugi::xml_node parent, const std::string& name, const ojson& value, const std::string& ptr,
                int depth) const {
        if (depth > kMaxXmlDepth) fail(ptr, "nested more than " + std::to_string(kMaxXmlDepth) + " deep");
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
                      (v.is_null()     ? "null"
                       : v.is_object() ? "an object"
                                       : "an array"));
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

}  // namespace

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
std::string json_tree_to_xml(const ojson&, const std::string& path) {
    throw InputError(path + ": cannot write XML: this build was made without pugixml (libpugixml-dev)");
}
#endif  // RT_NO_XML

}  // namespace rt
