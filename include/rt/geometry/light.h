// The lights as the integrator shades with them: one struct with a kind tag, each kind's
// sampling in one exhaustive switch (sample_light).
//
// Point (spec 3, "PointLight"): irradiance E = I / d^2 at distance d.
// Area (Lights/AreaLight; docs/conventions.md, "Assignment 3"): a square of side s about
// its centre, lit on both faces; a shaded point draws one point q on it per sample and
// takes E = L s^2 |n_l . w| / d^2, w the unit vector from q to the point.
#pragma once
#include <cmath>
#include <cstdint>

#include "rt/core/math.h"

namespace rt {

enum class LightKind : uint32_t { Point, Area };

struct Light {
    LightKind kind = LightKind::Point;
    Vec3 position;        // a point light's position; an area light's centre
    Vec3 power;           // Intensity (point) or Radiance (area)
    Vec3 normal;          // area: unit normal, and
    Vec3 edge_u, edge_v;  // its edges: orthogonal, each of length Size
    Real area = 0;        // area: Size^2

    static Light point(Vec3 position, Vec3 intensity) { return {LightKind::Point, position, intensity, {}, {}, {}, 0}; }
    static Light square(Vec3 centre, Vec3 unit_normal, Real size, Vec3 radiance) {
        // Any two unit vectors orthogonal to the normal and each other: the square's
        // orientation about its normal is not given; its samples are uniform either way.
        const Vec3 helper = std::fabs(unit_normal.x) < Real(0.9) ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
        const Vec3 u = normalize(cross(helper, unit_normal));
        const Vec3 v = cross(unit_normal, u);
        return {LightKind::Area, centre, radiance, unit_normal, u * size, v * size, size * size};
    }
    // Whether shading a point needs random numbers from its sample's stream.
    bool sampled() const {
        switch (kind) {
            case LightKind::Point:
                return false;
            case LightKind::Area:
                return true;
        }
        return false;
    }
};

// What a light sends towards a point: it comes from `from`, and the irradiance there is
// scale / d^2, d the distance from `from`.
struct LightSample {
    Vec3 from;
    Vec3 scale;
};

// Light l seen from point p; xi1, xi2 uniform in [0, 1), read by sampled kinds only.
inline LightSample sample_light(const Light& l, Vec3 p, Real xi1, Real xi2) {
    switch (l.kind) {
        case LightKind::Point:
            return {l.position, l.power};
        case LightKind::Area: {
            const Vec3 q = l.position + l.edge_u * (xi1 - Real(0.5)) + l.edge_v * (xi2 - Real(0.5));
            const Vec3 to_p = p - q;
            const Real d = length(to_p);
            const Real cos_l = d > 0 ? std::fabs(dot(l.normal, to_p)) / d : Real(0);
            return {q, l.power * (l.area * cos_l)};
        }
    }
    return {l.position, {}};
}

}  // namespace rt
