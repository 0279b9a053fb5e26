// The BVH's ray/box test (rt::test_node_boxes, include/rt/bvh/bvh.h): it never rejects a box
// the exact ray enters (checked in exact arithmetic: binary128 products and error-free
// sums), its entry distance is never above the exact entry by more than its rounding, and
// the SIMD and scalar versions agree lane by lane. Boxes near and far from the origin,
// flat and one float wide; rays that graze faces, edges and corners or run along walls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "bvh_test_support.h"
#include "rt/bvh/bvh.h"

namespace {

using namespace bvh_test;

// --- the box test: never rejects a box the exact ray enters -----------------------------

// Exact arithmetic for the reference: every product of two doubles (or floats) is exact in
// binary128 (106 of its 113 bits), and the sign of a sum of such products is exact through
// an expansion (Shewchuk's two-sum, error-free in any binary floating point that rounds to
// nearest).
__extension__ typedef __float128 Quad;

int exact_sign(std::initializer_list<Quad> terms) {
    std::vector<Quad> e;  // nonoverlapping, increasing magnitude, no zeros
    for (Quad q : terms) {
        std::vector<Quad> h;
        for (const Quad x : e) {
            const Quad s = q + x, bv = s - q, err = (q - (s - bv)) + (x - bv);
            if (err != 0) h.push_back(err);
            q = s;
        }
        if (q != 0) h.push_back(q);
        e = std::move(h);
    }
    return e.empty() ? 0 : e.back() > 0 ? 1 : -1;
}

// A box (float bounds, as in a node) and a ray with its t range.
struct SlabCase {
    float lo[3], hi[3];
    Vec3 org, dir;
    Real tmin, tmax;
};

// A slab distance (bound - org) / dir, kept as a fraction; bound is exact in binary128
// (a float bound moved by the padding).
struct Frac {
    Quad bound, org, dir;
};

// sign((n.bound - n.org) / n.dir - (f.bound - f.org) / f.dir), exactly. Each bound is a
// float plus or minus the padding, so it is a sum of two terms: split, every product is
// exact.
int compare(const Frac& n, const Frac& f) {
    const int s = (n.dir > 0) == (f.dir > 0) ? 1 : -1;
    return s * exact_sign({n.bound * f.dir, -n.org * f.dir, -f.bound * n.dir, f.org * n.dir});
}
// sign((x.bound - x.org) / x.dir - t), exactly (t finite).
int compare(const Frac& x, Quad t) { return (x.dir > 0 ? 1 : -1) * exact_sign({x.bound, -x.org, -t * x.dir}); }

// Whether the exact ray org + t dir, t in [tmin, tmax], meets the closed box [lo, hi]
// grown by `pad` on every side; `entry` gets the near fractions (the entry is their
// maximum and tmin).
bool exact_enters(const SlabCase& c, Quad pad, std::vector<Frac>* entry = nullptr) {
    std::vector<Frac> nears, fars;
    for (int a = 0; a < 3; ++a) {
        const Quad lo = Quad(c.lo[a]) - pad, hi = Quad(c.hi[a]) + pad;
        if (c.dir[a] == 0) {
            if (!(lo <= Quad(c.org[a]) && Quad(c.org[a]) <= hi)) return false;
            continue;
        }
        const bool pos = c.dir[a] > 0;
        nears.push_back({pos ? lo : hi, Quad(c.org[a]), Quad(c.dir[a])});
        fars.push_back({pos ? hi : lo, Quad(c.org[a]), Quad(c.dir[a])});
    }
    if (c.tmin > c.tmax) return false;
    for (const Frac& f : fars)
        if (compare(f, Quad(c.tmin)) < 0) return false;
    for (const Frac& n : nears) {
        if (std::isfinite(c.tmax) && compare(n, Quad(c.tmax)) > 0) return false;
        for (const Frac& f : fars)
            if (compare(n, f) > 0) return false;
    }
    if (entry) *entry = nears;
    return true;
}

// A value of magnitude around 10^e, either sign.
Real around(Rng& rng, int e) { return (pick(rng, 2) ? 1 : -1) * uniform(rng, 0.5, 2) * std::pow(Real(10), Real(e)); }

// Boxes (flat ones, one float wide ones) near and far from the world origin; rays that
// graze the faces, edges and corners of the box as the test pads it, run along the walls
// of flat boxes, or just miss; zero, tiny and huge direction components; t limits on and
// around the entry. `bvh` gets the box's extent, as for a scene of this one box.
SlabCase random_slab_case(Rng& rng, rt::Bvh& bvh);

// random_slab_case, drawn again until the ray's origin is finite (a tiny direction and a
// long distance can overflow it; the renderer's rays never have such origins).
SlabCase finite_slab_case(Rng& rng, rt::Bvh& bvh) {
    for (;;) {
        const SlabCase c = random_slab_case(rng, bvh);
        if (std::isfinite(c.org.x) && std::isfinite(c.org.y) && std::isfinite(c.org.z)) return c;
    }
}

SlabCase random_slab_case(Rng& rng, rt::Bvh& bvh) {
    SlabCase c;
    const int scale_exp = static_cast<int>(pick(rng, 7)) - 3;  // box sizes 1e-3 .. 1e3
    const int centre_exp = std::vector<int>{0, 0, 3, 6, 10}[pick(rng, 5)];
    for (int a = 0; a < 3; ++a) {
        const Real centre = pick(rng, 4) == 0 ? 0 : around(rng, centre_exp);
        c.lo[a] = rt::round_down_to_float(centre);
        const size_t kind = pick(rng, 4);  // flat, one ulp, sized, sized
        const Real extent = kind <= 1 ? 0 : std::fabs(around(rng, scale_exp));
        c.hi[a] = kind == 1 ? std::nextafter(c.lo[a], HUGE_VALF) : rt::round_up_to_float(c.lo[a] + extent);
    }
    bvh.extent = 0;
    for (int a = 0; a < 3; ++a) bvh.extent = std::max({bvh.extent, std::fabs(c.lo[a]), std::fabs(c.hi[a])});
    Vec3 d = random_unit(rng);
    const size_t dir_kind = pick(rng, 8);
    const int on_boundary = static_cast<int>(pick(rng, 4));  // axes on a bound: 0 inside .. 3 corner
    if (dir_kind == 0) {                                     // along a wall: zero components on bound axes
        for (int a = 0; a < on_boundary && a < 2; ++a) d[a] = pick(rng, 2) ? Real(0) : Real(-0.0);
    } else if (dir_kind == 1) {  // axis-aligned
        const int keep = static_cast<int>(pick(rng, 3));
        for (int a = 0; a < 3; ++a)
            if (a != keep) d[a] = 0;
    } else if (dir_kind == 2) {  // tiny or huge components
        for (int a = 0; a < 3; ++a) {
            const size_t k = pick(rng, 5);
            d[a] *= k == 0 ? Real(1e-30) : k == 1 ? Real(1e30) : k == 2 ? Real(1e-45) : k == 3 ? Real(3e38) : 1;
        }
    } else if (dir_kind == 3) {  // tiny or huge as a whole
        d = d * (pick(rng, 3) == 0 ? Real(1e-30) : pick(rng, 2) ? Real(1e30) : Real(2e38));
    }
    if (d[0] == 0 && d[1] == 0 && d[2] == 0) d[2] = 1;
    // The origin is picked first, some distance back from the box; the padding the test
    // applies for it is known then, and the target point is chosen on the padded box:
    // on a face, an edge, a corner, inside, or a few ulps off a bound.
    const Real len = rt::length(d);
    const Real dist =
        pick(rng, 6) == 0 ? 0 : std::fabs(around(rng, std::vector<int>{-30, -10, -2, 0, 1, 3, 6, 10}[pick(rng, 8)]));
    const Real s = dist / len;
    Vec3 centre;
    for (int a = 0; a < 3; ++a) centre[a] = (Real(c.lo[a]) + Real(c.hi[a])) / 2;
    const Quad pad = Quad(rt::box_padding(bvh, {centre - d * s, d}));
    Vec3 target;
    for (int a = 0; a < 3; ++a) {
        const bool bound = a < on_boundary;
        const bool hi_side = pick(rng, 2);
        Real v = bound ? Real(hi_side ? Quad(c.hi[a]) + pad : Quad(c.lo[a]) - pad) : uniform(rng, c.lo[a], c.hi[a]);
        if (bound && pick(rng, 4) == 0) {  // just outside (or inside) by a few ulps
            for (int k = 1 + static_cast<int>(pick(rng, 3)); k > 0; --k)
                v = std::nextafter(v, pick(rng, 2) ? Real(HUGE_VAL) : Real(-HUGE_VAL));
        }
        target[a] = v;
    }
    // (rounded: the ray passes within rounding of the target, on either side)
    c.org = target - d * s;
    c.dir = d;
    c.tmin = pick(rng, 3) == 0 ? s * uniform(rng, 0, 1) : 0;
    const size_t tk = pick(rng, 5);
    c.tmax = tk == 0   ? Real(HUGE_VAL)
             : tk == 1 ? s
             : tk == 2 ? std::nextafter(s, Real(0))
             : tk == 3 ? s * uniform(rng, 1, 2)
                       : std::nextafter(s, Real(HUGE_VAL));
    if (c.tmax < c.tmin) c.tmax = c.tmin;
    return c;
}

TEST(BvhBoxTest, NeverRejectsABoxTheExactRayEnters) {
    Rng rng(13);
    int entered = 0, rejected = 0, late_entry = 0, lane_mismatch = 0;
    std::string first_failure;
    for (int k = 0; k < 200000; ++k) {
        rt::Bvh bvh;
        const SlabCase c = finite_slab_case(rng, bvh);
        constexpr int kWidth = rt::BvhNode::kWidth;
        rt::BvhNode n;
        for (int i = 0; i < kWidth; ++i) {  // the case's box in every slot but the last (empty)
            for (int a = 0; a < 3; ++a) {
                n.lo[a][i] = i < kWidth - 1 ? c.lo[a] : HUGE_VALF;
                n.hi[a][i] = i < kWidth - 1 ? c.hi[a] : -HUGE_VALF;
            }
            n.child[i] = rt::BvhNode::kEmpty;
            n.count[i] = 0;
        }
        const rt::Ray ray{c.org, c.dir};
        Real t[kWidth], ts[kWidth];
        const int mask = rt::test_node_boxes(bvh, n, ray, c.tmin, c.tmax, t, false);
        const int mask_scalar = rt::test_node_boxes(bvh, n, ray, c.tmin, c.tmax, ts, true);
        if (mask != mask_scalar) ++lane_mismatch;
        for (int i = 0; i < kWidth; ++i)
            if ((mask >> i & 1) && std::memcmp(&t[i], &ts[i], sizeof(Real)) != 0) ++lane_mismatch;
        // Float rays with a direction component above 2^100 are outside the float box
        // test's domain (rt/bvh/box_test.h, kDirDomain): they enter every slot, empty ones too.
        const Real largest = std::max({std::fabs(c.dir[0]), std::fabs(c.dir[1]), std::fabs(c.dir[2])});
        if (!(std::is_same_v<Real, float> && largest > Real(0x1p100))) {
            EXPECT_EQ(mask >> (kWidth - 1), 0) << "an empty slot was entered";
        }
        std::vector<Frac> nears;
        if (!exact_enters(c, Quad(rt::box_padding(bvh, ray)), &nears)) continue;
        ++entered;
        if (!(mask & 1)) {
            ++rejected;
            if (first_failure.empty()) {
                std::ostringstream os;
                os.precision(17);
                os << "box lo " << c.lo[0] << ' ' << c.lo[1] << ' ' << c.lo[2] << " hi " << c.hi[0] << ' ' << c.hi[1]
                   << ' ' << c.hi[2] << " org " << c.org[0] << ' ' << c.org[1] << ' ' << c.org[2] << " dir " << c.dir[0]
                   << ' ' << c.dir[1] << ' ' << c.dir[2] << " t " << c.tmin << ' ' << c.tmax;
                first_failure = os.str();
            }
            continue;
        }
        // The entry bound: in float at most the exact entry rounded up to a float (the
        // exact entry lies above the float below t); in double at most a factor 1 + 2^-50
        // above it (three roundings), give or take a few subnormals where they underflow.
        constexpr bool kFloat = std::is_same_v<Real, float>;
        const Quad below_t =
            kFloat ? Quad(std::nextafter(float(t[0]), -HUGE_VALF)) : Quad(t[0]) * (1 - Quad(0x1p-50)) - Quad(0x1p-1070);
        const int least = kFloat ? 1 : 0;  // the sign that (entry - below_t) must reach
        bool on_time = (Quad(c.tmin) > below_t) - (Quad(c.tmin) < below_t) >= least;
        for (const Frac& f : nears) on_time = on_time || compare(f, below_t) >= least;
        if (!on_time) ++late_entry;
    }
    EXPECT_GT(entered, 50000) << "too few cases enter their box to test anything";
    EXPECT_EQ(rejected, 0) << "of " << entered << " boxes the exact ray enters; first: " << first_failure;
    EXPECT_EQ(late_entry, 0) << "entry distances above the exact entry";
    EXPECT_EQ(lane_mismatch, 0) << "the SIMD and scalar box tests disagree";
}

}  // namespace
