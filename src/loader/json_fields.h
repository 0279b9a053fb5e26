// Reading a scene tree's values with the loader's checks and messages: every value in the
// course's files is a string ("1 2 3"); numbers are also accepted where one number is
// expected. Errors name the file and the JSON pointer of the offending value; keys the
// renderer does not use are counted, each with the valid key it is a near miss of, and
// reported once per generic path (warnings()).
#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "rt/core/math.h"
#include "rt/loader/scene_desc.h"

namespace rt {

class JsonFields {
public:
    using json = nlohmann::json;

    explicit JsonFields(std::string file) : file_(std::move(file)) {}

    const std::string& file() const { return file_; }

    // Throws rt::InputError "<file>: <where>: <what>".
    [[noreturn]] void fail(const std::string& where, const std::string& what) const;

    static const json* find(const json& obj, const char* key) {
        auto it = obj.find(key);
        return it == obj.end() ? nullptr : &*it;
    }

    // A required key; when it is missing, the error names a near miss of it that the
    // object has instead ("found 'Raduis' instead").
    const json& require(const json& obj, const std::string& path, const char* key) const;
    // The first key of `obj` that is a near miss of one of `keys`, and the key it is a near
    // miss of: {"_plyfile", "_plyFile"}; {"", ""} when none is.
    static std::pair<std::string, std::string> near_key(const json& obj, const std::vector<std::string>& keys);
    void expect_object(const json& v, const std::string& path) const;

    // Records keys the renderer does not use; `generic` is the path without array indices.
    template <size_t N>
    void check_keys(const json& obj, const std::string& generic, const char* const (&known)[N]) {
        check_keys(obj, generic, std::vector<const char*>(known, known + N));
    }
    void check_keys(const json& obj, const std::string& generic, const std::vector<const char*>& known);

    // "<file>: <key>: unknown key ignored (N times) (did you mean K?)", one per generic path.
    std::vector<std::string> warnings() const;

    // Calls f(element, path) for a key holding one object or an array of them.
    template <class F>
    void for_each_item(const json& parent, const std::string& parent_path, const char* key, F f) const {
        const json* v = find(parent, key);
        const std::string path = parent_path + "/" + key;
        if (!v || v->is_null()) return;
        if (v->is_object()) {
            f(*v, path);
        } else if (v->is_array()) {
            for (size_t i = 0; i < v->size(); ++i) {
                const json& e = (*v)[i];
                const std::string ep = path + "/" + std::to_string(i);
                expect_object(e, ep);
                f(e, ep);
            }
        } else {
            fail(path, "expected an object or an array of objects, got " + type_name(*v));
        }
    }

    // --- values ---------------------------------------------------------------
    const std::string& text(const json& v, const std::string& path) const;
    // Whitespace-separated finite numbers, each within +-kMaxMagnitude.
    std::vector<double> numbers(const json& v, const std::string& path) const;
    std::vector<double> exactly(const json& v, const std::string& path, size_t n) const;
    Real real(const json& v, const std::string& path) const { return static_cast<Real>(exactly(v, path, 1)[0]); }
    Real positive(const json& v, const std::string& path) const;
    Real non_negative(const json& v, const std::string& path) const;
    long long integer(const json& v, const std::string& path) const;
    Vec3 vec3(const json& v, const std::string& path) const;
    Vec3 nonzero_vec3(const json& v, const std::string& path) const;
    // Colours and reflectances: three numbers, none negative (spec 2.7).
    Vec3 color(const json& v, const std::string& path) const;

    // An object's _id as the file writes it, or its 1-based `position` among its kind
    // when it has none: how --trace names it. Never an error (renders do not read it).
    static std::string object_id(const json& obj, size_t position);
    // A number as messages write it ("1e+31", "2.5").
    static std::string format_number(double d);
    // What a JSON value is, for messages: "an object", "a number", "null", ...
    static std::string type_name(const json& v);

private:
    std::string file_;
    struct Unknown {
        int count = 0;
        std::string suggestion;  // the valid key it is a near miss of (rt/loader/spelling.h), or ""
    };
    std::map<std::string, Unknown> unknown_;  // generic key path -> occurrences
};

}  // namespace rt
