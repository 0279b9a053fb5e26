// Misspelt keys (rt/loader/spelling.h, the loader's warnings) and --strict, through the binary:
// an unknown key within a small edit distance of a key valid at its place is reported
// with that key ("did you mean ...?"), a missing required key names the near miss found
// instead, --strict turns every warning into an error (exit 1, no image), the summary
// line counts the warnings, and every error line starts "error: ".
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/loader/spelling.h"
#include "test_support.h"

using json = nlohmann::ordered_json;

namespace {

// One object of every kind: a camera, a light, a material, a mesh, a triangle, a sphere
// and a plane, at 8x8.
json every_kind_scene() {
    return json::parse(R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0",
                             "NearPlane": "-1 1 -1 1", "NearDistance": "1",
                             "ImageResolution": "8 8", "ImageName": "k.png"}},
      "Lights": {"AmbientLight": "25 25 25",
                 "PointLight": {"_id": "1", "Position": "0 4 4", "Intensity": "1000 1000 1000"}},
      "Materials": {"Material": {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1",
                                 "SpecularReflectance": "1 1 1", "PhongExponent": "1"}},
      "VertexData": "-1 -1 0  1 -1 0  0 1 0  0 0 -3",
      "Objects": {
        "Mesh": {"_id": "1", "Material": "1", "Faces": {"_data": "1 2 3"}},
        "Triangle": {"_id": "1", "Material": "1", "Indices": "1 2 3"},
        "Sphere": {"_id": "1", "Material": "1", "Center": "4", "Radius": "0.5"},
        "Plane": {"_id": "1", "Material": "1", "Point": "4", "Normal": "0 0 1"}}}})");
}

std::string dump(const RunResult& r) { return "\n--- exit " + std::to_string(r.exit_code) + "\n" + r.err; }

// Renders `scene` (written as k.json) in a fresh folder with `flags`.
struct Rendered {
    TempDir tmp;
    RunResult r;
    std::vector<std::string> files;
};

void render(Rendered& out, const json& scene, std::vector<std::string> flags = {}) {
    write_text(out.tmp / "k.json", scene.dump(1));
    flags.push_back("k.json");
    out.r = run_raytracer(flags, out.tmp.path());
    out.files = list_files(out.tmp.path());
}

// Moves the value of key `from` of the object at `pointer` to key `to`.
json rename_key(json scene, const std::string& pointer, const std::string& from, const std::string& to) {
    json& obj = scene[json::json_pointer(pointer)];
    obj[to] = obj[from];
    obj.erase(from);
    return scene;
}

}  // namespace

TEST(Spelling, EditDistanceCountsInsertionsDeletionsSubstitutionsAndSwaps) {
    EXPECT_EQ(rt::edit_distance_nocase("", ""), 0u);
    EXPECT_EQ(rt::edit_distance_nocase("abc", ""), 3u);
    EXPECT_EQ(rt::edit_distance_nocase("Radius", "radius"), 0u);  // case only
    EXPECT_EQ(rt::edit_distance_nocase("Raduis", "Radius"), 1u);  // one swap
    EXPECT_EQ(rt::edit_distance_nocase("DiffuseReflectence", "DiffuseReflectance"), 1u);
    EXPECT_EQ(rt::edit_distance_nocase("Positon", "Position"), 1u);            // one deletion
    EXPECT_EQ(rt::edit_distance_nocase("NearDistances", "NearDistance"), 1u);  // one insertion
    EXPECT_EQ(rt::edit_distance_nocase("kitten", "sitting"), 3u);
    EXPECT_EQ(rt::edit_distance_nocase("ca", "abc"), 3u);  // optimal string alignment, not full Damerau (2)
}

TEST(Spelling, NearMissOnlyForCloseWords) {
    const std::vector<std::string> keys{"_id", "Material", "Center", "Radius"};
    EXPECT_EQ(rt::near_miss("Raduis", keys), "Radius");
    EXPECT_EQ(rt::near_miss("radius", keys), "Radius");
    EXPECT_EQ(rt::near_miss("Centre", keys), "Center");
    EXPECT_EQ(rt::near_miss("Materail", keys), "Material");
    EXPECT_EQ(rt::near_miss("id", keys), "_id");
    EXPECT_EQ(rt::near_miss("NumSamples", keys), "");
    EXPECT_EQ(rt::near_miss("Rad", keys), "");  // three edits from Radius
    EXPECT_EQ(rt::near_miss("Xy", keys), "");   // short words: one edit at most
    EXPECT_EQ(rt::near_miss("Radius", keys), "");
}

// A key of an object and a misspelling of it.
struct KeyTypo {
    const char* pointer;  // the object
    const char* key;      // a valid key of it
    const char* typo;
};

// A misspelt key in each kind of object is reported with the key meant, and the scene
// renders (exit 0) with the warning counted on the summary line.
TEST(MisspeltKeys, EachKindOfObjectSuggestsTheKeyMeant) {
    const KeyTypo cases[] = {
        {"/Scene/Cameras/Camera", "_id", "id"},
        {"/Scene/Lights/PointLight", "_id", "_Id"},
        {"/Scene/Materials/Material", "DiffuseReflectance", "DiffuseReflectence"},
        {"/Scene/Materials/Material", "PhongExponent", "phongexponent"},
        {"/Scene/Objects/Mesh", "_id", "_ids"},
        {"/Scene/Objects/Triangle", "_id", "__id"},
        {"/Scene/Objects/Sphere", "_id", "id"},
        {"/Scene/Objects/Plane", "_id", "_di"},
        {"/Scene", "BackgroundColor", "BackgroundColour"},
        {"/Scene", "ShadowRayEpsilon", "ShadowRayEpsillon"},
    };
    for (const KeyTypo& c : cases) {
        SCOPED_TRACE(std::string(c.pointer) + "/" + c.typo);
        json scene = every_kind_scene();
        scene[json::json_pointer(std::string(c.pointer) + "/" + c.key)] = "1";
        Rendered out;
        render(out, rename_key(scene, c.pointer, c.key, c.typo));
        EXPECT_EQ(out.r.exit_code, 0) << dump(out.r);
        EXPECT_TRUE(contains(out.r.err, std::string("warning: k.json: ") + c.pointer + "/" + c.typo +
                                            ": unknown key ignored (did you mean " + c.key + "?)\n"))
            << dump(out.r);
        EXPECT_TRUE(contains(out.r.err, "k.png: 8x8, ")) << dump(out.r);
        EXPECT_TRUE(contains(out.r.err, ", 1 warning\n")) << dump(out.r);
    }
}

// A key nothing like a valid one is reported without a suggestion.
TEST(MisspeltKeys, NoSuggestionForAnUnrelatedKey) {
    json scene = every_kind_scene();
    scene["Scene"]["Cameras"]["Camera"]["Exposure"] = "4";
    scene["Scene"]["Objects"]["Sphere"]["Texture"] = "wood";
    Rendered out;
    render(out, scene);
    EXPECT_EQ(out.r.exit_code, 0) << dump(out.r);
    const std::vector<std::string> lines = split_lines(out.r.err);
    ASSERT_EQ(lines.size(), 3u) << dump(out.r);
    EXPECT_EQ(lines[0], "warning: k.json: /Scene/Cameras/Camera/Exposure: unknown key ignored");
    EXPECT_EQ(lines[1], "warning: k.json: /Scene/Objects/Sphere/Texture: unknown key ignored");
    EXPECT_TRUE(contains(lines[2], ", 2 warnings")) << lines[2];
}

// A misspelt required key is an error naming the key found instead; every required key
// of each kind of object.
TEST(MisspeltKeys, MissingRequiredKeyNamesTheNearMiss) {
    const KeyTypo cases[] = {
        {"/Scene/Cameras/Camera", "NearDistance", "NearDistnace"},
        {"/Scene/Cameras/Camera", "Position", "position"},
        {"/Scene/Lights/PointLight", "Intensity", "Intensty"},
        {"/Scene/Objects/Mesh", "Material", "Materail"},
        {"/Scene/Objects/Mesh", "Faces", "Face"},
        {"/Scene/Objects/Triangle", "Indices", "Indexes"},
        {"/Scene/Objects/Sphere", "Radius", "Raduis"},
        {"/Scene/Objects/Sphere", "Center", "Centre"},
        {"/Scene/Objects/Plane", "Normal", "Normall"},
    };
    for (const KeyTypo& c : cases) {
        SCOPED_TRACE(std::string(c.pointer) + "/" + c.typo);
        Rendered out;
        render(out, rename_key(every_kind_scene(), c.pointer, c.key, c.typo));
        EXPECT_EQ(out.r.exit_code, 1) << dump(out.r);
        EXPECT_EQ(split_lines(out.r.err),
                  std::vector<std::string>{std::string("error: k.json: ") + c.pointer + "/" + c.key +
                                           ": required key is missing (found '" + c.typo + "' instead)"})
            << dump(out.r);
        EXPECT_EQ(out.files, std::vector<std::string>{"k.json"});
    }
    // Nothing near: the plain message.
    json scene = every_kind_scene();
    scene["Scene"]["Objects"]["Sphere"].erase("Radius");
    Rendered out;
    render(out, scene);
    EXPECT_EQ(split_lines(out.r.err),
              std::vector<std::string>{"error: k.json: /Scene/Objects/Sphere/Radius: required key is missing"})
        << dump(out.r);
}

// --strict: a warning is an error; the scene writes nothing and the exit status is 1;
// another scene without warnings on the same command line still renders. Without
// --strict the same scene renders.
TEST(MisspeltKeys, StrictTurnsWarningsIntoErrors) {
    Rendered out;
    write_text(out.tmp / "clean.json", [] {
        json clean = every_kind_scene();
        clean["Scene"]["Cameras"]["Camera"]["ImageName"] = "clean.png";
        return clean.dump();
    }());
    json scene =
        rename_key(every_kind_scene(), "/Scene/Materials/Material", "DiffuseReflectance", "DiffuseReflectence");
    render(out, scene, {"--strict", "clean.json"});
    EXPECT_EQ(out.r.exit_code, 1) << dump(out.r);
    const std::vector<std::string> lines = split_lines(out.r.err);
    ASSERT_EQ(lines.size(), 2u) << dump(out.r);
    EXPECT_EQ(lines[0].rfind("clean.png: 8x8, ", 0), 0u) << lines[0];  // clean.json comes first
    EXPECT_FALSE(contains(lines[0], "warning")) << lines[0];
    EXPECT_EQ(lines[1],
              "error: k.json: /Scene/Materials/Material/DiffuseReflectence: unknown key (did you mean "
              "DiffuseReflectance?); --strict makes it an error");
    EXPECT_EQ(out.files, (std::vector<std::string>{"clean.json", "clean.png", "k.json"}));

    // Quiet does not hide a --strict error; without --strict the image is written.
    Rendered quiet;
    render(quiet, scene, {"--strict", "-q"});
    EXPECT_EQ(quiet.r.exit_code, 1) << dump(quiet.r);
    EXPECT_EQ(split_lines(quiet.r.err).size(), 1u) << dump(quiet.r);
    Rendered lax;
    render(lax, scene);
    EXPECT_EQ(lax.r.exit_code, 0) << dump(lax.r);
    EXPECT_EQ(lax.files, (std::vector<std::string>{"k.json", "k.png"}));
}

// A degenerate triangle and extra NearPlane numbers are warnings too: counted, and under
// --strict errors that say what is wrong, not what the renderer would have done instead.
TEST(MisspeltKeys, StrictCoversEveryKindOfWarning) {
    struct Case {
        const char *pointer, *value, *warning, *error;
    };
    const Case cases[] = {
        {"/Scene/Objects/Triangle/Indices", "1 1 2", "warning: k.json: skipped 1 degenerate triangle",
         "error: k.json: 1 degenerate triangle; --strict makes it an error"},
        {"/Scene/Cameras/Camera/NearPlane", "-1 1 -1 1 3",
         "warning: k.json: /Scene/Cameras/Camera/NearPlane: 5 numbers, the first 4 used (left right bottom top)",
         "error: k.json: /Scene/Cameras/Camera/NearPlane: 5 numbers (expected 4: left right bottom top); --strict "
         "makes it an error"},
    };
    for (const Case& c : cases) {
        SCOPED_TRACE(c.pointer);
        json scene = every_kind_scene();
        scene[json::json_pointer(c.pointer)] = c.value;
        Rendered lax;
        render(lax, scene);
        EXPECT_EQ(lax.r.exit_code, 0) << dump(lax.r);
        EXPECT_TRUE(contains(lax.r.err, std::string(c.warning) + "\n")) << dump(lax.r);
        EXPECT_TRUE(contains(lax.r.err, ", 1 warning\n")) << dump(lax.r);
        Rendered strict;
        render(strict, scene, {"--strict"});
        EXPECT_EQ(strict.r.exit_code, 1) << dump(strict.r);
        EXPECT_EQ(split_lines(strict.r.err), std::vector<std::string>{c.error});
        EXPECT_EQ(strict.files, std::vector<std::string>{"k.json"});
    }
}

// A mesh's Faces needs one of two keys: a near miss of either is named with the key meant.
TEST(MisspeltKeys, FacesNamesTheNearMissOfItsKeys) {
    const std::pair<const char*, const char*> cases[] = {{"_plyfile", "_plyFile"}, {"_dta", "_data"}};
    for (const auto& [typo, meant] : cases) {
        SCOPED_TRACE(typo);
        json scene = every_kind_scene();
        scene["Scene"]["Objects"]["Mesh"]["Faces"] = {{typo, "m.ply"}};
        Rendered out;
        render(out, scene);
        EXPECT_EQ(out.r.exit_code, 1) << dump(out.r);
        EXPECT_EQ(
            split_lines(out.r.err),
            std::vector<std::string>{std::string("error: k.json: /Scene/Objects/Mesh/Faces: needs _data or _plyFile "
                                                 "(did you mean ") +
                                     meant + "? found " + typo + ")"})
            << dump(out.r);
    }
    // Nothing near: the plain message.
    json scene = every_kind_scene();
    scene["Scene"]["Objects"]["Mesh"]["Faces"] = {{"Vertices", "1 2 3"}};
    Rendered out;
    render(out, scene);
    EXPECT_EQ(split_lines(out.r.err),
              std::vector<std::string>{"error: k.json: /Scene/Objects/Mesh/Faces: needs _data or _plyFile"});
}

// Every line a failing run prints on stderr starts "error: " (a bad scene, an unwritable
// image, a usage error before its usage line).
TEST(MisspeltKeys, EveryErrorLineStartsWithError) {
    TempDir tmp;
    json scene = every_kind_scene();
    write_text(tmp / "ok.json", scene.dump());
    scene["Scene"]["Cameras"]["Camera"]["ImageName"] = "nodir/file.png";
    write_text(tmp / "nodir", "a file where a folder should be");
    write_text(tmp / "unwritable.json", scene.dump());
    for (const std::vector<std::string>& args : std::vector<std::vector<std::string>>{
             {"missing.json"}, {"unwritable.json"}, {"--bogus", "ok.json"}, {"--stats", "nodir/s.json", "ok.json"}}) {
        SCOPED_TRACE(args[0]);
        const RunResult r = run_raytracer(args, tmp.path());
        EXPECT_NE(r.exit_code, 0) << dump(r);
        const std::vector<std::string> lines = split_lines(r.err);
        ASSERT_FALSE(lines.empty());
        size_t errors = 0;
        for (const std::string& l : lines)
            if (l.rfind("error: ", 0) == 0)
                ++errors;
            else
                EXPECT_TRUE(l.rfind("usage:", 0) == 0 || l.rfind("  ", 0) == 0 || contains(l, ": 8x8, ")) << l;
        EXPECT_EQ(errors, 1u) << dump(r);
    }
}
