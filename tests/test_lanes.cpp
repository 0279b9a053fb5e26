// The traversal's box test (include/rt/bvh/box_test.h) for every lane type compiled
// into this build (include/rt/bvh/lanes.h) against the scalar kernel, OneLane, as
// tinybvh's SIMD reference test does: the same hit mask, and the same entry distances
// to the bit where it hits. The lane types must do the same IEEE operation in every
// lane (NaN and signed zero included) for the traversal to give the same images on
// every CPU, so the cases dwell on the edges: rays through box corners and edges,
// along slab planes with zero direction components, starting inside boxes or on their
// faces, clipped by tmin and tmax; flat, point and empty boxes; and for the float test
// rays outside its domain. Both precisions' tests run in both test programs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <type_traits>
#include <vector>

#include "rt/bvh/box_test.h"
#include "rt/bvh/bvh.h"
#include "rt/bvh/intersect.h"
#include "rt/bvh/lanes.h"

namespace {

namespace tr = rt::traversal;
using rt::Real;
using rt::Vec3;
using Rng = std::mt19937_64;
constexpr int kWidth = rt::BvhNode::kWidth;

Real uniform(Rng& rng, Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }
size_t pick(Rng& rng, size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }

// One node and one ray, with the ray's interval and the scene extent the float test
// pads by (Bvh::extent).
struct Case {
    rt::BvhNode node;
    rt::Ray ray;
    Real tmin, tmax;
    float extent;
};

// A node of boxes that touch, nest and degenerate: random, flat, point, copied from
// another slot, sharing a face with another, and empty slots.
void random_node(Rng& rng, rt::BvhNode& n) {
    const float scale = std::vector<float>{1, 100, 1e-3f, 1e6f}[pick(rng, 4)];
    for (int i = 0; i < kWidth; ++i) {
        const size_t kind = pick(rng, 8);
        for (int a = 0; a < 3; ++a) {
            float lo = float(uniform(rng, -1, 1)) * scale, hi = lo + float(uniform(rng, 0, 1)) * scale;
            if (kind == 0) lo = HUGE_VALF, hi = -HUGE_VALF;  // empty
            if (kind == 1 && a == 0) hi = lo;                // flat
            if (kind == 2) hi = lo;                          // point
            if (kind == 3 && i > 0) lo = n.lo[a][i - 1], hi = n.hi[a][i - 1];
            if (kind == 4 && i > 0 && a == 0) lo = n.hi[a][i - 1];  // shares a face
            if (kind == 4 && i > 0 && a != 0) lo = n.lo[a][i - 1], hi = n.hi[a][i - 1];
            if (kind == 5) lo = -std::fabs(lo), hi = std::fabs(hi);  // around the origin
            if (kind != 0 && hi < lo) hi = lo;
            n.lo[a][i] = lo;
            n.hi[a][i] = hi;
        }
        n.child[i] = rt::BvhNode::kEmpty;
        n.count[i] = 0;
    }
}

// A point of slot i: a corner, a point on an edge or a face, or inside.
Vec3 box_point(Rng& rng, const rt::BvhNode& n, int i) {
    const size_t on_bounds = pick(rng, 4);  // axes on a bound: 0 inside .. 3 corner
    Vec3 p;
    for (int a = 0; a < 3; ++a) {
        const Real lo = n.lo[a][i], hi = n.hi[a][i];
        p[a] = size_t(a) < on_bounds ? (pick(rng, 2) ? lo : hi) : lo + (hi - lo) * uniform(rng, 0, 1);
    }
    return p;
}

Case random_case(Rng& rng, const rt::BvhNode& node) {
    Case c;
    c.node = node;
    int box = static_cast<int>(pick(rng, kWidth));
    for (int k = 0; k < kWidth && !(node.lo[0][box] <= node.hi[0][box]); ++k) box = (box + 1) % kWidth;
    const bool real_box = node.lo[0][box] <= node.hi[0][box];
    const Vec3 target = real_box ? box_point(rng, node, box) : Vec3{0, 0, 0};
    Vec3 dir{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
    Vec3 org = target - dir * uniform(rng, 0, 4);
    switch (pick(rng, 6)) {
        case 0:  // along slab planes: zero components (either sign), the origin on the box's bounds
            for (int a = 0; a < 3; ++a)
                if (pick(rng, 2)) {
                    dir[a] = pick(rng, 2) ? Real(0) : Real(-0.0);
                    org[a] = target[a];
                }
            break;
        case 1:  // from one box point to another (corner to corner, edge to edge)
            if (real_box) org = box_point(rng, node, box), dir = target - org;
            break;
        case 2:  // from a point of another slot through this one's
            org = box_point(rng, node, static_cast<int>(pick(rng, kWidth)));
            if (!std::isfinite(org[0] + org[1] + org[2])) org = {0, 0, 0};
            dir = target - org;
            break;
        case 3:  // tiny and huge components (the float test's domain ends at 2^100)
            for (int a = 0; a < 3; ++a)
                dir[a] *= std::vector<Real>{Real(1e-30), Real(1e30), Real(0x1p101), 1}[pick(rng, 4)];
            break;
        default:
            break;
    }
    if (dir[0] == 0 && dir[1] == 0 && dir[2] == 0) dir[pick(rng, 3)] = pick(rng, 2) ? Real(1) : Real(-1);
    c.ray = {org, dir};
    const Real near = uniform(rng, 0, 4);
    c.tmin = std::vector<Real>{0, 0, near, Real(-1), Real(-0.0)}[pick(rng, 5)];
    c.tmax = std::vector<Real>{Real(HUGE_VAL), Real(HUGE_VAL), near, c.tmin, Real(1e-30), 0}[pick(rng, 6)];
    // The float test pads by the scene's extent: the node's, none (unpadded rays keep
    // their origin's bits), or beyond the test's domain (2^125: every box entered).
    float extent = 0;
    for (int a = 0; a < 3; ++a)
        for (int i = 0; i < kWidth; ++i)
            if (node.lo[a][i] <= node.hi[a][i])
                extent = std::max({extent, std::fabs(node.lo[a][i]), std::fabs(node.hi[a][i])});
    c.extent = std::vector<float>{extent, extent, 0, 0x1p126f}[pick(rng, 4)];
    return c;
}

std::vector<Case> random_cases(uint64_t seed, int n) {
    Rng rng(seed);
    std::vector<Case> cases;
    rt::BvhNode node;
    for (int k = 0; k < n; ++k) {
        if (k % 8 == 0) random_node(rng, node);
        cases.push_back(random_case(rng, node));
    }
    return cases;
}

const std::vector<Case>& cases() {
    static const std::vector<Case> all = random_cases(34, 60000);
    return all;
}

// What a comparison of two box tests found.
struct Tally {
    long cases = 0, lanes_hit = 0, lanes_missed = 0, mismatches = 0;
    std::string first;
};

// The box test in precision B (double or float) with lane type O, against `reference`,
// called as test_lanes is, on every case.
template <class B, class O, class Reference>
Tally compare(const Reference& reference) {
    Tally tally;
    for (const Case& c : cases()) {
        rt::Bvh bvh;
        bvh.extent = c.extent;
        const auto br = tr::box_ray_of<B>(rt::prepare(c.ray), bvh, c.tmin);
        alignas(tr::kBoxesAlign) B t[kWidth], want_t[kWidth];
        const int mask = tr::test_lanes<O>(c.node, br, B(c.tmin), B(c.tmax), t);
        const int want = reference(c.node, br, B(c.tmin), B(c.tmax), want_t);
        ++tally.cases;
        bool same = mask == want;
        for (int i = 0; i < kWidth; ++i) {
            if (want >> i & 1) {
                ++tally.lanes_hit;
                same = same && std::memcmp(&t[i], &want_t[i], sizeof(B)) == 0;
            } else {
                ++tally.lanes_missed;
            }
        }
        if (!same && tally.mismatches++ == 0) {
            char buf[512];
            std::snprintf(buf, sizeof buf,
                          "org %.17g %.17g %.17g dir %.17g %.17g %.17g t %.17g %.17g: mask %#x, scalar %#x",  //
                          double(c.ray.org[0]), double(c.ray.org[1]), double(c.ray.org[2]), double(c.ray.dir[0]),
                          double(c.ray.dir[1]), double(c.ray.dir[2]), double(c.tmin), double(c.tmax), unsigned(mask),
                          unsigned(want));
            tally.first = buf;
        }
    }
    return tally;
}

// The scalar kernel: test_lanes over OneLane, what builds without SIMD run.
template <class B>
int scalar_kernel(const rt::BvhNode& n, const tr::BoxRayOf<B>& r, B tmin, B tmax, B t[kWidth]) {
    return tr::test_lanes<tr::OneLane<B>>(n, r, tmin, tmax, t);
}

// The lane type O of precision B against the scalar kernel; its name joins `compared`.
template <class B, class O>
void expect_matches_scalar(const char* name, std::vector<std::string>& compared) {
    const Tally tally = compare<B, O>(scalar_kernel<B>);
    compared.push_back(name);
    EXPECT_EQ(tally.mismatches, 0) << name << " differs from OneLane<"
                                   << (std::is_same_v<B, float> ? "float" : "double") << "> in " << tally.mismatches
                                   << " of " << tally.cases << " cases; first: " << tally.first;
    // Enough of both outcomes that the comparison says something.
    EXPECT_GT(tally.lanes_hit, tally.cases) << name;
    EXPECT_GT(tally.lanes_missed, tally.cases) << name;
}

// The box test of one box, written out slab by slab from box_test.h's formulas: the
// scalar kernel's lane layout (which slot each lane and mask bit is) checked apart
// from the lane abstraction.
bool slab_test(const rt::BvhNode& n, int i, const tr::BoxRayOf<double>& r, double tmin, double tmax, double& t) {
    double tnear = tmin, tfar = tmax * tr::kSlabWiden;
    for (int a = 0; a < 3; ++a) {
        const double lo = n.lo[a][i], hi = n.hi[a][i];
        const double t0 = ((r.near_is_hi[a] ? hi : lo) - r.org[a]) * r.inv[a];
        const double t1 = ((r.near_is_hi[a] ? lo : hi) - r.org[a]) * r.inv[a] * tr::kSlabWiden;
        if (t0 > tnear) tnear = t0;  // a NaN leaves the interval as it was
        if (t1 < tfar) tfar = t1;
    }
    t = tnear <= tfar ? tnear : HUGE_VAL;
    return tnear <= tfar;
}
bool slab_test(const rt::BvhNode& n, int i, const tr::BoxRayOf<float>& r, float tmin, float tmax, float& t) {
    float tnear = tmin, tfar = tmax;
    for (int a = 0; a < 3; ++a) {
        const float lo = n.lo[a][i], hi = n.hi[a][i];
        const float t0 = ((r.near_is_hi[a] ? hi : lo) - r.org_near[a]) * r.inv_near[a];
        const float t1 = ((r.near_is_hi[a] ? lo : hi) - r.org_far[a]) * r.inv_far[a];
        if (t0 > tnear) tnear = t0;
        if (t1 < tfar) tfar = t1;
    }
    t = tnear;
    return tnear <= tfar;
}
template <class B>
int per_box(const rt::BvhNode& n, const tr::BoxRayOf<B>& r, B tmin, B tmax, B t[kWidth]) {
    int mask = 0;
    for (int i = 0; i < kWidth; ++i) mask |= slab_test(n, i, r, tmin, tmax, t[i]) << i;
    return mask;
}

TEST(BoxTestLanes, ScalarKernelIsTheSlabTestOfEachBox) {
    for (const Tally& tally :
         {compare<double, tr::OneLane<double>>(per_box<double>), compare<float, tr::OneLane<float>>(per_box<float>)})
        EXPECT_EQ(tally.mismatches, 0) << "of " << tally.cases << " cases; first: " << tally.first;
}

TEST(BoxTestLanes, EverySimdLaneTypeMatchesTheScalarKernel) {
    std::vector<std::string> compared;
#if defined(__SSE2__)
    expect_matches_scalar<float, tr::F32x4>("F32x4", compared);
#endif
#if defined(__AVX__)
    expect_matches_scalar<float, tr::F32x8>("F32x8", compared);
    expect_matches_scalar<double, tr::F64x4>("F64x4", compared);
#endif
#if defined(__AVX512F__)
    expect_matches_scalar<double, tr::F64x8>("F64x8", compared);
#endif
    std::string names;
    for (const std::string& name : compared) names += (names.empty() ? "" : " ") + name;
    RecordProperty("lane_types", names.empty() ? "none" : names);
    std::printf("[lanes] against OneLane<float> and OneLane<double>: %s\n", names.empty() ? "none" : names.c_str());
#if defined(__x86_64__)
    // SSE2 is part of x86-64: a build that compiles none of the SIMD types has lost its
    // SIMD box test.
    EXPECT_FALSE(compared.empty()) << "no SIMD lane type compiled into an x86-64 build";
#endif
}

// Lane types that break the contract the way a wrong intrinsic would: the comparison
// must see each of them, or the cases miss what they are there for.
template <class T>
struct NanFirstMax : tr::OneLane<T> {  // max keeps the first operand on NaN (and on +-0)
    static T max(T a, T b) { return b > a ? b : a; }
};
template <class T>
struct NanFirstMin : tr::OneLane<T> {
    static T min(T a, T b) { return b < a ? b : a; }
};
template <class T>
struct StrictLess : tr::OneLane<T> {  // rejects boxes the ray only touches
    static bool le(T a, T b) { return a < b; }
};

template <class B>
void expect_caught() {
    EXPECT_GT((compare<B, NanFirstMax<B>>(scalar_kernel<B>).mismatches), 0) << "max's NaN operand order";
    EXPECT_GT((compare<B, NanFirstMin<B>>(scalar_kernel<B>).mismatches), 0) << "min's NaN operand order";
    EXPECT_GT((compare<B, StrictLess<B>>(scalar_kernel<B>).mismatches), 0) << "touching boxes";
}

TEST(BoxTestLanes, ComparisonCatchesAWrongLaneType) {
    expect_caught<double>();
    expect_caught<float>();
}

}  // namespace
