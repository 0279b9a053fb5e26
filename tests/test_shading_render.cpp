// Shading tests, end to end: the Whitted integrator through rt::render on tiny scenes
// written as JSON (parse_scene -> build_scene -> render): diffuse and specular shading,
// shadows, mirrors, conductors, culling, glass with Fresnel and Beer's law. Expected pixel
// values are worked out by hand in the comments; inputs are chosen so that the exact
// value is far from an integer boundary (or exactly representable), so truncation is
// unambiguous.
#include <gtest/gtest.h>

#include <array>
#include <string>

#include "rt/image/image.h"
#include "rt/loader/load_scene.h"
#include "rt/render/render.h"
#include "rt/scene_build/build_scene.h"
#include "rt/shading/shading.h"

namespace {

// --- end-to-end through rt::render -----------------------------------------------------

using Pixel = std::array<int, 3>;

// A camera at the origin looking down -z; `near` is the half-width of a square near plane
// at distance 1; `res` is "W H".
std::string camera(const std::string& res = "1 1", const std::string& near = "1") {
    return R"("Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
        "NearPlane": "-)" +
           near + " " + near + " -" + near + " " + near + R"(", "NearDistance": "1",
        "ImageResolution": ")" +
           res + R"(", "ImageName": "t.png"}})";
}

rt::Image render_json(const std::string& scene_body, const rt::RenderOptions& opt = {}) {
    const std::string text = "{\"Scene\": {" + scene_body + "}}";
    const rt::Scene s = rt::build_scene(rt::parse_scene(text, "/nonexistent/shading_test.json"));
    return rt::render(s, 0, opt);
}

Pixel px(const rt::Image& img, int i, int j) {
    const size_t o = (static_cast<size_t>(j) * img.width + i) * 3;
    return {img.rgb[o], img.rgb[o + 1], img.rgb[o + 2]};
}

rt::RenderOptions nearest() {
    rt::RenderOptions o;
    o.rounding = rt::Rounding::Nearest;
    return o;
}

rt::RenderOptions no_cull() {
    rt::RenderOptions o;
    o.trace.cull = false;
    return o;
}

// Plane z = -10 facing the camera (+z), material 1.
const std::string kFacingPlane = R"("VertexData": {"_data": "0 0 -10"},
    "Objects": {"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 1"}})";

TEST(ShadingRender, DiffusePlaneUnderPointLight) {
    // Camera ray hits (0,0,-10); the light at the origin is straight above it along the normal:
    //   d = 10, E = 1000 / 100 = 10, n.l = 1.
    //   ambient = ka * Ia = (0.125, 0.25, 0.375) * 40 = (5, 10, 15)
    //   diffuse = kd * E * n.l = (0.25, 0.625, 0.75) * 10 = (2.5, 6.25, 7.5)
    //   total (7.5, 16.25, 22.5): truncated (7, 16, 22), rounded (8, 16, 23).
    const std::string body = camera() + R"(,
        "Lights": {"AmbientLight": "40 40 40", "PointLight": {"_id": "1", "Position": "0 0 0", "Intensity": "1000 1000 1000"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0.125 0.25 0.375",
            "DiffuseReflectance": "0.25 0.625 0.75", "SpecularReflectance": "0 0 0", "PhongExponent": "1"}},
        )" + kFacingPlane;
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{7, 16, 22}));
    EXPECT_EQ(px(render_json(body, nearest()), 0, 0), (Pixel{8, 16, 23}));
}

TEST(ShadingRender, InverseSquareFalloff) {
    // Light at (0,0,-5), 5 above the hit point: E = 1010 / 25 = 40.4.
    //   ambient 0; diffuse = (0.25, 0.625, 0.75) * 40.4 = (10.1, 25.25, 30.3) -> (10, 25, 30).
    const std::string body = camera() + R"(,
        "Lights": {"PointLight": {"_id": "1", "Position": "0 0 -5", "Intensity": "1010 1010 1010"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0 0 0",
            "DiffuseReflectance": "0.25 0.625 0.75", "SpecularReflectance": "0 0 0"}},
        )" + kFacingPlane;
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{10, 25, 30}));
}

// Light at (5,0,-5): from the hit point (0,0,-10), l = (5,0,5)/sqrt(50), d^2 = 50.
std::string oblique_light_scene(const std::string& extra_objects, const std::string& extra_vertices) {
    return camera() + R"(,
        "Lights": {"AmbientLight": "42 42 42", "PointLight": {"_id": "1", "Position": "5 0 -5", "Intensity": "1000 1000 1000"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0.125 0.25 0.375",
            "DiffuseReflectance": "0.25 0.625 0.75", "SpecularReflectance": "0 0 0"}},
        "VertexData": {"_data": "0 0 -10 )" +
           extra_vertices + R"("},
        "Objects": {"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 1"})" +
           extra_objects + "}";
}

TEST(ShadingRender, ObliqueLightUnshadowed) {
    // n.l = 5 / sqrt(50) = 0.70710678, E = 1000 / 50 = 20:
    //   ambient (0.125, 0.25, 0.375) * 42 = (5.25, 10.5, 15.75)
    //   diffuse (0.25, 0.625, 0.75) * 20 * 0.70710678 = (3.53553, 8.83883, 10.60660)
    //   total (8.78553, 19.33883, 26.35660) -> (8, 19, 26)
    EXPECT_EQ(px(render_json(oblique_light_scene("", "")), 0, 0), (Pixel{8, 19, 26}));
}

TEST(ShadingRender, PointInShadowGetsOnlyAmbient) {
    // A sphere of radius 0.5 at (2.5, 0, -7.5), halfway between the hit point and the light
    // (and off the camera ray, which runs along the z axis): ambient only,
    // (5.25, 10.5, 15.75) -> (5, 10, 15).
    const std::string sphere = R"(, "Sphere": {"_id": "1", "Material": "1", "Center": "2", "Radius": "0.5"})";
    EXPECT_EQ(px(render_json(oblique_light_scene(sphere, "2.5 0 -7.5")), 0, 0), (Pixel{5, 10, 15}));
}

TEST(ShadingRender, BackFacingOccluderStillCastsShadow) {
    // The occluder is a triangle around (2.5, 0, -7.5) = 0.25 P0 + 0.25 P1 + 0.5 P2 with
    // P0 = (2,-1,-7), P1 = (3,-1,-8), P2 = (2.5,1,-7.5); its normal (P1-P0) x (P2-P0)
    // = (1,0,-1) x (0.5,2,-0.5) = (2,0,2) points at the light, so the shadow ray (direction
    // (1,0,1)/sqrt2) meets its back. Shadow rays never cull: ambient only, (5, 10, 15).
    const std::string tri = R"(, "Triangle": {"_id": "1", "Material": "1", "Indices": "2 3 4"})";
    const std::string verts = "2 -1 -7 3 -1 -8 2.5 1 -7.5";
    EXPECT_EQ(px(render_json(oblique_light_scene(tri, verts)), 0, 0), (Pixel{5, 10, 15}));
    EXPECT_EQ(px(render_json(oblique_light_scene(tri, verts), no_cull()), 0, 0), (Pixel{5, 10, 15}));
}

TEST(ShadingRender, BlinnPhongSpecular) {
    // Light at (10,0,0); hit point (0,0,-10): to_light (10,0,10), d^2 = 200, E = 20000/200 = 100,
    // l = (1,0,1)/sqrt2, v = (0,0,1), h = normalize(l + v) bisects them: n.h = cos(22.5 deg) = 0.92387953.
    // Specular = ks * (n.h)^4 * E = (1, 0.5, 0.25) * 0.72855339 * 100 = (72.855, 36.428, 18.214)
    // -> truncated (72, 36, 18); rounded (73, 36, 18). (Phong's r.v would give 0.25 * 100 = 25.)
    const std::string body = camera() + R"(,
        "Lights": {"PointLight": {"_id": "1", "Position": "10 0 0", "Intensity": "20000 20000 20000"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0 0 0",
            "DiffuseReflectance": "0 0 0", "SpecularReflectance": "1 0.5 0.25", "PhongExponent": "4"}},
        )" + kFacingPlane;
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{72, 36, 18}));
    EXPECT_EQ(px(render_json(body, nearest()), 0, 0), (Pixel{73, 36, 18}));
}

TEST(ShadingRender, LightBehindSurfaceAddsNothing) {
    // Light at (10, 0, -10.5), below the plane z = -10: ambient only (the plane also blocks the
    // shadow ray here; SmoothNormalFacingAwayFromLight isolates the n.l test).
    // (0.125, 0.25, 0.375) * 42 = (5.25, 10.5, 15.75) -> (5, 10, 15).
    const std::string body = camera() + R"(,
        "Lights": {"AmbientLight": "42 42 42", "PointLight": {"_id": "1", "Position": "10 0 -10.5", "Intensity": "20000 20000 20000"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0.125 0.25 0.375",
            "DiffuseReflectance": "1 1 1", "SpecularReflectance": "1 1 1", "PhongExponent": "1"}},
        )" + kFacingPlane;
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{5, 10, 15}));
}

TEST(ShadingRender, SmoothNormalFacingAwayFromLight) {
    // A smooth ridge along y: left slope L0 (-2,-5,-12) L1 (-2,5,-12) up to the ridge R0 (0,-5,-10)
    // R1 (0,5,-10), right slope down to O0 (2,-5,-12) O1 (2,5,-12). Face normals (-1,0,1)/sqrt2 and
    // (1,0,1)/sqrt2; R0 lies in 1 left + 2 right triangles, so its vertex normal is (1,0,3)/sqrt10,
    // R1's is (-1,0,3)/sqrt10, O1's is (1,0,1)/sqrt2.
    // The camera at (0.25,0,0) looking down -z hits the right slope at p = (0.25, 0, -10.25), in
    // triangle (R0, O1, R1) with weights (0.5, 0.125, 0.375): shading normal
    // normalize(0.5 (0.3162,0,0.9487) + 0.125 (0.7071,0,0.7071) + 0.375 (-0.3162,0,0.9487))
    // = (0.1379, 0, 0.9904).
    // The light sits at p + 10 (1, 0, -0.3): l = (0.9578, 0, -0.2873), above the face
    // (n_g.l = 0.474, the shadow ray is clear) but behind the shading normal (n_s.l = -0.153).
    // Diffuse is 0, and the specular term is dropped too although n_s.h = 0.70 (kept, it would
    // add 0.70 * E = 0.70 * 10900 / 109 = 70). Ambient only: (5.25, 10.5, 15.75) -> (5, 10, 15).
    const std::string body = R"("Cameras": {"Camera": {"_id": "1", "Position": "0.25 0 0", "Gaze": "0 0 -1",
            "Up": "0 1 0", "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "1 1", "ImageName": "t.png"}},
        "Lights": {"AmbientLight": "42 42 42", "PointLight": {"_id": "1", "Position": "10.25 0 -13.25", "Intensity": "10900 10900 10900"}},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0.125 0.25 0.375",
            "DiffuseReflectance": "1 1 1", "SpecularReflectance": "1 1 1", "PhongExponent": "1"}},
        "VertexData": {"_data": "-2 -5 -12  -2 5 -12  0 -5 -10  0 5 -10  2 -5 -12  2 5 -12"},
        "Objects": {"Mesh": {"_id": "1", "Material": "1", "_shadingMode": "smooth",
            "Faces": {"_data": "1 3 4  1 4 2  3 5 6  3 6 4"}}})";
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{5, 10, 15}));
    // Control: flat shading uses n_g, which faces the light: n.l = 0.47410, E = 100, and with
    // h = normalize(l + (0,0,1)) = (0.80229, 0, 0.59693), n.h = (0.80229 + 0.59693)/sqrt2 = 0.98940:
    // (5.25, 10.5, 15.75) + 47.410 + 98.940 = (151.600, 156.850, 162.100) -> (151, 156, 162).
    std::string flat = body;
    flat.replace(flat.find("smooth"), 6, "flat");
    EXPECT_EQ(px(render_json(flat), 0, 0), (Pixel{151, 156, 162}));
}

// Mirror sphere (radius 1 at z = -10) seen through the centre pixel of a 3x3 image; the
// reflected ray goes straight back (+z) and meets a plane at z = 5 behind the camera.
std::string mirror_scene(const std::string& extra_scene, bool with_plane, const std::string& sphere_ambient) {
    std::string objects = R"("Sphere": {"_id": "1", "Material": "1", "Center": "1", "Radius": "1"})";
    if (with_plane) objects += R"(, "Plane": {"_id": "1", "Material": "2", "Point": "2", "Normal": "0 0 -1"})";
    return camera("3 3") + extra_scene + R"(,
        "Lights": {"AmbientLight": "100 100 100"},
        "Materials": {"Material": [
            {"_id": "1", "_type": "mirror", "AmbientReflectance": ")" +
           sphere_ambient + R"(",
             "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0", "MirrorReflectance": "0.75 0.75 0.75"},
            {"_id": "2", "AmbientReflectance": "1 0.5 0.25", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"}]},
        "VertexData": {"_data": "0 0 -10 0 0 5"},
        "Objects": {)" +
           objects + "}";
}

TEST(ShadingRender, MirrorSphereReflectsColouredPlane) {
    // Centre pixel: sphere ambient 0.125 * 100 = 12.5, plus MirrorReflectance 0.75 times the
    // plane's colour (1, 0.5, 0.25) * 100 = (100, 50, 25): 12.5 + (75, 37.5, 18.75)
    // = (87.5, 50, 31.25) -> (87, 50, 31).
    const rt::Image img = render_json(mirror_scene(R"(, "BackgroundColor": "20 30 40")", true, "0.125 0.125 0.125"));
    EXPECT_EQ(px(img, 1, 1), (Pixel{87, 50, 31}));
    // Corner pixels miss the sphere (their rays leave at ~43 degrees) and never reach the plane
    // behind the camera: background.
    EXPECT_EQ(px(img, 0, 0), (Pixel{20, 30, 40}));
    EXPECT_EQ(px(img, 2, 2), (Pixel{20, 30, 40}));
}

TEST(ShadingRender, MaxRecursionDepthZeroDisablesMirror) {
    // No bounce allowed: only the sphere's own ambient, 12.5 -> 12.
    const rt::Image d0 = render_json(mirror_scene(R"(, "MaxRecursionDepth": "0")", true, "0.125 0.125 0.125"));
    EXPECT_EQ(px(d0, 1, 1), (Pixel{12, 12, 12}));
    // One bounce is enough to see the plane: (87, 50, 31) as above.
    const rt::Image d1 = render_json(mirror_scene(R"(, "MaxRecursionDepth": "1")", true, "0.125 0.125 0.125"));
    EXPECT_EQ(px(d1, 1, 1), (Pixel{87, 50, 31}));
}

TEST(ShadingRender, BackgroundOnlyForCameraRays) {
    // Without the plane the mirror reflects nothing: black (sphere ambient 0), not the
    // background, which the corner pixels show.
    const rt::Image img = render_json(mirror_scene(R"(, "BackgroundColor": "200 100 50")", false, "0 0 0"));
    EXPECT_EQ(px(img, 1, 1), (Pixel{0, 0, 0}));
    EXPECT_EQ(px(img, 0, 0), (Pixel{200, 100, 50}));
    EXPECT_EQ(px(img, 2, 0), (Pixel{200, 100, 50}));
}

TEST(ShadingRender, MirrorReflectionDirection) {
    // A mirror plane through (0,0,-10) with normal (1,0,1)/sqrt2 turns the camera ray (0,0,-1)
    // into d - 2 (d.n) n = (0,0,-1) + (1,0,1) = (1,0,0): it must see the red sphere at
    // (10,0,-10), not the green one at (-10,0,-10) or the blue one at (0,10,-10).
    // Red sphere ambient (1,0,0) * 100; mirror reflectance 1 -> (100, 0, 0).
    const std::string body = camera() + R"(,
        "Lights": {"AmbientLight": "100 100 100"},
        "Materials": {"Material": [
            {"_id": "1", "_type": "mirror", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1"},
            {"_id": "2", "AmbientReflectance": "1 0 0", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
            {"_id": "3", "AmbientReflectance": "0 1 0", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
            {"_id": "4", "AmbientReflectance": "0 0 1", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"}]},
        "VertexData": {"_data": "0 0 -10 10 0 -10 -10 0 -10 0 10 -10"},
        "Objects": {"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "1 0 1"},
            "Sphere": [{"_id": "1", "Material": "2", "Center": "2", "Radius": "1"},
                       {"_id": "2", "Material": "3", "Center": "3", "Radius": "1"},
                       {"_id": "3", "Material": "4", "Center": "4", "Radius": "1"}]})";
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{100, 0, 0}));
}

TEST(ShadingRender, ConductorUsesFresnelTimesMirrorReflectance) {
    // Gold-like conductor sphere, centre pixel at normal incidence: F = 0.84942977 (see
    // NormalIncidenceGold). Plane colour (100, 50, 25); MirrorReflectance (1, 0.5, 1):
    //   (100 * 0.84943 * 1, 50 * 0.84943 * 0.5, 25 * 0.84943 * 1) = (84.943, 21.236, 21.236) -> (84, 21, 21).
    const std::string body = camera("3 3") + R"(,
        "Lights": {"AmbientLight": "100 100 100"},
        "Materials": {"Material": [
            {"_id": "1", "_type": "conductor", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 0.5 1", "RefractionIndex": "0.37",
             "AbsorptionIndex": "2.82"},
            {"_id": "2", "AmbientReflectance": "1 0.5 0.25", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"}]},
        "VertexData": {"_data": "0 0 -10 0 0 5"},
        "Objects": {"Sphere": {"_id": "1", "Material": "1", "Center": "1", "Radius": "1"},
            "Plane": {"_id": "1", "Material": "2", "Point": "2", "Normal": "0 0 -1"}})";
    EXPECT_EQ(px(render_json(body), 1, 1), (Pixel{84, 21, 21}));
}

// Triangle at z = -5 with vertices (-1,-1), (0,1), (1,-1): (b-a) x (c-a) = (1,2,0) x (2,0,0)
// = (0,0,-4), facing away from the camera. `reverse` flips it towards the camera.
std::string culling_scene(bool reverse) {
    return camera() + R"(, "BackgroundColor": "10 20 30",
        "Lights": {"AmbientLight": "100 100 100"},
        "Materials": {"Material": {"_id": "1", "AmbientReflectance": "0.5 0.5 0.5", "DiffuseReflectance": "0 0 0",
            "SpecularReflectance": "0 0 0"}},
        "VertexData": {"_data": "-1 -1 -5 0 1 -5 1 -1 -5"},
        "Objects": {"Triangle": {"_id": "1", "Material": "1", "Indices": ")" +
           (reverse ? "3 2 1" : "1 2 3") + R"("}})";
}

TEST(ShadingRender, BackFaceCulling) {
    // Ambient 0.5 * 100 = 50 when visible; background (10, 20, 30) when culled.
    EXPECT_EQ(px(render_json(culling_scene(false)), 0, 0), (Pixel{10, 20, 30}));
    EXPECT_EQ(px(render_json(culling_scene(false), no_cull()), 0, 0), (Pixel{50, 50, 50}));
    EXPECT_EQ(px(render_json(culling_scene(true)), 0, 0), (Pixel{50, 50, 50}));
    EXPECT_EQ(px(render_json(culling_scene(true), no_cull()), 0, 0), (Pixel{50, 50, 50}));
}

TEST(ShadingRender, InvisibleGlass) {
    // A dielectric sphere (radius 1 at z = -5) with RefractionIndex 1, no absorption and no
    // reflectances reflects nothing (F = 0) and bends nothing, so the plane behind it keeps its
    // colour: (0.995, 0.505, 0.255) * 100 = (99.5, 50.5, 25.5) -> (99, 50, 25) in every pixel.
    // The near plane +-0.15 keeps all 9 pixel rays (|s| <= 0.1) inside the sphere's outline
    // (tan = 1/sqrt(24) = 0.204).
    for (bool glass : {false, true}) {
        std::string objects = R"("Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 1"})";
        if (glass) objects += R"(, "Sphere": {"_id": "1", "Material": "2", "Center": "2", "Radius": "1"})";
        const std::string body = camera("3 3", "0.15") + R"(, "BackgroundColor": "255 0 255",
            "Lights": {"AmbientLight": "100 100 100"},
            "Materials": {"Material": [
                {"_id": "1", "AmbientReflectance": "0.995 0.505 0.255", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
                {"_id": "2", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
                 "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1", "RefractionIndex": "1",
                 "AbsorptionCoefficient": "0 0 0"}]},
            "VertexData": {"_data": "0 0 -10 0 0 -5"},
            "Objects": {)" + objects +
                                 "}";
        const rt::Image img = render_json(body);
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 3; ++i)
                EXPECT_EQ(px(img, i, j), (Pixel{99, 50, 25}))
                    << (glass ? "with" : "without") << " glass, pixel " << i << "," << j;
    }
}

// A glass slab 2 thick: a front quad at z = -4 (normal +z) and a back quad at z = -6
// (normal -z), spanning x in [-2, 3], y in [-3, 2] so that their diagonals (y = x - 1) miss
// the centre ray. Behind it, a plane of colour 200 at z = -10. ShadowRayEpsilon 1e-6 keeps
// the path inside the glass at 2 - 1e-6.
std::string slab_scene(const std::string& index, const std::string& glass_ambient, const std::string& absorption) {
    return camera() + R"(, "ShadowRayEpsilon": "1e-6",
        "Lights": {"AmbientLight": "200 200 200"},
        "Materials": {"Material": [
            {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
            {"_id": "2", "_type": "dielectric", "AmbientReflectance": ")" +
           glass_ambient + R"(",
             "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1",
             "RefractionIndex": ")" +
           index + R"(", "AbsorptionCoefficient": ")" + absorption + R"("}]},
        "VertexData": {"_data": "0 0 -10  -2 -3 -4 3 -3 -4 3 2 -4 -2 2 -4  -2 -3 -6 -2 2 -6 3 2 -6 3 -3 -6"},
        "Objects": {"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 1"},
            "Mesh": [{"_id": "1", "Material": "2", "Faces": {"_data": "2 3 4 2 4 5"}},
                     {"_id": "2", "Material": "2", "Faces": {"_data": "6 7 8 6 8 9"}}]})";
}

TEST(ShadingRender, BeerLawThroughSlab) {
    // Index 1 (no Fresnel, no bending), c = (0.1, 0.5, 1), path 2:
    //   200 * (e^-0.2, e^-1, e^-2) = 200 * (0.81873, 0.36788, 0.13534) = (163.746, 73.576, 27.067)
    //   -> (163, 73, 27).
    EXPECT_EQ(px(render_json(slab_scene("1", "0 0 0", "0.1 0.5 1")), 0, 0), (Pixel{163, 73, 27}));
    // Without absorption the slab is invisible: 200.
    EXPECT_EQ(px(render_json(slab_scene("1", "0 0 0", "0 0 0")), 0, 0), (Pixel{200, 200, 200}));
}

TEST(ShadingRender, GlassSlabWithFresnel) {
    // Index 1.5 at normal incidence: R = 0.04, T = 0.96 at each face. Direct path
    // T^2 e^-2c; the next path reflects once off each face inside: T^2 R^2 e^-6c
    // (later ones are below 1e-5 of a level). For c = (0.1, 0.5, 1):
    //   200 * 0.9216 * (e^-0.2 + 0.0016 e^-0.6, e^-1 + 0.0016 e^-3, e^-2 + 0.0016 e^-6)
    //   = (151.070, 67.822, 24.946) -> (151, 67, 24).
    // (The reflection off the front face heads back past the camera into nothing: black.)
    const rt::Image img = render_json(slab_scene("1.5", "0 0 0", "0.1 0.5 1"));
    EXPECT_EQ(px(img, 0, 0), (Pixel{151, 67, 24}));
}

TEST(ShadingRender, GlassShadedOnlyFromOutside) {
    // Glass ambient 0.125 * 200 = 25 is added where the camera ray enters (front face, from
    // outside) but not where it leaves (hit from inside): 25 + 200 = 225 with index 1 and no
    // absorption. Shading the inside hit too would give 250.
    EXPECT_EQ(px(render_json(slab_scene("1", "0.125 0.125 0.125", "0 0 0")), 0, 0), (Pixel{225, 225, 225}));
}

TEST(ShadingRender, NoCullingInsideGlass) {
    // The back quad's normal points away from the camera; a ray travelling inside the glass
    // must still hit it (culling never applies inside a dielectric), with culling on or off:
    // the Beer's-law result of BeerLawThroughSlab in both cases.
    EXPECT_EQ(px(render_json(slab_scene("1", "0 0 0", "0.1 0.5 1"), no_cull()), 0, 0), (Pixel{163, 73, 27}));
}

// A mirror inside glass: the camera ray enters a glass face at z = -4 (normal +z, index
// 1.5, absorption `absorption`) and meets a mirror at z = -6 facing it; the mirror sends
// the ray straight back to the glass face, which it now meets from behind. Behind the
// camera, a wall at z = +5 facing it, of colour W = (0.995, 0.505, 0.255) * 100.
// MaxRecursionDepth 3: camera ray 0, refracted 1, mirror reflection 2, what the glass
// spawns from it 3 (a depth-3 ray meeting the mirror again reflects nothing).
std::string mirror_in_glass_scene(const std::string& absorption) {
    return camera() + R"(, "ShadowRayEpsilon": "1e-6", "MaxRecursionDepth": "3",
        "Lights": {"AmbientLight": "100 100 100"},
        "Materials": {"Material": [
            {"_id": "1", "AmbientReflectance": "0.995 0.505 0.255", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
            {"_id": "2", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1", "RefractionIndex": "1.5",
             "AbsorptionCoefficient": ")" +
           absorption + R"("},
            {"_id": "3", "_type": "mirror", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1"}]},
        "VertexData": {"_data": "0 0 5  -2 -3 -4 3 -3 -4 3 2 -4 -2 2 -4  -2 -3 -6 3 -3 -6 3 2 -6 -2 2 -6"},
        "Objects": {"Plane": {"_id": "1", "Material": "1", "Point": "1", "Normal": "0 0 -1"},
            "Mesh": [{"_id": "1", "Material": "2", "Faces": {"_data": "2 3 4 2 4 5"}},
                     {"_id": "2", "Material": "3", "Faces": {"_data": "6 7 8 6 8 9"}}]})";
}

TEST(ShadingRender, MirrorReflectionInsideGlassIsCulled) {
    // Which rays count as inside a dielectric is decided by the interface that spawned them
    // (docs/conventions.md): the mirror's reflection is not inside, so with culling it passes
    // the glass face it meets from behind and sees the wall undimmed. With F = 0.04 at normal
    // incidence: 0.04 W (front reflection) + 0.96 W = W = (99.5, 50.5, 25.5) -> (99, 50, 25).
    EXPECT_EQ(px(render_json(mirror_in_glass_scene("0 0 0")), 0, 0), (Pixel{99, 50, 25}));
    // Without culling it leaves through the glass (0.96; the depth-3 internal reflection meets
    // the mirror and adds nothing): 0.04 W + 0.96^2 W = (95.68, 48.56, 24.52) -> (95, 48, 24).
    // Tracking the medium across the mirror bounce (a ray inside glass stays inside) would give
    // this with culling on too.
    EXPECT_EQ(px(render_json(mirror_in_glass_scene("0 0 0"), no_cull()), 0, 0), (Pixel{95, 48, 24}));
}

TEST(ShadingRender, BeerLawOnlyAfterADielectricInterface) {
    // c = (0.1, 0.5, 1). Beer's law dims the segment the glass face refracted inside (to the
    // mirror, 2 - 1e-6 long) but not the mirror's reflection, which no dielectric interface
    // spawned. Culling on: 0.04 W + 0.96 e^-2c W = (82.19, 19.85, 4.33) -> (82, 19, 4).
    EXPECT_EQ(px(render_json(mirror_in_glass_scene("0.1 0.5 1")), 0, 0), (Pixel{82, 19, 4}));
    // Culling off, leaving through the glass: 0.04 W + 0.96^2 e^-2c W = (79.06, 19.14, 4.20)
    // -> (79, 19, 4). Dimming the mirror's reflection as well would give (65.45, 8.32, 1.45).
    EXPECT_EQ(px(render_json(mirror_in_glass_scene("0.1 0.5 1"), no_cull()), 0, 0), (Pixel{79, 19, 4}));
}

TEST(ShadingRender, RefractionBendsTowardsTheNormal) {
    // The camera looks along (1,0,-1)/sqrt2 and enters glass (index 1.5) through the face z = -4
    // at (4, 0, -4). Snell: sin t = sin 45 / 1.5 = 0.47140, tan t = 0.53452, so after 2 more units
    // of depth the ray reaches z = -6 at x = 4 + 2 * 0.53452 = 5.069, on the red strip x in
    // [4.5, 5.5]; unbent it would land at x = 6, on the green part. The strip lies inside the glass
    // (which has no back face), so it is seen through one interface:
    // (1 - F(45 deg)) * 200 = (1 - 0.05023991) * 200 = 189.952 -> (189, 0, 0).
    const std::string body = R"("Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "1 0 -1",
            "Up": "0 1 0", "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "1 1", "ImageName": "t.png"}},
        "Lights": {"AmbientLight": "200 200 200"},
        "Materials": {"Material": [
            {"_id": "1", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
             "SpecularReflectance": "0 0 0", "MirrorReflectance": "1 1 1", "RefractionIndex": "1.5",
             "AbsorptionCoefficient": "0 0 0"},
            {"_id": "2", "AmbientReflectance": "1 0 0", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"},
            {"_id": "3", "AmbientReflectance": "0 1 0", "DiffuseReflectance": "0 0 0", "SpecularReflectance": "0 0 0"}]},
        "VertexData": {"_data": "-10 -10 -4  20 -10 -4  20 10 -4  -10 10 -4   4.5 -1 -6  5.5 -1 -6  5.5 1 -6  4.5 1 -6   8 -1 -6  8 1 -6"},
        "Objects": {"Mesh": [
            {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3 1 3 4"}},
            {"_id": "2", "Material": "2", "Faces": {"_data": "5 6 7 5 7 8"}},
            {"_id": "3", "Material": "3", "Faces": {"_data": "6 9 10 6 10 7"}}]})";
    EXPECT_EQ(px(render_json(body), 0, 0), (Pixel{189, 0, 0}));
}

TEST(ShadingRender, TraceDoesNotDependOnThreadCount) {
    rt::RenderOptions one;
    one.threads = 1;
    rt::RenderOptions many;
    many.threads = 4;
    // 64 x 48 pixels: 4 x 3 tiles of 16 x 16, so several threads really share the work.
    std::string body = mirror_scene(R"(, "BackgroundColor": "20 30 40")", true, "0.125 0.125 0.125");
    body.replace(body.find("\"3 3\""), 5, "\"64 48\"");
    const rt::Image a = render_json(body, one), b = render_json(body, many);
    ASSERT_EQ(a.width, 64);
    ASSERT_EQ(a.height, 48);
    EXPECT_EQ(a.rgb, b.rgb);
    // The image is not uniform: the sphere and the background both show.
    EXPECT_EQ(px(a, 0, 0), (Pixel{20, 30, 40}));
    EXPECT_EQ(px(a, 32, 24), (Pixel{87, 50, 31}));
}

}  // namespace
