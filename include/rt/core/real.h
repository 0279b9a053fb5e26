// One alias decides the precision of geometry and shading: double, or float in the
// library's float copy, which the Makefile compiles with -DRT_REAL_FLOAT into namespace
// rt_float (docs/precision.md); `raytracer --precision float` runs that copy.
#pragma once

namespace rt {
#ifdef RT_REAL_FLOAT
using Real = float;
inline constexpr const char* kPrecisionName = "float";
#else
using Real = double;
inline constexpr const char* kPrecisionName = "double";
#endif
}  // namespace rt
