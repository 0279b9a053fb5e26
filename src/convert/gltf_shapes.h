// Internal: the export's tessellated spheres and planes recognised in what a pipeline made
// of them (docs/gltf.md, "Files that pipelines wrote"): quantised (their vertices moved by
// up to half a step of 14 bits of the primitive's extent), joined with other meshes of their
// material, flattened into world space (a sphere under a non-uniform scaling an ellipsoid).
#pragma once
#include <array>
#include <utility>
#include <vector>

#include "gltf_primitives.h"
#include "rt/core/affine.h"

namespace rt {

// `g` with its vertices moved by `m`, and its box.
GltfTriangles moved(const GltfTriangles& g, const Affine& m);

// Whether every vertex of `g` is within `tolerance` x r of the sphere (c, r).
bool on_sphere(const GltfTriangles& g, const std::array<double, 3>& c, double r, double tolerance);

// Whether every vertex of `g` is within `tolerance` x its distance from p (at least 1) of
// the plane through p of normal `nrm`.
bool on_plane(const GltfTriangles& g, const std::array<double, 3>& p, const std::array<double, 3>& nrm,
              double tolerance);

// Each part of `g` (sharing no vertex with the others) as the sphere about its box's centre
// that its vertices lie on, to within 2e-4 of `extent` (half the largest side of the box of
// the primitive the part was quantised in; half a 14-bit step is 1.1e-4 of it), and its
// triangles' centres too, to within 30% of the radius (a tessellation, not a box whose
// corners lie on a sphere). None unless every part is one.
std::vector<std::pair<std::array<double, 3>, double>> quantised_spheres(const GltfTriangles& g, double extent);

// The same for ellipsoids: each part as the map of the unit sphere onto the ellipsoid its
// vertices lie on (least squares over the quadric's 9 coefficients, then checked as above).
std::vector<Affine> quantised_ellipsoids(const GltfTriangles& g, double extent);

}  // namespace rt
