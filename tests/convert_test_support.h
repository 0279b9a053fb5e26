// Shared by the converters' tests (tests/test_convert_*.cpp).
#pragma once
#include <sstream>
#include <string>

#include "rt/core/math.h"

namespace convert_test {

// Whether two vectors are equal, exactly.
inline bool same(const rt::Vec3& a, const rt::Vec3& b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

// A vector as text, for failure messages.
inline std::string str(const rt::Vec3& v) {
    std::ostringstream s;
    s.precision(17);
    s << v.x << " " << v.y << " " << v.z;
    return s.str();
}

}  // namespace convert_test
