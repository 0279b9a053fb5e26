// Box's rounding of Real bounds outwards to float (rt/bvh/bvh.h).
#include <cmath>

#include "rt/bvh/bvh.h"

namespace rt {

float round_down_to_float(Real x) {
    const float f = static_cast<float>(x);
    return static_cast<Real>(f) > x ? std::nextafter(f, -HUGE_VALF) : f;
}
float round_up_to_float(Real x) {
    const float f = static_cast<float>(x);
    return static_cast<Real>(f) < x ? std::nextafter(f, HUGE_VALF) : f;
}

}  // namespace rt
