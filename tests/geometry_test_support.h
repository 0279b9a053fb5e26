// Shared by the geometry tests (tests/test_geometry_*.cpp): the tolerances for values worked
// out by hand, and an empty scene description to add primitives to.
#pragma once
#include <limits>

#include "rt/core/math.h"
#include "rt/loader/scene_desc.h"

namespace geometry_test {

using rt::Real;
using rt::Vec3;

// Tolerance for directions and distances worked out by hand: a few ulps of Real.
const Real kTol = 16 * std::numeric_limits<Real>::epsilon();
// Tolerances for values worked out by hand: tight ones for a single formula, loose ones for
// results of a few chained operations (double by default; float with PRECISION=float).
const Real kClose = sizeof(Real) == sizeof(double) ? Real(1e-12) : Real(2e-5);
const Real kLoose = sizeof(Real) == sizeof(double) ? Real(1e-9) : Real(2e-4);

// A scene description with one default material and nothing else.
inline rt::SceneDesc empty_desc() {
    rt::SceneDesc d;
    d.path = "/nonexistent/x.json";
    d.materials.push_back({});
    return d;
}

}  // namespace geometry_test
