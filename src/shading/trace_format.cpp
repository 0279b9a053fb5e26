// A pixel's ray tree as indented text and as JSON, beside the tree itself (trace.cpp,
// rt/shading/trace.h; the format: docs/trace.md).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>

#include "rt/materials/materials.h"
#include "rt/shading/trace.h"

namespace rt {
namespace {

// The shortest decimal that reads back as the same T: a float's 0.37f is "0.37", not
// the "0.3700000048" of its double.
template <class T>
std::string shortest(T v) {
    char buf[40];
    for (int digits = std::numeric_limits<T>::digits10; digits <= std::numeric_limits<T>::max_digits10; ++digits) {
        std::snprintf(buf, sizeof buf, "%.*g", digits, double(v));
        if (T(std::strtod(buf, nullptr)) == v) break;
    }
    return buf;
}

// Text: in double, 10 significant digits, enough to see a channel just under an
// integer; in float, every digit the float has (at most 9).
std::string num(Real v) {
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    if constexpr (sizeof(Real) < sizeof(double)) return shortest(v);
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", double(v));
    return buf;
}

std::string vec(Vec3 v) { return "(" + num(v.x) + ", " + num(v.y) + ", " + num(v.z) + ")"; }

// The material's _id (its 1-based position for scenes built in code).
std::string material_id(const Scene& scene, size_t index) {
    const std::string& id = scene.setup.materials[index].id;
    return id.empty() ? std::to_string(index + 1) : id;
}

std::string light_name(size_t index) { return "light " + std::to_string(index + 1); }

// An instance's hit in its mesh's own space: the face as the scene file numbers it and
// the point there. False for other hits.
bool object_space(const Scene& scene, const RayTrace& r, std::string& face, Vec3& point) {
    if (r.shape.kind != ShapeKind::Instance) return false;
    const Instance& inst = scene.geometry.all<Instance>()[r.shape.index];
    face = inst.mesh->names.name({ShapeKind::Triangle, r.part});
    point = inst.to_object.point(r.point);
    return true;
}

// --- text ------------------------------------------------------------------------------

// Lines of text are at most this long (a terminal's width): longer ones are broken
// after a ", " or ": " outside parentheses and brackets, the rest indented under them.
constexpr size_t kTextWidth = 100;

class TextWriter {
public:
    TextWriter(const Scene& scene, const PixelTrace& trace) : scene_(scene), trace_(trace) {}

    void line(int indent, const std::string& text) {
        const std::string pad(size_t(indent) * 2, ' ');
        std::string rest = text;
        std::string lead = pad;
        while (lead.size() + rest.size() > kTextWidth) {
            // The last break that fits, else the first one there is.
            size_t cut = std::string::npos;
            int depth = 0;
            for (size_t i = 0; i + 1 < rest.size(); ++i) {
                depth += (rest[i] == '(' || rest[i] == '[') ? 1 : (rest[i] == ')' || rest[i] == ']') ? -1 : 0;
                if (depth == 0 && (rest[i] == ',' || rest[i] == ':') && rest[i + 1] == ' ') {
                    if (lead.size() + i + 1 > kTextWidth && cut != std::string::npos) break;
                    cut = i + 1;
                }
            }
            if (cut == std::string::npos) break;
            out_ += lead + rest.substr(0, cut) + "\n";
            rest = rest.substr(cut + 1);
            lead = pad + "    ";
        }
        out_ += lead + rest + "\n";
    }

    void ray(const RayTrace& r, int indent, bool child) {
        std::string head = std::string(ray_kind_name(r.kind)) + " ray, depth " + std::to_string(r.depth);
        if (child) head += ", weight " + num(r.weight) + ", factor " + vec(r.factor);
        if (r.pruned) {
            line(indent, head + ": not traced (weight below --min-weight " + shortest(trace_.min_weight) + ")");
            return;
        }
        line(indent, head);
        const int in = indent + 1;
        line(in, "origin " + vec(r.ray.org) + (scene_.geometry.moves ? ", time " + num(r.ray.time) : ""));
        line(in, "direction " + vec(r.ray.dir));
        if (r.perturbed) line(in + 1, "rough surface (Roughness): turned from the ideal direction " + vec(r.ideal));
        std::string search = "t in (" + num(r.tmin) + ", " + num(r.tmax) + ")";
        search += r.cull ? ", back faces culled" : ", no culling";
        if (r.medium >= 0) search += ", inside material " + material_id(scene_, size_t(r.medium));
        line(in, search);
        if (r.culled) line(in, "back face culled: " + scene_.names.name(r.culled_shape) + " at t = " + num(r.culled_t));
        if (!r.hit) {
            line(in, "miss");
            line(in, "returns " + vec(r.radiance));
            return;
        }
        const Material& m = scene_.setup.materials[r.material];
        line(in, "hit " + scene_.names.name(r.shape) + " at t = " + num(r.t) + ", point " + vec(r.point));
        std::string face;
        Vec3 object_point;
        if (object_space(scene_, r, face, object_point))
            line(in + 1, "in its mesh's own space: " + face + ", point " + vec(object_point));
        line(in, r.front ? "front face: the ray meets the side the outward normals point to"
                         : "back face: the ray meets the inside; the outward normals point away from it");
        line(in + 1, "geometric normal " + vec(r.ng) + ", outward");
        line(in + 1, "shading normal " + vec(r.ns) + ", outward: the lights use it");
        line(in + 1, "facing normal " + vec(r.nf) + ": the shading normal turned towards the ray");
        const Real eps = scene_.setup.shadow_ray_epsilon;
        if (r.shaded)
            line(in + 1, "shadow rays start at " + vec(r.point + r.ns * eps) + ", point + shading normal x eps");
        line(in + 1, "reflected rays start at " + vec(r.point + r.nf * eps) + ", point + facing normal x eps");
        if (refracts(m.type))
            line(in + 1, "refracted rays start at " + vec(r.point - r.nf * eps) + ", point - facing normal x eps");
        line(in, "material " + material_id(scene_, r.material) + " (" + material_type_name(m.type) + ")");
        if (r.shaded) {
            line(in, "ambient " + vec(r.ambient));
            for (const LightTrace& l : r.lights) light(l, in);
            line(in, "local (ambient + lights) " + vec(r.local));
        } else {
            line(in, std::string("not shaded (a ") + material_type_name(m.type) + " hit from inside)");
        }
        if (r.has_fresnel) fresnel(r, in);
        if (r.beer) line(in, "Beer's law over distance " + num(r.t) + ": attenuation " + vec(r.attenuation));
        if (r.depth_limit) line(in, "MaxRecursionDepth reached: no secondary rays");
        for (const RayTrace& c : r.children) ray(c, in, true);
        line(in, "returns " + vec(r.radiance));
    }

    // The Fresnel equations' terms (rt/materials/optics.h, FresnelTerms).
    void fresnel(const RayTrace& r, int indent) {
        const FresnelTerms& f = r.fresnel;
        switch (f.formula) {
            case FresnelFormula::Dielectric:
                line(indent, "Fresnel (dielectric): n1 " + num(f.eta_i) + " -> n2 " + num(f.eta_t) + ", cos theta_i " +
                                 num(f.cos_i) + ", sin^2 theta_t " + num(f.sin_t2) +
                                 (f.sin_t2 < 1 ? ", cos theta_t " + num(f.cos_t) : " (>= 1)"));
                break;
            case FresnelFormula::Conductor:
                line(indent, "Fresnel (conductor): n1 1 -> n2 " + num(f.eta_t) + " + " + num(f.k) + "i, cos theta_i " +
                                 num(f.cos_i));
                break;
        }
        line(indent + 1, "R parallel " + num(f.r_par) + ", R perpendicular " + num(f.r_perp) +
                             ", reflectance F = (R par + R perp) / 2 = " + num(f.reflectance));
        if (f.formula != FresnelFormula::Dielectric) return;
        line(indent + 1, "transmittance 1 - F = " + num(1 - f.reflectance));
        if (r.refracts)
            line(indent + 1, "refracted direction " + vec(r.refracted));
        else
            line(indent + 1, r.tir ? "total internal reflection: no refracted ray" : "no refracted ray");
    }

    void light(const LightTrace& l, int indent) {
        std::string s = light_name(l.light);
        if (scene_.setup.lights[l.light].kind == LightKind::Area)
            s += " (area): point drawn " + vec(l.from) + ", L A |cos| " + vec(l.scale);
        s += ": n.l = " + num(l.ndotl);
        if (!l.facing) {
            line(indent, s + ", faces away");
            return;
        }
        if (l.shadowed) {
            s += ", shadowed";
            if (l.occluder_found) s += " by " + scene_.names.name(l.occluder) + " at t = " + num(l.occluder_t);
        } else {
            s += ", lit, I/d^2 " + vec(l.irradiance) + ", diffuse " + vec(l.diffuse) + ", specular " + vec(l.specular) +
                 " (n.h = " + num(l.ndoth) + ")";
        }
        line(indent, s);
        if (l.shadow_traced)
            line(indent + 1, std::string(ray_kind_name(RayKind::Shadow)) + " ray: origin " + vec(l.shadow.org) +
                                 ", direction " + vec(l.shadow.dir) + ", t in (0, " + num(l.shadow_tmax) + ")");
        else
            line(indent + 1, "no shadow ray (the light is within 2 ShadowRayEpsilon)");
    }

    std::string take() { return std::move(out_); }

private:
    const Scene& scene_;
    const PixelTrace& trace_;
    std::string out_;
};

// --- JSON ------------------------------------------------------------------------------

// Numbers read back exactly (the shortest decimal of the precision's type); infinities
// as null.
std::string jnum(Real v) { return std::isfinite(v) ? shortest(v) : "null"; }

std::string jvec(Vec3 v) { return "[" + jnum(v.x) + ", " + jnum(v.y) + ", " + jnum(v.z) + "]"; }

std::string jstr(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            char buf[8];
            std::snprintf(buf, sizeof buf, "\\u%04x", unsigned(c));
            out += buf;
        } else {
            out += c;
        }
    }
    return out + "\"";
}

const char* jbool(bool b) { return b ? "true" : "false"; }

// A JSON object written field by field.
class Object {
public:
    Object& field(const std::string& key, const std::string& raw_value) {
        out_ += (out_.empty() ? "{" : ", ") + jstr(key) + ": " + raw_value;
        return *this;
    }
    std::string done() const { return out_.empty() ? "{}" : out_ + "}"; }

private:
    std::string out_;
};

std::string jshadow_ray(const Ray& r, Real tmax) {
    return Object()
        .field("kind", jstr(ray_kind_name(RayKind::Shadow)))
        .field("origin", jvec(r.org))
        .field("direction", jvec(r.dir))
        .field("tmin", "0")
        .field("tmax", jnum(tmax))
        .done();
}

// An instance's hit in its mesh's space, {"face", "point"}; null for other hits.
std::string object_space_json(const Scene& scene, const RayTrace& r) {
    std::string face;
    Vec3 point;
    if (!object_space(scene, r, face, point)) return "null";
    return Object().field("face", jstr(face)).field("point", jvec(point)).done();
}

std::string jshape(const Scene& scene, ShapeRef s, Real t) {
    return Object().field("object", jstr(scene.names.name(s))).field("t", jnum(t)).done();
}

std::string jlight(const Scene& scene, const LightTrace& l) {
    Object o;
    o.field("light", std::to_string(l.light + 1));
    if (scene.setup.lights[l.light].kind == LightKind::Area)
        o.field("area_point", jvec(l.from)).field("area_scale", jvec(l.scale));
    o.field("n_dot_l", jnum(l.ndotl)).field("facing", jbool(l.facing));
    if (!l.facing) return o.done();
    o.field("shadow_ray", l.shadow_traced ? jshadow_ray(l.shadow, l.shadow_tmax) : "null");
    o.field("shadowed", jbool(l.shadowed));
    o.field("occluder", l.shadowed && l.occluder_found ? jshape(scene, l.occluder, l.occluder_t) : "null");
    if (!l.shadowed) {
        o.field("irradiance", jvec(l.irradiance))
            .field("n_dot_h", jnum(l.ndoth))
            .field("diffuse", jvec(l.diffuse))
            .field("specular", jvec(l.specular))
            .field("added", jvec(l.added));
    }
    return o.done();
}

std::string jnode(const Scene& scene, const RayTrace& r) {
    Object o;
    o.field("kind", jstr(ray_kind_name(r.kind))).field("depth", std::to_string(r.depth));
    o.field("factor", jvec(r.factor)).field("weight", jnum(r.weight)).field("traced", jbool(!r.pruned));
    if (r.pruned) return o.done();
    o.field("origin", jvec(r.ray.org)).field("direction", jvec(r.ray.dir)).field("time", jnum(r.ray.time));
    o.field("ideal_direction", r.perturbed ? jvec(r.ideal) : "null");
    o.field("tmin", jnum(r.tmin)).field("tmax", jnum(r.tmax)).field("cull", jbool(r.cull));
    o.field("inside_material", r.medium >= 0 ? jstr(material_id(scene, size_t(r.medium))) : "null");
    o.field("culled", r.culled ? jshape(scene, r.culled_shape, r.culled_t) : "null");
    if (r.hit) {
        const Material& m = scene.setup.materials[r.material];
        o.field("hit", Object()
                           .field("object", jstr(scene.names.name(r.shape)))
                           .field("t", jnum(r.t))
                           .field("point", jvec(r.point))
                           .field("object_space", object_space_json(scene, r))
                           .field("geometric_normal", jvec(r.ng))
                           .field("shading_normal", jvec(r.ns))
                           .field("facing_normal", jvec(r.nf))
                           .field("front", jbool(r.front))
                           .field("material", Object()
                                                  .field("id", jstr(material_id(scene, r.material)))
                                                  .field("type", jstr(material_type_name(m.type)))
                                                  .done())
                           .done());
        o.field("shaded", jbool(r.shaded));
        if (r.shaded) {
            std::string lights;
            for (const LightTrace& l : r.lights) lights += (lights.empty() ? "" : ", ") + jlight(scene, l);
            o.field("ambient", jvec(r.ambient)).field("lights", "[" + lights + "]").field("local", jvec(r.local));
        }
        if (r.has_fresnel) {
            const FresnelTerms& t = r.fresnel;
            Object f;
            f.field("n1", jnum(t.eta_i)).field("n2", jnum(t.eta_t));
            if (t.formula == FresnelFormula::Conductor) f.field("k", jnum(t.k));
            f.field("cos_i", jnum(t.cos_i));
            if (t.formula == FresnelFormula::Dielectric)
                f.field("sin2_t", jnum(t.sin_t2)).field("cos_t", jnum(t.cos_t));
            f.field("r_parallel", jnum(t.r_par)).field("r_perpendicular", jnum(t.r_perp));
            f.field("reflectance", jnum(t.reflectance));
            if (t.formula == FresnelFormula::Dielectric)
                f.field("transmittance", jnum(1 - t.reflectance))
                    .field("refracted", r.refracts ? jvec(r.refracted) : "null")
                    .field("total_internal_reflection", jbool(r.tir));
            o.field("fresnel", f.done());
        }
        o.field("beer", r.beer ? Object().field("distance", jnum(r.t)).field("attenuation", jvec(r.attenuation)).done()
                               : "null");
        o.field("depth_limit", jbool(r.depth_limit));
    } else {
        o.field("hit", "null");
    }
    std::string children;
    for (const RayTrace& c : r.children) children += (children.empty() ? "" : ", ") + jnode(scene, c);
    o.field("children", "[" + children + "]");
    o.field("radiance", jvec(r.radiance));
    return o.done();
}

std::string rounding_name(Rounding r) { return r == Rounding::Nearest ? "nearest" : "truncate"; }

std::string pixel_text(const uint8_t p[3]) {
    return std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " + std::to_string(p[2]);
}

}  // namespace

std::string trace_text(const Scene& scene, const PixelTrace& t) {
    const Camera& cam = scene.setup.cameras.at(t.camera);
    TextWriter w(scene, t);
    w.line(0, "pixel x " + std::to_string(t.x) + ", y " + std::to_string(t.y) + " of camera " +
                  std::to_string(t.camera + 1) + " (" + cam.image_name + ", " + std::to_string(cam.width) + "x" +
                  std::to_string(cam.height) + ", " + kPrecisionName + "), MaxRecursionDepth " +
                  std::to_string(scene.setup.max_recursion_depth) + ", ShadowRayEpsilon " +
                  num(scene.setup.shadow_ray_epsilon));
    if (t.samples > 0) {
        w.line(0, "sample " + std::to_string(t.sample) + " of " + std::to_string(t.samples) + " (--sample, seed " +
                      std::to_string(t.seed) + ", sampler " + sampler_name(t.sampler) + "): at (" + num(t.dx) + ", " +
                      num(t.dy) + ") in the pixel from its top-left corner" +
                      (t.lens ? ", lens point (" + num(t.lx) + ", " + num(t.ly) + ") of the aperture" : "") +
                      (scene.geometry.moves ? ", time " + num(t.root.ray.time) : ""));
    }
    w.ray(t.root, 0, false);
    if (t.taken > 1)
        w.line(0, "this sample: " + vec(t.clamped) + " clamped, " + vec(t.root.radiance) + " before clamping");
    w.line(0, "pixel [" + pixel_text(t.pixel) + "] after rounding (" + rounding_name(t.rounding) + "), from " +
                  (t.taken > 1 ? "the mean of its " + std::to_string(t.taken) + " samples " + vec(t.mean) +
                                     " (clamped after averaging)"
                               : vec(t.clamped) + " clamped, " + vec(t.root.radiance) + " before clamping"));
    return w.take();
}

std::string trace_json(const Scene& scene, const PixelTrace& t) {
    const Camera& cam = scene.setup.cameras.at(t.camera);
    return Object()
               .field("scene", jstr(t.scene))
               .field("camera", std::to_string(t.camera + 1))
               .field("image", jstr(cam.image_name))
               .field("width", std::to_string(cam.width))
               .field("height", std::to_string(cam.height))
               .field("x", std::to_string(t.x))
               .field("y", std::to_string(t.y))
               .field("max_recursion_depth", std::to_string(scene.setup.max_recursion_depth))
               .field("shadow_ray_epsilon", jnum(scene.setup.shadow_ray_epsilon))
               .field("rounding", jstr(rounding_name(t.rounding)))
               .field("min_weight", shortest(t.min_weight))
               .field("precision", jstr(kPrecisionName))
               .field("pixel", "[" + pixel_text(t.pixel) + "]")
               .field("radiance", jvec(t.root.radiance))
               .field("clamped", jvec(t.clamped))
               .field("samples", std::to_string(t.samples))
               .field("sample", t.samples > 0
                                    ? Object()
                                          .field("index", std::to_string(t.sample))
                                          .field("seed", std::to_string(t.seed))
                                          .field("sampler", jstr(sampler_name(t.sampler)))
                                          .field("taken", std::to_string(t.taken))
                                          .field("pixel_offset", "[" + jnum(t.dx) + ", " + jnum(t.dy) + "]")
                                          .field("lens", t.lens ? "[" + jnum(t.lx) + ", " + jnum(t.ly) + "]" : "null")
                                          .field("time", jnum(t.root.ray.time))
                                          .field("mean", jvec(t.mean))
                                          .done()
                                    : "null")
               .field("ray", jnode(scene, t.root))
               .done() +
           "\n";
}

}  // namespace rt
