// The loader's value readers and key bookkeeping (json_fields.h).
#include "json_fields.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iterator>
#include <sstream>

#include "rt/core/error.h"
#include "rt/core/parse_number.h"
#include "rt/loader/spelling.h"

namespace rt {

void JsonFields::fail(const std::string& where, const std::string& what) const {
    throw InputError(file_ + ": " + (where.empty() ? "/" : where) + ": " + what);
}

const JsonFields::json& JsonFields::require(const json& obj, const std::string& path, const char* key) const {
    const json* v = find(obj, key);
    if (!v) {
        const auto [found, meant] = near_key(obj, {key});
        fail(path + "/" + key, "required key is missing" + (found.empty() ? "" : " (found '" + found + "' instead)"));
    }
    return *v;
}

std::pair<std::string, std::string> JsonFields::near_key(const json& obj, const std::vector<std::string>& keys) {
    for (auto it = obj.begin(); it != obj.end(); ++it)
        if (const std::string meant = near_miss(it.key(), keys); !meant.empty()) return {it.key(), meant};
    return {};
}

void JsonFields::expect_object(const json& v, const std::string& path) const {
    if (!v.is_object()) fail(path, "expected an object, got " + type_name(v));
}

void JsonFields::check_keys(const json& obj, const std::string& generic, const std::vector<const char*>& known) {
    for (auto it = obj.begin(); it != obj.end(); ++it) {
        bool ok = false;
        for (const char* k : known) ok = ok || it.key() == k;
        if (ok) continue;
        Unknown& u = unknown_[generic + "/" + it.key()];
        if (u.count++ == 0) u.suggestion = near_miss(it.key(), std::vector<std::string>(known.begin(), known.end()));
    }
}

std::vector<std::string> JsonFields::warnings() const {
    std::vector<std::string> out;
    for (const auto& [key, u] : unknown_)
        out.push_back(file_ + ": " + key + ": unknown key ignored" +
                      (u.count > 1 ? " (" + std::to_string(u.count) + " times)" : "") +
                      (u.suggestion.empty() ? "" : " (did you mean " + u.suggestion + "?)"));
    return out;
}

const std::string& JsonFields::text(const json& v, const std::string& path) const {
    if (!v.is_string()) fail(path, "expected a string, got " + type_name(v));
    return v.get_ref<const std::string&>();
}

std::vector<double> JsonFields::numbers(const json& v, const std::string& path) const {
    std::vector<double> out;
    if (v.is_number()) {
        out.push_back(v.get<double>());
    } else {
        const std::string& s = text(v, path);
        const char* p = s.data();
        const char* end = p + s.size();
        while (true) {
            while (p < end && std::isspace(static_cast<unsigned char>(*p))) ++p;
            if (p == end) break;
            const char* tok = p;
            if (*p == '+') ++p;  // from_chars rejects a leading '+'
            double d;
            auto r = parse_number(p, end, d);
            if (r.ec == std::errc::result_out_of_range)
                fail(path, "number out of range: '" + std::string(tok, r.ptr) + "'");
            if (r.ec != std::errc() || (r.ptr < end && !std::isspace(static_cast<unsigned char>(*r.ptr)))) {
                const char* e = tok;
                while (e < end && !std::isspace(static_cast<unsigned char>(*e))) ++e;
                fail(path, "not a number: '" + std::string(tok, e) + "'");
            }
            out.push_back(d);
            p = r.ptr;
        }
    }
    for (double d : out) {
        if (!std::isfinite(d)) fail(path, "not a finite number");
        if (std::fabs(d) > kMaxMagnitude) fail(path, "number beyond +-1e30: " + format_number(d));
    }
    return out;
}

std::vector<double> JsonFields::exactly(const json& v, const std::string& path, size_t n) const {
    std::vector<double> xs = numbers(v, path);
    if (xs.size() != n)
        fail(path,
             "expected " + std::to_string(n) + " number" + (n > 1 ? "s" : "") + ", got " + std::to_string(xs.size()));
    return xs;
}

Real JsonFields::positive(const json& v, const std::string& path) const {
    const Real r = real(v, path);
    if (!(r > 0)) fail(path, "must be greater than 0");
    return r;
}

Real JsonFields::non_negative(const json& v, const std::string& path) const {
    const Real r = real(v, path);
    if (r < 0) fail(path, "must not be negative");
    return r;
}

long long JsonFields::integer(const json& v, const std::string& path) const {
    const double d = exactly(v, path, 1)[0];
    if (d != std::floor(d) || std::fabs(d) > 9e15) fail(path, "expected an integer");
    return static_cast<long long>(d);
}

Vec3 JsonFields::vec3(const json& v, const std::string& path) const {
    const std::vector<double> xs = exactly(v, path, 3);
    return {static_cast<Real>(xs[0]), static_cast<Real>(xs[1]), static_cast<Real>(xs[2])};
}

Vec3 JsonFields::nonzero_vec3(const json& v, const std::string& path) const {
    const Vec3 x = vec3(v, path);
    if (!(length(x) > 0)) fail(path, "must not be the zero vector");
    return x;
}

Vec3 JsonFields::color(const json& v, const std::string& path) const {
    const Vec3 c = vec3(v, path);
    if (c.x < 0 || c.y < 0 || c.z < 0) fail(path, "must not be negative");
    return c;
}

std::string JsonFields::object_id(const json& obj, size_t position) {
    const json* v = find(obj, "_id");
    if (v && v->is_string()) return v->get<std::string>();
    if (v && v->is_number()) return v->dump();
    return std::to_string(position);
}

std::string JsonFields::format_number(double d) {
    std::ostringstream s;
    s << d;
    return s.str();
}

std::string JsonFields::type_name(const json& v) {
    if (v.is_null()) return "null";
    if (v.is_discarded()) return "nothing";
    if (v.is_binary()) return "binary data";  // never parsed from text
    const std::string name = v.type_name();
    return (v.is_object() || v.is_array() ? "an " : "a ") + name;
}

}  // namespace rt
