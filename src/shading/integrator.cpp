// The recursive Whitted integrator (spec 2.6-2.8, section 3 "Material"), with the
// conventions the course's reference images imply (reference-conventions.md).
#include <cmath>
#include <limits>

#include "rt/intersect.h"
#include "rt/scene.h"
#include "rt/shading.h"
#include "rt/trace.h"

namespace rt {
namespace {

constexpr int kNoMedium = -1;

// A reflected or refracted ray is not traced when the factor its radiance would
// be multiplied by on its way to the pixel (products of MirrorReflectance x
// Fresnel, 1 - Fresnel and Beer's law along the path) is below this. Every
// path's weight at one depth sums to at most 1, so at most 1/kMinWeight rays
// per depth survive: dielectrics facing each other at MaxRecursionDepth 50 stay
// bounded, while a pruned ray changes a pixel by less than kMinWeight times its
// radiance (the official scenes render to the same bytes either way).
constexpr Real kMinWeight = Real(1e-4);

inline Real max_component(Vec3 v) { return max_num(v.x, max_num(v.y, v.z)); }
inline Real max_abs(Vec3 v) { return max_num(std::fabs(v.x), max_num(std::fabs(v.y), std::fabs(v.z))); }

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

    // Ambient + Blinn-Phong diffuse and specular from every unshadowed point light.
    // `n` is the outward shading normal, also for surfaces hit from behind. `rec`: the
    // recorded tree's node, or null (renders).
    Vec3 local(const Material& m, Vec3 p, Vec3 n, Vec3 to_eye, RayTrace* rec) const {
        const SceneSetup& setup = s.setup;
        Vec3 c = m.ambient * setup.ambient_light;
        if (rec) rec->ambient = c;
        for (size_t li = 0; li < setup.lights.size(); ++li) {
            const PointLight& light = setup.lights[li];
            const Vec3 to_light = light.position - p;
            const Real d2 = dot(to_light, to_light);
            const Vec3 l = to_light / std::sqrt(d2);
            const Real ndotl = dot(n, l);
            LightTrace* lt = nullptr;
            if (rec) {
                lt = &rec->lights.emplace_back();
                lt->light = li;
                lt->ndotl = ndotl;
            }
            // Nothing to add: diffuse is max(0, n.l) and the specular term is
            // dropped when n.l <= 0 (reference-conventions.md, "Shading"). n.l
            // within the rounding error of p counts as 0: a light lying in the
            // surface's plane would otherwise switch the specular term on and off
            // from pixel to pixel (its irradiance is huge that close).
            const Real noise =
                8 * std::numeric_limits<Real>::epsilon() * (max_abs(p) + max_abs(light.position)) / std::sqrt(d2);
            if (!(ndotl > noise)) continue;
            if (lt) lt->facing = true;
            // Shadow ray from p + n * ShadowRayEpsilon (spec 3), never culled. It
            // stops eps short of the light, so a light lying on a surface is not
            // hidden by that surface at random. It starts at t = 0: the references
            // count occluders right at the offset origin (ignoring those within eps,
            // tower_smooth goes from 16 to 461 pixels off).
            const Real eps = setup.shadow_ray_epsilon;
            const Vec3 so = p + n * eps;
            const Vec3 so_to_light = light.position - so;
            const Real dist = length(so_to_light);
            uint32_t* hint = cache ? &cache->last_occluder[li] : nullptr;
            if (dist > 2 * eps) {  // a light within 2 eps of the point is never occluded
                ++rays.shadow;
                if (lt) {
                    lt->shadow_traced = true;
                    lt->shadow = Ray{so, so_to_light / dist};
                    lt->shadow_tmax = dist - eps;
                }
                if (any_hit(s, Ray{so, so_to_light / dist}, 0, dist - eps, hint)) {
                    if (lt) {
                        lt->shadowed = true;
                        lt->occluder_found =
                            nearest_occluder(lt->shadow, lt->shadow_tmax, lt->occluder, lt->occluder_t);
                    }
                    continue;
                }
            }
            const Vec3 e = light.intensity / d2;  // irradiance E = I / d^2 (spec 2.8)
            const Vec3 h = normalize(l + to_eye);
            const Real ndoth = max_num(Real(0), dot(n, h));
            const Real lobe = phong_pow(ndoth, m.phong_exponent);
            const Vec3 added = (m.diffuse * ndotl + m.specular * lobe) * e;
            c += added;
            if (lt) {
                lt->irradiance = e;
                lt->ndoth = ndoth;
                lt->diffuse = m.diffuse * ndotl * e;
                lt->specular = m.specular * lobe * e;
                lt->added = added;
            }
        }
        if (rec) rec->local = c;
        return c;
    }

    // `medium` is the dielectric material the ray travels inside, or kNoMedium. It is
    // decided by the interface that spawned the ray alone, as the references do
    // (docs/conventions.md, "Inside a dielectric"): a ray refracted into a dielectric
    // or reflected off the inside of its surface is inside it; every other ray,
    // including a mirror's or conductor's reflection met inside the glass, is not.
    // `weight` is what this ray's radiance is multiplied by in the pixel. `rec`: this
    // ray's node of the recorded tree (its kind, factor and weight set), or null (renders).
    Vec3 trace(const Ray& ray, int depth, int medium, bool primary, Real weight, RayTrace* rec) const {
        Hit h;
        const bool cull = cull_of(medium);
        const bool hit = closest_hit(s, ray, 0, HUGE_VAL, cull, h);
        if (rec) record_ray(*rec, ray, depth, medium, cull, hit, h);
        return hit ? shade(ray, h, depth, medium, weight, rec) : missed(primary, rec);
    }

    // The radiance of a ray that hits nothing.
    Vec3 missed(bool primary, RayTrace* rec) const {
        const Vec3 miss = primary ? s.setup.background : Vec3{};  // spec 3, BackgroundColor
        if (rec) rec->radiance = miss;
        return miss;
    }

    // The radiance of a ray (as trace()) that hits h.
    Vec3 shade(const Ray& ray, const Hit& h, int depth, int medium, Real weight, RayTrace* rec) const {
        const Vec3 p = ray.org + ray.dir * h.t;
        const Surface surf = s.geometry.surface(h, p);
        const Vec3 ng = surf.ng, ns = surf.ns;
        const uint32_t mat_id = surf.material;
        const Material& m = s.setup.materials[mat_id];
        const bool front = dot(ray.dir, ng) < 0;
        const Vec3 nf = front ? ns : -ns;  // shading normal facing the incoming ray
        if (rec) {
            rec->point = p;
            rec->ng = ng;
            rec->ns = ns;
            rec->front = front;
            rec->material = mat_id;
        }

        Vec3 color;
        // Dielectrics are shaded only when hit from outside (reference-conventions.md).
        if (m.type != MaterialType::Dielectric || front) {
            color = local(m, p, ns, -ray.dir, rec);
            if (rec) rec->shaded = true;
        }

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
            const Real eps = s.setup.shadow_ray_epsilon;
            const Real cos_i = -dot(ray.dir, nf);
            // The reflected ray, spawned on the side the incoming ray came from.
            auto reflected = [&] { return spawn_ray(p, nf, eps, normalize(ray.dir + nf * (2 * cos_i))); };
            // Adds factor * L(r) unless the ray's weight is negligible (kMinWeight).
            auto secondary = [&](Vec3 factor, const Ray& r, int r_medium, RayKind kind) {
                const Real w = weight * max_component(beer) * max_component(factor);
                RayTrace* child = nullptr;
                if (rec) {
                    child = &rec->children.emplace_back();
                    child->kind = kind;
                    child->depth = depth + 1;
                    child->ray = r;
                    child->factor = factor;
                    child->weight = w;
                    child->pruned = !(w >= kMinWeight);
                }
                if (!(w >= kMinWeight)) return;
                ++(kind == RayKind::Refraction ? rays.refraction : rays.reflection);
                color += factor * trace(r, depth + 1, r_medium, false, w, child);
            };
            switch (m.type) {
                case MaterialType::Plain:
                    // No secondary rays: MirrorReflectance on a material without _type is
                    // ignored (reference-conventions.md, "Shading"; the akif_uslu scenes carry it).
                    break;
                case MaterialType::Mirror:
                    secondary(m.mirror, reflected(), kNoMedium, RayKind::Reflection);
                    break;
                case MaterialType::Conductor: {
                    const Real fr = fresnel_conductor(cos_i, m.refraction_index, m.absorption_index);
                    if (rec) {
                        rec->has_fresnel = true;
                        rec->fresnel = fr;
                    }
                    secondary(m.mirror * fr, reflected(), kNoMedium, RayKind::Reflection);
                    break;
                }
                case MaterialType::Dielectric: {
                    const int self = static_cast<int>(mat_id);
                    const Real eta_i = front ? Real(1) : m.refraction_index;
                    const Real eta_t = front ? m.refraction_index : Real(1);
                    Real cos_t = 0;
                    const Real fr = fresnel_dielectric(cos_i, eta_i, eta_t, &cos_t);
                    // Inside this dielectric: the ray reflected off its inside, or refracted in.
                    const int refl_medium = front ? kNoMedium : self;
                    const int refr_medium = front ? self : kNoMedium;
                    if (rec) {
                        rec->has_fresnel = true;
                        rec->fresnel = fr;
                        rec->tir = !(fr < 1) && eta_i > eta_t;
                    }
                    secondary(m.mirror * fr, reflected(), refl_medium, RayKind::Reflection);
                    if (fr < 1) {
                        const Real eta = eta_i / eta_t;
                        const Vec3 t_dir = normalize(ray.dir * eta + nf * (eta * cos_i - cos_t));
                        if (rec) {
                            rec->refracts = true;
                            rec->refracted = t_dir;
                        }
                        secondary(Vec3{1, 1, 1} * (1 - fr), spawn_ray(p, -nf, eps, t_dir), refr_medium,
                                  RayKind::Refraction);
                    }
                    break;
                }
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

Vec3 trace_primary(const Scene& scene, const Ray& ray, const TraceOptions& options, TraceCache* cache,
                   RayTrace* record) {
    RayCounts unused;
    const Integrator it = camera_integrator(scene, options, cache, unused);
    ++it.rays.camera;
    if (record) {
        record->kind = RayKind::Camera;
        record->weight = 1;
    }
    return it.trace(ray, 0, kNoMedium, true, 1, record);
}

void trace_primaries(const Scene& scene, const Ray* rays, int n, const TraceOptions& options, TraceCache* cache,
                     Vec3* radiance) {
    RayCounts unused;
    const Integrator it = camera_integrator(scene, options, cache, unused);
    it.rays.camera += static_cast<uint64_t>(n);
    Hit hits[kPacket];
    bool found[kPacket];
    closest_hits(scene, rays, n, 0, HUGE_VAL, it.cull_of(kNoMedium), hits, found);
    for (int i = 0; i < n; ++i)
        if (found[i]) scene.geometry.prefetch_surface(hits[i]);
    for (int i = 0; i < n; ++i)
        radiance[i] = found[i] ? it.shade(rays[i], hits[i], 0, kNoMedium, 1, nullptr) : it.missed(true, nullptr);
}

}  // namespace rt
