// The registries of shapes (rt/shapes/shapes.h) and materials (rt/materials/materials.h):
// properties every kind of the lists must have, checked kind by kind, so that a new
// kind is held to them without a test of its own for each:
//   - every material kind's _type word loads as that kind; the words and names are
//     distinct, and exactly one kind (the default) has no word;
//   - every material kind's secondary rays start ShadowRayEpsilon off the surface on
//     the side they leave from, have unit directions, and carry factors within [0, 1]
//     that sum to at most 1 per channel (no energy is made);
//   - every shape kind's hits lie within its bounds (bounded kinds) and have unit
//     normals with the shading normal on the geometric normal's side; keys are distinct.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>

#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/materials/materials.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shapes/shapes.h"

namespace {

using rt::Real;
using rt::Vec3;

const double kTol = 64 * double(std::numeric_limits<Real>::epsilon());

std::string scene_with_material(const std::string& material) {
    return R"({"Scene": {"Cameras": {"Camera": {"Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "4 4", "ImageName": "r.png"}},
        "Materials": {"Material": )" +
           material + R"(}, "VertexData": "0 0 -5 1 0 -5 0 1 -5",
        "Objects": {"Triangle": {"Material": "1", "Indices": "1 2 3"}}}})";
}

TEST(MaterialRegistry, EveryTypeWordLoadsAsItsKind) {
    std::set<std::string> names, words;
    int without_word = 0;
    rt::for_each_material_format([&](auto k) {
        using M = decltype(k);
        EXPECT_TRUE(names.insert(M::kName).second) << M::kName;
        if (!M::kTypeWord) {
            ++without_word;
            const rt::SceneDesc d =
                rt::parse_scene(scene_with_material(R"({"DiffuseReflectance": "1 1 1"})"), "m.json");
            EXPECT_EQ(d.materials.at(0).type, rt::material_type_of_format<M>) << M::kName;
            return;
        }
        EXPECT_TRUE(words.insert(M::kTypeWord).second) << M::kTypeWord;
        // Every key any kind reads, with a valid value: the kind reads those it needs.
        const std::string m = std::string(R"({"_type": ")") + M::kTypeWord +
                              R"(", "MirrorReflectance": "0.5 0.5 0.5", "RefractionIndex": "1.5",
                                    "AbsorptionIndex": "2", "AbsorptionCoefficient": "0.1 0.1 0.1"})";
        const rt::SceneDesc d = rt::parse_scene(scene_with_material(m), "m.json");
        EXPECT_EQ(d.materials.at(0).type, rt::material_type_of_format<M>) << M::kTypeWord;
        EXPECT_STREQ(rt::material_type_name(d.materials.at(0).type), M::kName);
    });
    EXPECT_EQ(without_word, 1);
    EXPECT_EQ(names.size(), rt::kMaterialTypeCount);
    try {
        rt::parse_scene(scene_with_material(R"({"_type": "velvet"})"), "m.json");
        ADD_FAILURE() << "an unknown _type loaded";
    } catch (const rt::InputError& e) {
        for (const std::string& w : words) EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
    }
}

TEST(MaterialRegistry, SecondaryRaysLeaveTheSurfaceAndMakeNoEnergy) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    rt::for_each_material([&](auto k) {
        using M = decltype(k);
        for (int i = 0; i < 2000; ++i) {
            rt::Material m;
            m.type = rt::material_type_of<M>;
            m.mirror = {Real(u(rng)), Real(u(rng)), Real(u(rng))};
            m.refraction_index = Real(0.2 + 3 * u(rng));
            m.absorption_index = Real(4 * u(rng));
            // A unit normal facing the ray, and a ray arriving at any angle.
            const Vec3 nf{0, 0, 1};
            const Real cos_i = Real(u(rng));
            const Real sin_i = std::sqrt(1 - cos_i * cos_i);
            const rt::Ray ray{{-sin_i, 0, cos_i}, {sin_i, 0, -cos_i}};
            const rt::ScatterIn in{ray, {0, 0, 0}, nf, u(rng) < 0.5, cos_i, Real(1e-3), 0};
            rt::ScatterOut out;
            M::scatter(m, in, out);
            Vec3 sum{0, 0, 0};
            for (int r = 0; r < out.n; ++r) {
                const rt::ScatterOut::Secondary& s = out.rays[r];
                for (Real c : {s.factor.x, s.factor.y, s.factor.z}) {
                    EXPECT_GE(c, 0) << M::Format::kName;
                    EXPECT_LE(c, 1) << M::Format::kName;
                }
                sum = sum + s.factor;
                EXPECT_NEAR(rt::length(s.ray.dir), 1, kTol) << M::Format::kName;
                // Reflections leave on the facing side, refractions on the other.
                const Real side = s.kind == rt::RayKind::Refraction ? -1 : 1;
                EXPECT_NEAR(double(s.ray.org.z), side * 1e-3, kTol) << M::Format::kName;
                EXPECT_GE(side * s.ray.dir.z, 0) << M::Format::kName;
            }
            for (Real c : {sum.x, sum.y, sum.z}) EXPECT_LE(c, 1 + kTol) << M::Format::kName;
        }
    });
}

// A random affine map: a rotation, a non-uniform scaling (mirroring at times) and a
// translation, so that kinds are tested moved as Transformations move them.
rt::Affine random_transform(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1), s(0.3, 2);
    const double sign = u(rng) < 0 ? -1 : 1;
    return rt::Affine::translation(u(rng), u(rng), u(rng)) * rt::Affine::rotation(180 * u(rng), u(rng), u(rng), 1) *
           rt::Affine::scaling(sign * s(rng), s(rng), s(rng));
}

// A shape of kind S for the property test: the scene format's fields, random, moved by
// a random transformation half of the time. Instances show a tetrahedron of `in`.
template <class S>
typename S::Desc random_desc(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(-1, 1);
    const auto vec = [&] { return Vec3{Real(u(rng)), Real(u(rng)), Real(u(rng))}; };
    typename S::Desc d;
    if constexpr (S::Desc::kReadAsShape) {
        struct Reader {
            decltype(vec)& v;
            std::mt19937& rng;
            Vec3 vertex(const char*) const { return v(); }
            Real positive(const char*) const { return Real(0.1 + std::uniform_real_distribution<double>(0, 1)(rng)); }
            Vec3 nonzero_vec3(const char*) const {
                for (;;)
                    if (const Vec3 n = v(); rt::length(n) > Real(0.1)) return n;
            }
        } r{vec, rng};
        S::Desc::read(r, d);
    }
    if (u(rng) < 0) S::Desc::apply_transform(d, random_transform(rng));
    return d;
}

// The meshes random_desc's instances show: mesh 0, a tetrahedron about the origin.
rt::BuildInputs tetrahedron_inputs() {
    rt::SceneDesc d;
    rt::MeshDesc m;
    m.positions = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
    m.indices = {0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2};
    d.meshes.push_back(m);
    rt::BuildInputs in;
    in.mesh_scenes.push_back(std::make_shared<rt::Scene>(rt::build_scene(std::move(d))));
    return in;
}

TEST(ShapeRegistry, HitsLieInTheBoundsWithUnitNormals) {
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(-1, 1);
    std::set<std::string> keys;
    const rt::BuildInputs inputs = tetrahedron_inputs();
    rt::for_each_shape([&](auto k) {
        using S = decltype(k);
        EXPECT_TRUE(keys.insert(S::Desc::kKey).second) << S::Desc::kKey;
        EXPECT_STREQ(rt::shape_key(rt::kind_of<S>), S::Desc::kKey);
        int hits = 0;
        for (int i = 0; i < 2000; ++i) {
            const S shape = S::build(random_desc<S>(rng), inputs);
            const Vec3 org{Real(3 * u(rng)), Real(3 * u(rng)), Real(3 * u(rng))};
            const Vec3 target{Real(u(rng)), Real(u(rng)), Real(u(rng))};
            const rt::Ray ray{org, rt::normalize(target - org)};
            Real t, w[3] = {0, 0, 0};
            uint32_t part = 0;
            if (!shape.template intersect<false, false>(ray, 0, HUGE_VAL, t, w, part)) continue;
            ++hits;
            const Vec3 p = ray.org + ray.dir * t;
            if constexpr (S::kBounded) {
                const rt::Box b = shape.bounds();
                for (int a = 0; a < 3; ++a) {
                    EXPECT_GE(double(p[a]), double(b.lo[a]) - kTol) << S::Desc::kKey;
                    EXPECT_LE(double(p[a]), double(b.hi[a]) + kTol) << S::Desc::kKey;
                }
            }
            const rt::Surface s = shape.surface(p, w, part);
            EXPECT_NEAR(rt::length(s.ng), 1, kTol) << S::Desc::kKey;
            EXPECT_NEAR(rt::length(s.ns), 1, kTol) << S::Desc::kKey;
            EXPECT_GE(rt::dot(s.ng, s.ns), 0) << S::Desc::kKey;
        }
        EXPECT_GT(hits, 100) << S::Desc::kKey << ": too few hits to test";
    });
    EXPECT_EQ(keys.size(), rt::kShapeKindCount - 1);
}

}  // namespace
