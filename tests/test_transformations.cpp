// Transformations and mesh instances (docs/transformations.md): the matrices by hand,
// the loader's composition order and instance resolution, its errors, and the
// two-level traversal against the same mesh moved once (the ray tests must agree).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

#include "loader_test_support.h"
#include "rt/core/affine.h"
#include "rt/core/error.h"
#include "rt/geometry/traverse.h"
#include "rt/loader/load_scene.h"
#include "rt/scene_build/build_scene.h"

namespace {

using namespace loader_test;
using rt::Affine;
using rt::Real;
using rt::Vec3;

const double kTol = 1e3 * double(std::numeric_limits<Real>::epsilon());

void expect_near(Vec3 a, Vec3 b, double tol = kTol) {
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(double(a[i]), double(b[i]), tol) << "coordinate " << i;
}

TEST(Affine, MatricesByHand) {
    expect_near(Affine::translation(1, 2, 3).point({1, 1, 1}), {2, 3, 4});
    expect_near(Affine::translation(1, 2, 3).vector({1, 1, 1}), {1, 1, 1});
    expect_near(Affine::scaling(2, -1, 3).point({1, 1, 1}), {2, -1, 3});
    // 90 degrees about +z takes +x to +y (counter-clockwise seen from the axis' tip).
    expect_near(Affine::rotation(90, 0, 0, 1).point({1, 0, 0}), {0, 1, 0});
    expect_near(Affine::rotation(90, 0, 0, 5).point({0, 1, 0}), {-1, 0, 0});  // axis length does not matter
    expect_near(Affine::rotation(90, 1, 0, 0).point({0, 1, 0}), {0, 0, 1});
    expect_near(Affine::rotation(120, 1, 1, 1).point({1, 0, 0}), {0, 1, 0});
    // a * b applies b first.
    const Affine ts = Affine::translation(1, 0, 0) * Affine::scaling(2, 2, 2);
    expect_near(ts.point({1, 1, 1}), {3, 2, 2});
    EXPECT_DOUBLE_EQ(Affine::scaling(2, -1, 3).det(), -6);
    const Affine m = Affine::translation(1, -2, 3) * Affine::rotation(33, 1, 2, 3) * Affine::scaling(2, 0.5, -3);
    expect_near((m * m.inverse()).point({0.3, -0.7, 1.1}), {0.3, -0.7, 1.1});
    EXPECT_TRUE((Affine{}).is_identity());
    EXPECT_FALSE(m.is_identity());
    // Normals by the inverse transpose stay perpendicular to moved tangents.
    const Vec3 n{0, 0, 1}, tangent{1, 2, 0};
    EXPECT_NEAR(double(rt::dot(m.inverse().transposed_vector(n), m.vector(tangent))), 0, kTol);
}

// The sample scene with a Transformations section and `objects` as its Objects.
json scene_with(const json& objects, const json& transformations) {
    json j = sample();
    j["Scene"]["Transformations"] = transformations;
    j["Scene"]["Objects"] = objects;
    return j;
}

const json kTransforms = json::parse(R"({
    "Translation": [{"_id": "1", "_data": "1 0 0"}, {"_id": "2", "_data": "0 0 -5"}],
    "Scaling": {"_id": "1", "_data": "2 2 2"},
    "Rotation": {"_id": "1", "_data": "90 0 0 1"},
    "Composite": {"_id": "1", "_data": "1 0 0 0 0 1 0 7 0 0 1 0 0 0 0 1"}})");

TEST(TransformationsLoader, AppliedInTheOrderWritten) {
    // VertexData 8 is (0 -0.5 0): s1 then t1 gives (1, -1, 0); t1 then s1 gives (2, -1, 0).
    json j = scene_with(json::parse(R"({"Sphere": [
        {"_id": "1", "Material": "1", "Center": "9", "Radius": "1", "Transformations": "s1 t1"},
        {"_id": "2", "Material": "1", "Center": "9", "Radius": "1", "Transformations": "t1 s1"},
        {"_id": "3", "Material": "1", "Center": "9", "Radius": "1", "Transformations": "r1 c1"}]})"),
                        kTransforms);
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.all<rt::SphereDesc>().size(), 3u);
    expect_near(d.all<rt::SphereDesc>()[0].transform.point({0, -0.5, 0}), {1, -1, 0});
    expect_near(d.all<rt::SphereDesc>()[1].transform.point({0, -0.5, 0}), {2, -1, 0});
    // r1 takes (0, -0.5, 0) to (0.5, 0, 0); c1 adds 7 to y.
    expect_near(d.all<rt::SphereDesc>()[2].transform.point({0, -0.5, 0}), {0.5, 7, 0});
}

TEST(TransformationsLoader, LightsCamerasPlanesAndMeshes) {
    json j = scene_with(json::parse(R"({
        "Mesh": {"_id": "1", "Material": "1", "Transformations": "t2",
                 "Faces": {"_data": "1 2 3", "_type": "triangle"}},
        "Plane": {"_id": "1", "Material": "1", "Point": "9", "Normal": "1 0 0", "Transformations": "r1 t1"}})"),
                        kTransforms);
    j["Scene"]["Lights"]["PointLight"]["Transformations"] = "t1 t1";
    j["Scene"]["Cameras"]["Camera"]["Transformations"] = "r1 t2";
    const rt::SceneDesc d = parse(j.dump());
    expect_near(d.point_lights[0].position, {2, 0, 0});
    expect_near(d.cameras[0].position, {0, 0, -5});
    expect_near(d.cameras[0].gaze, {0, 0, -1});  // about the gaze: unchanged, and not translated
    expect_near(d.cameras[0].up, {-1, 0, 0});
    expect_near(d.meshes[0].transform.point(d.meshes[0].positions[0]), {-0.5, 0.5, -7});
    const rt::PlaneDesc& p = d.all<rt::PlaneDesc>()[0];
    expect_near(p.point, {1.5, 0, 0});
    expect_near(p.normal, {0, 1, 0});
}

TEST(TransformationsLoader, InstancesResolveTheirBase) {
    json j = scene_with(json::parse(R"({
        "Mesh": {"_id": "4", "Material": "1", "Transformations": "t1",
                 "Faces": {"_data": "1 2 3", "_type": "triangle"}},
        "MeshInstance": [
            {"_id": "6", "_baseMeshId": "5", "Transformations": "t1"},
            {"_id": "5", "_baseMeshId": "4", "Transformations": "t2"},
            {"_id": "7", "_baseMeshId": "6", "_resetTransform": "true", "Transformations": "s1"}]})"),
                        kTransforms);
    const rt::SceneDesc d = parse(j.dump());
    ASSERT_EQ(d.meshes.size(), 1u);
    EXPECT_TRUE(d.meshes[0].instanced);
    const auto& inst = d.all<rt::InstanceDesc>();
    ASSERT_EQ(inst.size(), 4u);  // the mesh itself first, then the three in file order
    EXPECT_STREQ(inst[0].key, "Mesh");
    EXPECT_EQ(inst[0].id, "4");
    expect_near(inst[0].transform.point({0, 0, 0}), {1, 0, 0});
    expect_near(inst[1].transform.point({0, 0, 0}), {2, 0, -5});  // t1 (mesh), t2 (5), t1 (6)
    expect_near(inst[2].transform.point({0, 0, 0}), {1, 0, -5});  // t1 (mesh), t2
    expect_near(inst[3].transform.point({1, 1, 1}), {2, 2, 2});   // reset: s1 alone
    for (const rt::InstanceDesc& i : inst) {
        EXPECT_EQ(i.mesh, 0u);
        EXPECT_EQ(i.material, 0u);
    }
}

TEST(TransformationsLoader, Errors) {
    const json sphere = json::parse(R"({"Sphere": {"_id": "1", "Material": "1", "Center": "9", "Radius": "1"}})");
    auto expect_error = [](const json& j, const std::string& pointer, const std::string& also) {
        try {
            parse(j.dump());
            ADD_FAILURE() << "no error; expected one at " << pointer;
        } catch (const rt::InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(kPath + ": " + pointer + ": ", 0), 0u) << msg;
            EXPECT_NE(msg.find(also), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    };
    auto with_ref = [&](const std::string& ref) {
        json j = scene_with(sphere, kTransforms);
        j["Scene"]["Objects"]["Sphere"]["Transformations"] = ref;
        return j;
    };
    const std::string sp = "/Scene/Objects/Sphere/Transformations";
    expect_error(with_ref("t1 t9"), sp, "transformation 't9' does not exist");
    expect_error(with_ref("s2"), sp, "no Scaling with _id 2");
    expect_error(with_ref("q1"), sp, "'q1' is not a transformation reference");
    expect_error(with_ref("t"), sp, "'t' is not a transformation reference");

    auto with_transform = [&](const char* kind, const std::string& data) {
        json t;
        t[kind] = {{"_id", "1"}, {"_data", data}};
        return scene_with(sphere, t);
    };
    expect_error(with_transform("Scaling", "1 0 1"), "/Scene/Transformations/Scaling/_data", "zero");
    expect_error(with_transform("Rotation", "30 0 0 0"), "/Scene/Transformations/Rotation/_data", "zero vector");
    expect_error(with_transform("Rotation", "30 0 1"), "/Scene/Transformations/Rotation/_data", "expected 4 numbers");
    expect_error(with_transform("Composite", "1 0 0 0 0 1 0 0 0 0 1 0 1 0 0 1"),
                 "/Scene/Transformations/Composite/_data", "last row");
    expect_error(with_transform("Composite", "1 0 0 0 0 1 0 0 0 0 0 0 0 0 0 1"),
                 "/Scene/Transformations/Composite/_data", "singular");
    json dup = scene_with(sphere, json::parse(R"({"Translation": [{"_id": "1", "_data": "1 0 0"},
                                                                   {"_id": "1", "_data": "2 0 0"}]})"));
    expect_error(dup, "/Scene/Transformations/Translation/1/_id", "duplicate Translation id 1");

    auto with_instances = [&](const std::string& instances) {
        json o = json::parse(R"({"Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3"}}})");
        o["MeshInstance"] = json::parse(instances);
        return scene_with(o, kTransforms);
    };
    const std::string ip = "/Scene/Objects/MeshInstance";
    expect_error(with_instances(R"({"_id": "2", "_baseMeshId": "9"})"), ip + "/_baseMeshId",
                 "no Mesh or MeshInstance has _id 9");
    expect_error(with_instances(R"({"_id": "2"})"), ip + "/_baseMeshId", "required key is missing");
    expect_error(with_instances(R"([{"_id": "2", "_baseMeshId": "3"}, {"_id": "3", "_baseMeshId": "2"}])"),
                 ip + "/0/_baseMeshId", "cycle");
    expect_error(with_instances(R"({"_id": "2", "_baseMeshId": "1", "_resetTransform": "yes"})"),
                 ip + "/_resetTransform", "expected true or false");
    expect_error(with_instances(R"([{"_id": "1", "_baseMeshId": "1"}, {"_id": "3", "_baseMeshId": "1"}])"),
                 ip + "/0/_baseMeshId", "more than one Mesh or MeshInstance has _id 1");
    expect_error(with_instances(R"({"_id": "2", "_baseMeshId": "1", "Material": "8"})"), ip + "/Material",
                 "material id 8 does not exist");
}

// A random smooth-ish mesh about the origin: a bumpy closed sphere of triangles.
rt::MeshDesc bumpy_mesh(std::mt19937& rng) {
    std::uniform_real_distribution<double> u(0.8, 1.2);
    rt::MeshDesc m;
    const int rings = 8, segs = 12;
    for (int r = 0; r <= rings; ++r)
        for (int s = 0; s < segs; ++s) {
            const double th = M_PI * r / rings, ph = 2 * M_PI * s / segs, k = u(rng);
            m.positions.push_back(
                {Real(k * std::sin(th) * std::cos(ph)), Real(k * std::cos(th)), Real(k * std::sin(th) * std::sin(ph))});
        }
    auto at = [&](int r, int s) { return uint32_t(r * segs + (s % segs)); };
    for (int r = 0; r < rings; ++r)
        for (int s = 0; s < segs; ++s) {
            m.indices.insert(m.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
            m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
        }
    return m;
}

// The same mesh drawn by an instance (two levels, the ray moved) and moved once into the
// world by hand (one level, the mesh moved): the same hits to rounding, the same faces, the
// same outward normals and the same culling, under random rotations, non-uniform and
// mirroring scalings and translations.
TEST(TransformationsInstances, TwoLevelsEqualTheMeshMovedOnce) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1), s(0.4, 2);
    int hits = 0, compared = 0;
    for (int trial = 0; trial < 40; ++trial) {
        const Affine m = Affine::translation(3 * u(rng), 3 * u(rng), 3 * u(rng)) *
                         Affine::rotation(180 * u(rng), u(rng), u(rng), u(rng) + 1.5) *
                         Affine::scaling((trial % 2 ? -1 : 1) * s(rng), s(rng), s(rng));
        const rt::MeshDesc mesh = bumpy_mesh(rng);
        // The mesh moved once, by hand: its vertices by m, and where m mirrors each
        // face's winding reversed, so that counter-clockwise stays the outside.
        rt::SceneDesc baked, instanced;
        baked.meshes.push_back(mesh);
        for (Vec3& p : baked.meshes[0].positions) p = m.point(p);
        if (m.det() < 0)
            for (size_t f = 0; f + 2 < mesh.indices.size(); f += 3)
                std::swap(baked.meshes[0].indices[f + 1], baked.meshes[0].indices[f + 2]);
        instanced.meshes.push_back(mesh);
        instanced.meshes[0].instanced = true;
        rt::InstanceDesc inst;
        inst.mesh = 0;
        inst.transform = m;
        instanced.all<rt::InstanceDesc>().push_back(inst);
        const rt::Scene a = rt::build_scene(baked), b = rt::build_scene(instanced);
        ASSERT_EQ(b.geometry.all<rt::Instance>().size(), 1u);
        for (int i = 0; i < 500; ++i) {
            const Vec3 org = m.point({Real(4 * u(rng)), Real(4 * u(rng)), Real(4 * u(rng))});
            const Vec3 target = m.point({Real(0.7 * u(rng)), Real(0.7 * u(rng)), Real(0.7 * u(rng))});
            const rt::Ray ray{org, rt::normalize(target - org)};
            for (bool cull : {false, true}) {
                rt::Hit ha, hb;
                const bool fa = rt::closest_hit(a, ray, 0, HUGE_VAL, cull, ha);
                const bool fb = rt::closest_hit(b, ray, 0, HUGE_VAL, cull, hb);
                ++compared;
                ASSERT_EQ(fa, fb) << "trial " << trial << " ray " << i << " cull " << cull;
                EXPECT_EQ(rt::any_hit(a, ray, 0, HUGE_VAL), rt::any_hit(b, ray, 0, HUGE_VAL));
                if (!fa) continue;
                ++hits;
                EXPECT_NEAR(double(ha.t), double(hb.t), 1e-9 * std::max(1.0, double(ha.t)) + kTol);
                ASSERT_EQ(hb.kind, rt::ShapeKind::Instance);
                EXPECT_EQ(ha.index, hb.part) << "the same face";
                const Vec3 p = ray.org + ray.dir * ha.t;
                const rt::Surface sa = a.geometry.surface(ha, p), sb = b.geometry.surface(hb, p);
                // The moved-once mesh's vertices are rounded to Real after the move, so
                // its normal is as precise as Real: 1e-6, or kTol where that is coarser (float).
                expect_near(sa.ng, sb.ng, std::max(1e-6, kTol));
            }
        }
    }
    EXPECT_GT(hits, 5000) << "of " << compared;
}

}  // namespace
