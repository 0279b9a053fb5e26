// Spheres, ellipsoids and planes in what pipelines made of the export's tessellations
// (gltf_shapes.h).
#include "gltf_shapes.h"

#include <algorithm>
#include <cmath>

namespace rt {
#ifndef RT_NO_GLTF
namespace {

using V3 = std::array<double, 3>;

V3 vertex(const GltfTriangles& g, size_t i) {
    return {g.positions[3 * i], g.positions[3 * i + 1], g.positions[3 * i + 2]};
}

// Whether the centre of every triangle of `g` is within 30% of the radius of the surface
// `radius_at` measures (1 on it, 0 at its centre): a tessellation's triangles are small
// against its curvature (an icosahedron's centres are at 0.79); a box's corners lie on a
// sphere, its faces' triangles' centres at 0.64.
template <class RadiusAt>
bool tessellated(const GltfTriangles& g, RadiusAt&& radius_at) {
    for (size_t t = 0; t + 2 < g.indices.size(); t += 3) {
        const V3 a = vertex(g, g.indices[t]), b = vertex(g, g.indices[t + 1]), c = vertex(g, g.indices[t + 2]);
        if (!(radius_at(V3{(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3}) > 0.7))
            return false;
    }
    return true;
}

// Solves the n x n system a x = b (row-major, partial pivoting); false when singular.
bool solve(std::vector<double> a, std::vector<double> b, size_t n, std::vector<double>& x) {
    for (size_t c = 0; c < n; ++c) {
        size_t pivot = c;
        for (size_t r = c + 1; r < n; ++r)
            if (std::fabs(a[r * n + c]) > std::fabs(a[pivot * n + c])) pivot = r;
        if (!(std::fabs(a[pivot * n + c]) > 1e-300)) return false;
        for (size_t k = 0; k < n; ++k) std::swap(a[c * n + k], a[pivot * n + k]);
        std::swap(b[c], b[pivot]);
        for (size_t r = c + 1; r < n; ++r) {
            const double f = a[r * n + c] / a[c * n + c];
            for (size_t k = c; k < n; ++k) a[r * n + k] -= f * a[c * n + k];
            b[r] -= f * b[c];
        }
    }
    x.assign(n, 0);
    for (size_t c = n; c-- > 0;) {
        double v = b[c];
        for (size_t k = c + 1; k < n; ++k) v -= a[c * n + k] * x[k];
        x[c] = v / a[c * n + c];
    }
    return true;
}

// The ellipsoid `part`'s vertices lie on, as the map of the unit sphere onto it; false when
// they lie on none (a quadric that is not an ellipsoid, or too few vertices).
bool fit_ellipsoid(const GltfTriangles& part, Affine& out) {
    const size_t n = part.positions.size() / 3;
    if (n < 9) return false;
    // In coordinates about the box's centre, scaled to its size, for a well-conditioned fit.
    const V3 mid = {(part.lo[0] + part.hi[0]) / 2, (part.lo[1] + part.hi[1]) / 2, (part.lo[2] + part.hi[2]) / 2};
    const double s = std::max({part.hi[0] - part.lo[0], part.hi[1] - part.lo[1], part.hi[2] - part.lo[2]}) / 2;
    if (!(s > 0)) return false;
    // a x^2 + b y^2 + c z^2 + 2d xy + 2e xz + 2f yz + 2g x + 2h y + 2i z = 1, least squares.
    std::vector<double> ata(81, 0.0), atb(9, 0.0), q;
    for (size_t i = 0; i < n; ++i) {
        const V3 p = vertex(part, i);
        const double x = (p[0] - mid[0]) / s, y = (p[1] - mid[1]) / s, z = (p[2] - mid[2]) / s;
        const double row[9] = {x * x, y * y, z * z, 2 * x * y, 2 * x * z, 2 * y * z, 2 * x, 2 * y, 2 * z};
        for (size_t r = 0; r < 9; ++r) {
            atb[r] += row[r];
            for (size_t k = 0; k < 9; ++k) ata[r * 9 + k] += row[r] * row[k];
        }
    }
    if (!solve(ata, atb, 9, q)) return false;
    const std::vector<double> a = {q[0], q[3], q[4], q[3], q[1], q[5], q[4], q[5], q[2]};
    std::vector<double> centre;  // A c = -v
    if (!solve(a, {-q[6], -q[7], -q[8]}, 3, centre)) return false;
    // (p - c)^T A (p - c) = 1 + c^T A c: Q = A / k.
    double k = 1;
    for (size_t r = 0; r < 3; ++r)
        for (size_t c = 0; c < 3; ++c) k += centre[r] * a[r * 3 + c] * centre[c];
    if (!(k > 0)) return false;
    // Q = L L^T (Cholesky; fails unless Q is positive definite: an ellipsoid).
    double l[3][3] = {};
    for (size_t r = 0; r < 3; ++r)
        for (size_t c = 0; c <= r; ++c) {
            double v = a[r * 3 + c] / k;
            for (size_t m = 0; m < c; ++m) v -= l[r][m] * l[c][m];
            if (r == c) {
                if (!(v > 0)) return false;
                l[r][r] = std::sqrt(v);
            } else {
                l[r][c] = v / l[c][c];
            }
        }
    // The unit sphere's u = L^T (p - c), so p = c + L^-T u: M = L^-T, upper triangular.
    double inv[3][3] = {};  // L^-1, lower triangular
    for (size_t c = 0; c < 3; ++c) {
        inv[c][c] = 1 / l[c][c];
        for (size_t r = c + 1; r < 3; ++r) {
            double v = 0;
            for (size_t m = c; m < r; ++m) v -= l[r][m] * inv[m][c];
            inv[r][c] = v / l[r][r];
        }
    }
    double rows[12];
    for (size_t r = 0; r < 3; ++r) {
        for (size_t c = 0; c < 3; ++c) rows[4 * r + c] = s * inv[c][r];  // (L^-1)^T, back to scale s
        rows[4 * r + 3] = mid[r] + s * centre[r];
    }
    out = Affine::rows(rows);
    return true;
}

}  // namespace

GltfTriangles moved(const GltfTriangles& g, const Affine& m) {
    GltfTriangles out = g;
    out.lo = {HUGE_VAL, HUGE_VAL, HUGE_VAL};
    out.hi = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
    for (size_t i = 0; i < g.positions.size(); i += 3) {
        const V3 q = apply(m, {g.positions[i], g.positions[i + 1], g.positions[i + 2]}, true);
        for (size_t k = 0; k < 3; ++k) {
            out.positions[i + k] = q[k];
            out.lo[k] = std::min(out.lo[k], q[k]);
            out.hi[k] = std::max(out.hi[k], q[k]);
        }
    }
    return out;
}

bool on_sphere(const GltfTriangles& g, const V3& c, double r, double tolerance) {
    for (size_t i = 0; i < g.positions.size() / 3; ++i)
        if (std::fabs(norm(sub(vertex(g, i), c)) - r) > tolerance * r) return false;
    return true;
}

bool on_plane(const GltfTriangles& g, const V3& p, const V3& nrm, double tolerance) {
    const double len = norm(nrm);
    double size = 1;
    for (size_t i = 0; i < g.positions.size() / 3; ++i) size = std::max(size, norm(sub(vertex(g, i), p)));
    for (size_t i = 0; i < g.positions.size() / 3; ++i) {
        const V3 d = sub(vertex(g, i), p);
        if (std::fabs(d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2]) / len > tolerance * size) return false;
    }
    return true;
}

std::vector<std::pair<V3, double>> quantised_spheres(const GltfTriangles& g, double extent) {
    std::vector<std::pair<V3, double>> out;
    for (const GltfTriangles& part : connected_parts(g)) {
        const size_t n = part.positions.size() / 3;
        const V3 c = {(part.lo[0] + part.hi[0]) / 2, (part.lo[1] + part.hi[1]) / 2, (part.lo[2] + part.hi[2]) / 2};
        double r = 0;
        for (size_t i = 0; i < n; ++i) r += norm(sub(vertex(part, i), c)) / double(n);
        const double tolerance = 2e-4 * std::max(r, extent);
        if (n < 4 || !(r > 10 * tolerance) || !on_sphere(part, c, r, tolerance / r) ||
            !tessellated(part, [&](const V3& p) { return norm(sub(p, c)) / r; }))
            return {};
        out.push_back({c, r});
    }
    return out;
}

std::vector<Affine> quantised_ellipsoids(const GltfTriangles& g, double extent) {
    std::vector<Affine> out;
    for (const GltfTriangles& part : connected_parts(g)) {
        Affine m;
        if (!fit_ellipsoid(part, m)) return {};
        const Affine inv = m.inverse();
        double longest = 0;
        for (int k = 0; k < 3; ++k) longest = std::max(longest, norm({m.m[0][k], m.m[1][k], m.m[2][k]}));
        const double tolerance = 2e-4 * std::max(extent, longest);
        auto radius_at = [&](const V3& p) { return norm(apply(inv, p, true)); };
        for (size_t i = 0; i < part.positions.size() / 3; ++i) {
            // Its distance from the surface along the ray from the centre (at least the least).
            const V3 u = apply(inv, vertex(part, i), true);
            const V3 d = apply(m, {u[0] / norm(u), u[1] / norm(u), u[2] / norm(u)}, true);
            if (!(norm(sub(d, vertex(part, i))) <= tolerance)) return {};
        }
        if (!tessellated(part, radius_at)) return {};
        out.push_back(m);
    }
    return out;
}

#endif  // RT_NO_GLTF
}  // namespace rt
