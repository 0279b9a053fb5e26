// One alias decides the precision of geometry and shading. Build with
// `make PRECISION=float` to switch; double is the default (see README).
#pragma once

namespace rt {
#ifdef RT_REAL_FLOAT
using Real = float;
#else
using Real = double;
#endif
}  // namespace rt
