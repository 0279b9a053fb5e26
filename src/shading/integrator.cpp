// The recursive Whitted integrator (spec 2.6-2.8, section 3 "Material"), with the
// conventions the course's reference images imply (reference-conventions.md).
#include <cmath>
#include <limits>

#include "rt/bvh/intersect.h"
#include "rt/core/random.h"
#include "rt/geometry/scene.h"
#include "rt/geometry/traverse.h"
#include "rt/materials/materials.h"
#include "rt/shading/shading.h"
#include "rt/shading/trace.h"

namespace rt {
namespace {

inline Real max_component(Vec3 v) { return max_num(v.x, max_num(v.y, v.z)); }
inline Real max_abs(Vec3 v) { return max_num(std::fabs(v.x), max_num(std::fabs(v.y), std::fabs(v.z))); }

// The point a ray hit, its surface, and how the ray meets it.
struct HitPoint {
    Vec3 p;
    Surface surf;
    bool front = false;  // hit from the side the geometric normal faces
    Vec3 nf;             // shading normal facing the incoming ray
    bool lit = false;    // shaded by the lights (not a dielectric hit from inside)
};

struct Integrator {
    const Scene& s;
    TraceOptions opt;
    TraceCache* cache;  // may be null
    RayCounts& rays;    // the cache's counts, or a throwaway

    // Culling applies to every ray but those inside a dielectric, and shadow rays
    // (reference-conventions.md, "Back-face culling"; docs/conventions.md for
    // which rays count as inside).
    bool cull_of(int medium) const { return opt.cull && medium == kNoMedium; }

    // For a recorded tree only: the nearest primitive in (tmin, tmax) without culling.
    bool nearest_unculled(const Ray& ray, Real tmin, Real tmax, ShapeRef& shape, Real& t) const {
        Hit h;
        if (!closest_hit(s, ray, tmin, tmax, false, h)) return false;
        shape = {h.kind, h.index};
        t = h.t;
        return true;
    }

    // For a recorded tree only: the nearest occluder of a shadow ray that any_hit counts.
    // A closest hit any_hit does not see (a t within rounding error of 0, which shadow
    // rays ignore: intersect_triangle's kShadow) is passed over.
    bool nearest_occluder(const Ray& ray, Real tmax, ShapeRef& shape, Real& t) const {
        for (Real from = 0; nearest_unculled(ray, from, tmax, shape, t); from = t)
            if (any_hit(s, ray, 0, next_up(t))) return true;
        return false;
    }

    // Ambient + Blinn-Phong diffuse and specular from every unshadowed point light,
    // into out[i] for each point pts[i] (i < n <= N) that the lights shade
    // (HitPoint::lit), seen along incoming[i]. The shadow rays of all the points
    // towards one light are traced together (any_hits); each point adds its lights in
    // the scene's order. Every shadow ray first tests the light's last occluder
    // (TraceCache), whichever point's ray found it. `rec`: the recorded tree's node
    // when n is 1, or null (renders). N: the capacity of the arrays, kPacket or 1 (a
    // secondary ray's point writes no packet's worth of them).
    // streams[i]: point i's sample's random numbers (area lights draw from them).
    template <int N>
    void local(const HitPoint* pts, const Ray* incoming, int n, Vec3* out, RayTrace* rec, SampleStream* streams) const {
        const SceneSetup& setup = s.setup;
        for (int i = 0; i < n; ++i)
            if (pts[i].lit) out[i] = setup.materials[pts[i].surf.material].ambient * setup.ambient_light;
        if (rec) rec->ambient = out[0];
        for (size_t li = 0; li < setup.lights.size(); ++li) {
            LightTerm terms[N];
            ShadowQuery queries[N];
            int n_queries = 0;
            for (int i = 0; i < n; ++i)
                if (pts[i].lit)
                    light_term(terms[i], li, pts[i].p, pts[i].surf.ns, incoming[i].time, streams[i], queries, n_queries,
                               rec ? &rec->lights.emplace_back() : nullptr);
            bool blocked[N];
            any_hits(s, queries, n_queries, blocked);
            for (int i = 0; i < n; ++i) {
                if (!pts[i].lit) continue;
                const LightTerm& term = terms[i];
                LightTrace* lt = rec ? &rec->lights.back() : nullptr;
                if (term.query >= 0 && blocked[term.query]) {
                    if (lt) {
                        lt->shadowed = true;
                        lt->occluder_found =
                            nearest_occluder(lt->shadow, lt->shadow_tmax, lt->occluder, lt->occluder_t);
                    }
                } else if (term.facing) {
                    out[i] +=
                        light_added(setup.materials[pts[i].surf.material], term, pts[i].surf.ns, -incoming[i].dir, lt);
                }
            }
        }
        if (rec) rec->local = out[0];
    }

    // A light seen from a shaded point: what local() needs of it.
    struct LightTerm {
        size_t light = 0;  // index in SceneSetup::lights
        Vec3 scale;        // the irradiance times d^2 (LightSample)
        Vec3 l;            // unit vector to the light
        Real d2 = 0;       // squared distance
        Real ndotl = 0;
        bool facing = false;  // the light may add something (n.l above rounding noise)
        int query = -1;       // its shadow ray's index in the queries, or -1 (none traced)
    };

    // Light li at point p with outward shading normal n: its term into `term`, and its
    // shadow ray appended to queries[0 .. n_queries) when one is traced. `lt`: the
    // recorded tree's entry, or null. The term is written in place, field by field: a
    // returned one copied into the caller's array is one wide load over narrower stores,
    // which waits for them to reach the cache.
    void light_term(LightTerm& term, size_t li, Vec3 p, Vec3 n, Real time, SampleStream& stream, ShadowQuery* queries,
                    int& n_queries, LightTrace* lt) const {
        const SceneSetup& setup = s.setup;
        const Light& source = setup.lights[li];
        Real xi1 = 0, xi2 = 0;
        if (source.sampled()) stream.next2(xi1, xi2);
        const LightSample light = sample_light(source, p, xi1, xi2);
        const Vec3 to_light = light.from - p;
        term.light = li;
        term.scale = light.scale;
        term.facing = false;
        term.query = -1;
        term.d2 = dot(to_light, to_light);
        const Real d = std::sqrt(term.d2);  // the light's distance from p
        term.l = to_light / d;
        term.ndotl = dot(n, term.l);
        if (lt) {
            lt->light = li;
            lt->from = light.from;
            lt->scale = light.scale;
            lt->ndotl = term.ndotl;
        }
        // Nothing to add: diffuse is max(0, n.l) and the specular term is
        // dropped when n.l <= 0 (reference-conventions.md, "Shading"). n.l
        // within the rounding error of p counts as 0: a light lying in the
        // surface's plane would otherwise switch the specular term on and off
        // from pixel to pixel (its irradiance is huge that close).
        const Real noise = 8 * std::numeric_limits<Real>::epsilon() * (max_abs(p) + max_abs(light.from)) / d;
        if (!(term.ndotl > noise)) return;
        term.facing = true;
        if (lt) lt->facing = true;
        // Shadow ray from p + n * ShadowRayEpsilon (spec 3), never culled. It
        // reaches as far as the light is from p itself, which is up to eps past the
        // light (the origin is nearer): a surface the light lies on hides it, as the
        // references show (mirror_room's light on its ceiling plane;
        // docs/conventions.md, "Shadow rays"). It starts at t = 0: the references
        // count occluders right at the offset origin (ignoring those within eps,
        // tower_smooth goes from 16 to 461 pixels off).
        const Real eps = setup.shadow_ray_epsilon;
        const Vec3 so = p + n * eps;
        const Vec3 so_to_light = light.from - so;
        const Real dist = length(so_to_light);
        if (!(dist > 2 * eps)) return;  // a light within 2 eps of the point is never occluded
        ++rays.shadow;
        const Ray shadow{so, so_to_light / dist, time};
        if (lt) {
            lt->shadow_traced = true;
            lt->shadow = shadow;
            lt->shadow_tmax = d;
        }
        term.query = n_queries;
        queries[n_queries++] = {shadow, 0, d, cache ? &cache->last_occluder[li] : nullptr};
    }

    // Diffuse and specular of an unshadowed light that faces the point (spec 2.8).
    Vec3 light_added(const Material& m, const LightTerm& term, Vec3 n, Vec3 to_eye, LightTrace* lt) const {
        const Vec3 e = term.scale / term.d2;  // irradiance E = I / d^2 (spec 2.8; area lights: LightSample)
        const Vec3 h = normalize(term.l + to_eye);
        const Real ndoth = max_num(Real(0), dot(n, h));
        const Real lobe = phong_pow(ndoth, m.phong_exponent);
        const Vec3 added = (m.diffuse * term.ndotl + m.specular * lobe) * e;
        if (lt) {
            lt->irradiance = e;
            lt->ndoth = ndoth;
            lt->diffuse = m.diffuse * term.ndotl * e;
            lt->specular = m.specular * lobe * e;
            lt->added = added;
        }
        return added;
    }

    // The point a ray hit, its surface and whether the lights shade it.
    HitPoint hit_point(const Ray& ray, const Hit& h, RayTrace* rec) const {
        HitPoint hp;
        hp.p = ray.org + ray.dir * h.t;
        hp.surf = s.geometry.surface(h, hp.p);
        hp.front = dot(ray.dir, hp.surf.ng) < 0;
        hp.nf = hp.front ? hp.surf.ns : -hp.surf.ns;  // shading normal facing the incoming ray
        // Dielectrics are shaded only when hit from outside (reference-conventions.md).
        hp.lit = hp.front || shaded_from_inside(s.setup.materials[hp.surf.material].type);
        if (rec) {
            rec->point = hp.p;
            rec->ng = hp.surf.ng;
            rec->ns = hp.surf.ns;
            rec->nf = hp.nf;
            rec->front = hp.front;
            rec->material = hp.surf.material;
            rec->shaded = hp.lit;
        }
        return hp;
    }

    // `medium` is the dielectric material the ray travels inside, or kNoMedium. It is
    // decided by the interface that spawned the ray alone, as the references do
    // (docs/conventions.md, "Inside a dielectric"): a ray refracted into a dielectric
    // or reflected off the inside of its surface is inside it; every other ray,
    // including a mirror's or conductor's reflection met inside the glass, is not.
    // `weight` is what this ray's radiance is multiplied by in the pixel. `rec`: this
    // ray's node of the recorded tree (its kind, factor and weight set), or null (renders).
    // trace() and bounce() are inlined into their callers, so that a secondary ray costs
    // one call (shade()) as before they were split out (docs/performance.md).
    // `stream`: the random numbers of the path's sample (area lights, rough surfaces).
    [[gnu::always_inline]] Vec3 trace(const Ray& ray, int depth, int medium, bool primary, Real weight, RayTrace* rec,
                                      SampleStream& stream) const {
        Hit h;
        const bool cull = cull_of(medium);
        const bool hit = closest_hit(s, ray, 0, HUGE_VAL, cull, h);
        if (rec) record_ray(*rec, ray, depth, medium, cull, hit, h);
        return hit ? shade(ray, h, depth, medium, weight, rec, stream) : missed(primary, rec);
    }

    // The radiance of a ray that hits nothing.
    Vec3 missed(bool primary, RayTrace* rec) const {
        const Vec3 miss = primary ? s.setup.background : Vec3{};  // spec 3, BackgroundColor
        if (rec) rec->radiance = miss;
        return miss;
    }

    // The radiance of a ray (as trace()) that hits h.
    Vec3 shade(const Ray& ray, const Hit& h, int depth, int medium, Real weight, RayTrace* rec,
               SampleStream& stream) const {
        const HitPoint hp = hit_point(ray, h, rec);
        Vec3 color;
        if (hp.lit) local<1>(&hp, &ray, 1, &color, rec, &stream);
        return bounce(ray, h, hp, color, depth, medium, weight, rec, stream);
    }

    // The rest of shade() once the lights' share `color` at the hit point is known:
    // the secondary rays and Beer's law.
    [[gnu::always_inline]] Vec3 bounce(const Ray& ray, const Hit& h, const HitPoint& hp, Vec3 color, int depth,
                                       int medium, Real weight, RayTrace* rec, SampleStream& stream) const {
        const uint32_t mat_id = hp.surf.material;
        const Material& m = s.setup.materials[mat_id];

        // Beer's law on the segment a dielectric's interface sent inside it, internally
        // reflected ones included (reference-conventions.md, "Materials").
        const Vec3 beer = medium != kNoMedium ? beer_attenuation(s.setup.materials[medium].absorption_coefficient, h.t)
                                              : Vec3{1, 1, 1};
        if (rec) {
            rec->beer = medium != kNoMedium;
            rec->attenuation = beer;
            rec->depth_limit = !(depth < s.setup.max_recursion_depth);
        }
        if (depth < s.setup.max_recursion_depth) {
            // The material's secondary rays (rt/materials/), traced in its order.
            const ScatterIn in{ray,        hp.p, hp.nf, hp.front, -dot(ray.dir, hp.nf), s.setup.shadow_ray_epsilon,
                               int(mat_id)};
            ScatterOut out;
            visit_material<void>(m.type, [&](auto k) { decltype(k)::scatter(m, in, out); });
            if (rec) {
                rec->has_fresnel = out.has_fresnel;
                rec->fresnel = out.fresnel;
                rec->tir = out.tir;
                rec->refracts = out.refracts;
                rec->refracted = out.refracted;
            }
            // Adds factor * L(r) unless the ray's weight is below TraceOptions::min_weight.
            // Every path's weight at one depth sums to at most 1, so at most 1/min_weight
            // rays per depth are traced: dielectrics facing each other at MaxRecursionDepth
            // 50 stay bounded, while a skipped ray changes a pixel by less than min_weight
            // times its radiance.
            for (int i = 0; i < out.n; ++i) {
                ScatterOut::Secondary& r = out.rays[i];
                // Every secondary ray at the incoming ray's time; a rough surface's
                // turned (Roughness), drawing from the path's stream even when pruned
                // below, so that the draws do not depend on the weights.
                r.ray.time = ray.time;
                const Vec3 ideal = r.ray.dir;
                if (m.roughness > 0) {
                    Real xi1, xi2;
                    stream.next2(xi1, xi2);
                    r.ray.dir = perturb_direction(ideal, m.roughness, xi1, xi2);
                }
                const Real w = weight * max_component(beer) * max_component(r.factor);
                const Real min_weight = static_cast<Real>(opt.min_weight);
                RayTrace* child = nullptr;
                if (rec) {
                    child = &rec->children.emplace_back();
                    child->kind = r.kind;
                    child->depth = depth + 1;
                    child->ray = r.ray;
                    child->factor = r.factor;
                    child->perturbed = m.roughness > 0;
                    child->ideal = ideal;
                    child->weight = w;
                    child->pruned = !(w >= min_weight);
                }
                if (!(w >= min_weight)) continue;
                ++(r.kind == RayKind::Refraction ? rays.refraction : rays.reflection);
                color += r.factor * trace(r.ray, depth + 1, r.medium, false, w, child, stream);
            }
        }
        if (medium != kNoMedium) color = color * beer;
        if (rec) rec->radiance = color;
        return color;
    }

    // The ray's own fields of its node, and with culling the nearest back face the
    // culled query passed over (a second query, without culling).
    void record_ray(RayTrace& rec, const Ray& ray, int depth, int medium, bool cull, bool hit, const Hit& h) const {
        rec.depth = depth;
        rec.ray = ray;
        rec.tmin = 0;
        rec.tmax = HUGE_VAL;
        rec.cull = cull;
        rec.medium = medium;
        rec.hit = hit;
        if (hit) {
            rec.shape = {h.kind, h.index};
            rec.part = h.part;
            rec.t = h.t;
        }
        if (cull) rec.culled = nearest_unculled(ray, 0, hit ? h.t : HUGE_VAL, rec.culled_shape, rec.culled_t);
    }
};

}  // namespace

namespace {
// The integrator for camera rays, with the cache sized for the scene's lights.
Integrator camera_integrator(const Scene& scene, const TraceOptions& options, TraceCache* cache, RayCounts& unused) {
    if (cache && cache->last_occluder.size() != scene.setup.lights.size())
        cache->last_occluder.assign(scene.setup.lights.size(), kNoOccluder);
    return Integrator{scene, options, cache, cache ? cache->rays : unused};
}
}  // namespace

Vec3 trace_primary(const Scene& scene, const Ray& ray, const TraceOptions& options, TraceCache* cache, RayTrace* record,
                   SampleStream* stream) {
    RayCounts unused;
    const Integrator it = camera_integrator(scene, options, cache, unused);
    ++it.rays.camera;
    if (record) {
        record->kind = RayKind::Camera;
        record->weight = 1;
    }
    SampleStream fallback(0, 0, 0);
    return it.trace(ray, 0, kNoMedium, true, 1, record, stream ? *stream : fallback);
}

void trace_primaries(const Scene& scene, const Ray* rays, int n, const TraceOptions& options, TraceCache* cache,
                     SampleStream* streams, Vec3* radiance) {
    RayCounts unused;
    const Integrator it = camera_integrator(scene, options, cache, unused);
    it.rays.camera += static_cast<uint64_t>(n);
    Hit hits[kPacket];
    bool found[kPacket];
    closest_hits(scene, rays, n, 0, HUGE_VAL, it.cull_of(kNoMedium), hits, found);
    for (int i = 0; i < n; ++i)
        if (found[i]) scene.geometry.prefetch_surface(hits[i]);
    // The packet's points trace their shadow rays together (Integrator::local).
    HitPoint pts[kPacket];
    for (int i = 0; i < n; ++i)
        if (found[i]) pts[i] = it.hit_point(rays[i], hits[i], nullptr);
    Vec3 colors[kPacket];
    it.local<kPacket>(pts, rays, n, colors, nullptr, streams);
    for (int i = 0; i < n; ++i)
        radiance[i] = found[i] ? it.bounce(rays[i], hits[i], pts[i], colors[i], 0, kNoMedium, 1, nullptr, streams[i])
                               : it.missed(true, nullptr);
}

}  // namespace rt
