// Shared by the BVH tests (tests/test_bvh_*.cpp): random numbers, a brute-force loop over
// every primitive, the Checker that compares rt::closest_hit, rt::any_hit and their packet
// forms (closest_hits, any_hits) with it, the structural check of a built tree, and
// shoot, rays from around a scene.
#pragma once
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "rt/bvh/bvh.h"
#include "rt/geometry/scene.h"
#include "rt/geometry/traverse.h"

namespace bvh_test {

using rt::Real;
using rt::Vec3;
using Rng = std::mt19937_64;

inline Real uniform(Rng& rng, Real lo, Real hi) { return std::uniform_real_distribution<Real>(lo, hi)(rng); }
inline size_t pick(Rng& rng, size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); }

// A random unit vector.
Vec3 random_unit(Rng& rng);

// --- brute force -------------------------------------------------------------------

struct Answer {
    bool found = false;
    Real t = HUGE_VAL;
    uint32_t gid = 0;  // triangles, then spheres, then planes
    Real w[3] = {0, 0, 0};
};

// The id of a hit in the brute force's numbering (triangles, then spheres, then planes).
uint32_t global_id(const rt::Scene& s, const rt::Hit& h);

// The closest hit in (tmin, tmax) of every primitive tested in turn (ties to the lowest
// id), culling back faces when `cull`; and whether any primitive is hit.
Answer brute_closest(const rt::Scene& s, const rt::Ray& r, Real tmin, Real tmax, bool cull);
bool brute_any(const rt::Scene& s, const rt::Ray& r, Real tmin, Real tmax);

// The ray and its t range, for failure messages.
std::string describe(const rt::Ray& r, Real tmin, Real tmax);

// Compares closest_hit (cull on and off) and any_hit with brute force for one ray.
// Returns the number of mismatches (reporting the first few through gtest).
struct Checker {
    const rt::Scene& s;
    int mismatches = 0;
    int hits = 0, queries = 0, closest_queries = 0;

    void fail(const std::string& msg) {
        if (++mismatches <= 8) ADD_FAILURE() << msg;
    }

    void closest(const rt::Ray& r, Real tmin, Real tmax) {
        for (bool cull : {false, true}) {
            ++queries;
            ++closest_queries;
            const Answer want = brute_closest(s, r, tmin, tmax, cull);
            rt::Hit got;
            const bool found = rt::closest_hit(s, r, tmin, tmax, cull, got);
            if (found != want.found) {
                fail(describe(r, tmin, tmax) + (cull ? " cull" : " no cull") + ": closest_hit says " +
                     (found ? "hit" : "miss") + ", brute force says " + (want.found ? "hit" : "miss") +
                     (want.found ? " (id " + std::to_string(want.gid) + ")" : std::string()));
                continue;
            }
            if (!found) continue;
            ++hits;
            const uint32_t gid = global_id(s, got);
            if (got.t != want.t || gid != want.gid) {
                std::ostringstream o;
                o.precision(17);
                o << describe(r, tmin, tmax) << (cull ? " cull" : " no cull") << ": closest_hit id " << gid << " t "
                  << got.t << ", brute force id " << want.gid << " t " << want.t;
                fail(o.str());
                continue;
            }
            if (got.kind == rt::ShapeKind::Triangle &&
                (got.w[0] != want.w[0] || got.w[1] != want.w[1] || got.w[2] != want.w[2]))
                fail(describe(r, tmin, tmax) + ": barycentric weights differ");
        }
    }

    // closest_hits (the packet traversal) against closest_hit, ray by ray, for the
    // rays of one packet: the same answer to the last bit (hit, t, primitive,
    // leaf-order corners, and a triangle's weights: other shapes have none). Rays from random places make packets whose
    // rays part at once; neighbouring camera rays, packets that part at silhouettes.
    void packet(const rt::Ray* rays, int n, Real tmin, Real tmax) {
        for (bool cull : {false, true}) {
            ++queries;
            rt::Hit got[rt::kPacket];
            bool found[rt::kPacket];
            rt::closest_hits(s, rays, n, tmin, tmax, cull, got, found);
            for (int i = 0; i < n; ++i) {
                rt::Hit want;
                const bool want_found = rt::closest_hit(s, rays[i], tmin, tmax, cull, want);
                const std::string where = describe(rays[i], tmin, tmax) + (cull ? " cull" : " no cull") + ", ray " +
                                          std::to_string(i) + " of a packet of " + std::to_string(n);
                if (found[i] != want_found) {
                    fail(where + ": closest_hits says " + (found[i] ? "hit" : "miss") + ", closest_hit " +
                         (want_found ? "hit" : "miss"));
                } else if (want_found &&
                           (got[i].t != want.t || got[i].kind != want.kind || got[i].index != want.index ||
                            got[i].corners != want.corners || got[i].stride != want.stride ||
                            (want.kind == rt::ShapeKind::Triangle &&
                             (got[i].w[0] != want.w[0] || got[i].w[1] != want.w[1] || got[i].w[2] != want.w[2])))) {
                    fail(where + ": closest_hits and closest_hit differ");
                }
            }
        }
    }

    // Closest-hit queries over (0, inf) are also collected into packets of 1, 2, ..
    // kPacket rays in turn (pending), checked by packet(); finish() checks the last one.
    std::vector<rt::Ray> pending = {};
    int next_packet = 1;
    void collect(const rt::Ray& r) {
        pending.push_back(r);
        if (static_cast<int>(pending.size()) == next_packet) finish();
    }
    void finish() {
        if (!pending.empty()) packet(pending.data(), static_cast<int>(pending.size()), 0, HUGE_VAL);
        pending.clear();
        next_packet = next_packet % rt::kPacket + 1;
        finish_any();
    }

    void any(const rt::Ray& r, Real tmin, Real tmax) {
        ++queries;
        const bool want = brute_any(s, r, tmin, tmax);
        if (rt::any_hit(s, r, tmin, tmax) != want)
            fail(describe(r, tmin, tmax) + ": any_hit says " + (want ? "miss" : "hit") + ", brute force says " +
                 (want ? "hit" : "miss"));
        collect_any({r, tmin, tmax, nullptr});
    }

    // any_hits (the packet any-hit traversal) against any_hit, query by query, for one
    // packet of queries. Every other packet's queries share one hint, as the
    // integrator's shadow rays towards one light do: absent at first (kNoOccluder) or a
    // random primitive, then whatever the traversal writes into it.
    uint32_t shared_hint = rt::kNoOccluder;
    int any_packets = 0;
    void any_packet(rt::ShadowQuery* q, int n, Rng& rng) {
        ++queries;
        const size_t prims = s.accel.bvh.prims.size();
        shared_hint = (prims == 0 || pick(rng, 2)) ? rt::kNoOccluder : static_cast<uint32_t>(pick(rng, prims));
        const bool hinted = ++any_packets % 2 == 0;
        for (int i = 0; i < n; ++i) q[i].occluder = hinted ? &shared_hint : nullptr;
        bool got[rt::kPacket];
        rt::any_hits(s, q, n, got);
        for (int i = 0; i < n; ++i) {
            const bool want = rt::any_hit(s, q[i].ray, q[i].tmin, q[i].tmax);
            if (got[i] != want)
                fail(describe(q[i].ray, q[i].tmin, q[i].tmax) + ", query " + std::to_string(i) + " of a packet of " +
                     std::to_string(n) + (hinted ? " (hinted)" : "") + ": any_hits says " + (got[i] ? "hit" : "miss") +
                     ", any_hit " + (want ? "hit" : "miss"));
        }
    }

    // The points where `rays` (a camera packet) first hit the scene, without culling.
    std::vector<Vec3> hit_points(const rt::Ray* rays, int n) const {
        std::vector<Vec3> points;
        for (int i = 0; i < n; ++i) {
            rt::Hit h;
            if (rt::closest_hit(s, rays[i], 0, HUGE_VAL, false, h)) points.push_back(rays[i].org + rays[i].dir * h.t);
        }
        return points;
    }

    // The shadow rays from `points` (at most kPacket) towards `light`, from just off
    // each point: one packet for any_packet.
    void shadow_packet(const std::vector<Vec3>& points, Vec3 light, Rng& rng) {
        rt::ShadowQuery q[rt::kPacket];
        int m = 0;
        for (const Vec3& p : points) {
            const Real d = rt::length(light - p);
            if (d > 0) q[m++] = {{p, (light - p) / d}, Real(1e-4) * d, d, nullptr};
        }
        any_packet(q, m, rng);
    }

    // any() queries are also collected into packets of 1, 2, .. kPacket queries in turn
    // (pending_any), checked by any_packet(); finish() checks the last one.
    std::vector<rt::ShadowQuery> pending_any = {};
    int next_any_packet = 1;
    Rng any_rng{4242};
    void collect_any(const rt::ShadowQuery& q) {
        pending_any.push_back(q);
        if (static_cast<int>(pending_any.size()) == next_any_packet) finish_any();
    }
    void finish_any() {
        if (!pending_any.empty()) any_packet(pending_any.data(), static_cast<int>(pending_any.size()), any_rng);
        pending_any.clear();
        next_any_packet = next_any_packet % rt::kPacket + 1;
    }
};

// --- structure -----------------------------------------------------------------------

// Checks that s.accel.bvh is well formed: every primitive in exactly one leaf, every node
// reached once, every box around its primitives or its child node's boxes, depth <= 64.
void check_structure(const rt::Scene& s);

// Rays from around the scene: random directions, rays aimed at vertices, edge points,
// interior points and sphere surfaces, axis-aligned rays, and random t intervals.
void shoot(const rt::Scene& s, Checker& ck, Rng& rng, int rays, Real extent);

}  // namespace bvh_test
