// The scene's ray queries: closest hit (src/geometry/closest.cpp) and any hit
// (src/geometry/any_hit.cpp), one ray or a packet of neighbouring rays.
#pragma once
#include <cstdint>

#include "rt/geometry/scene.h"

namespace rt {

// Closest hit in (tmin, tmax). With `cull`, triangles whose geometric normal
// points along the ray are ignored (spec 2.9). Ties in t go to the lower
// primitive id, so the answer does not depend on the BVH layout.
bool closest_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, bool cull, Hit& hit);

// closest_hit for n rays at once (1 <= n <= kPacket), found[i] its result for
// rays[i], hits[i] its hit: the same answers, for rays that are near each other
// (camera rays of neighbouring pixels) in less time, each node loaded once for all.
constexpr int kPacket = 16;
void closest_hits(const Scene& scene, const Ray* rays, int n, Real tmin, Real tmax, bool cull, Hit* hits, bool* found);

// True when anything lies in (tmin, tmax); never culls (spec 2.9: shadow rays).
// `occluder`, when given, is a hint: a BVH primitive id (or kNoOccluder) tested
// before the traversal, and on a BVH hit it receives the id that was found.
// Neighbouring shadow rays are mostly blocked by the same primitive; the answer
// never depends on the hint.
constexpr uint32_t kNoOccluder = ~0u;
bool any_hit(const Scene& scene, const Ray& ray, Real tmin, Real tmax, uint32_t* occluder = nullptr);

// any_hit for n queries at once (0 <= n <= kPacket), hit[i] the answer for
// queries[i]: the same answers, for rays that are near each other (the shadow rays
// of a camera packet's points towards one light) in less time, each node loaded
// once for all.
struct ShadowQuery {
    Ray ray;
    Real tmin, tmax;
    uint32_t* occluder;  // any_hit's hint, or null
};
void any_hits(const Scene& scene, const ShadowQuery* queries, int n, bool* hit);

}  // namespace rt
