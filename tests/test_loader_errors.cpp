// Tests for the JSON scene loader (include/rt/loader/load_scene.h, src/loader/), bad input:
// every class must throw rt::InputError whose one-line message starts with the file path
// and names the JSON pointer of the offending value.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <exception>
#include <string>

#include "loader_test_support.h"
#include "rt/core/error.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/scene_desc.h"
#include "rt/loader/scene_tree.h"

namespace {

using namespace loader_test;

// --- bad input --------------------------------------------------------------------------

// Parses `text`, expecting rt::InputError "<path>: ...<pointer>...". `also` must appear too.
void expect_error(const std::string& text, const std::string& pointer, const std::string& also = "") {
    try {
        const rt::SceneDesc d = parse(text);
        ADD_FAILURE() << "no error; expected one at " << pointer;
    } catch (const rt::InputError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(kPath + ": ", 0), 0u) << "message must start with the file path: " << msg;
        EXPECT_NE(msg.find(pointer), std::string::npos) << "message must contain " << pointer << ": " << msg;
        if (!also.empty()) {
            EXPECT_NE(msg.find(also), std::string::npos) << "message must contain " << also << ": " << msg;
        }
        EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
    } catch (const std::exception& e) {
        ADD_FAILURE() << "wrong exception type: " << e.what();
    }
}

const std::string kCam = "/Scene/Cameras/Camera";

// The message of the InputError parsing `text` throws ("" if none).
std::string parse_error_of(const std::string& text) {
    try {
        (void)parse(text);
    } catch (const rt::InputError& e) {
        return e.what();
    }
    return "";
}

// A value followed by another value without a comma: nlohmann reports the place of the
// second; the message adds where the comma is missing (after the end of the first, which
// may span lines), and nothing when the mistake is another one.
TEST(LoaderErrors, MissingCommaNamesTheLineBefore) {
    const std::string members = "{\"Scene\": {\n  \"A\": \"1\"\n  \"B\": \"2\"\n}}";
    EXPECT_EQ(parse_error_of(members),
              kPath +
                  ": parse error at line 3, column 5: syntax error while parsing object - unexpected string "
                  "literal; expected '}' (missing ',' after line 2?)");
    const std::string after_object = "{\"Scene\": {\n \"A\": {\n  \"x\": \"a \\\" b\"\n }\n\n \"B \\\" c\": 2}}";
    EXPECT_NE(parse_error_of(after_object).find("(missing ',' after line 4?)"), std::string::npos)
        << parse_error_of(after_object);
    const std::string elements = "{\"Scene\": [\n 1\n 22\n]}";
    EXPECT_NE(parse_error_of(elements).find("expected ']' (missing ',' after line 2?)"), std::string::npos)
        << parse_error_of(elements);
    for (const char* value : {"{}", "[1]", "true", "null", "false", "-1.5e3", "\"x\""}) {
        const std::string text = std::string("{\"Scene\": {\"A\": \"1\"\n\n ") + value + "}}";
        EXPECT_NE(parse_error_of(text).find("(missing ',' after line 1?)"), std::string::npos)
            << value << ": " << parse_error_of(text);
    }
    // Not a missing comma: no hint.
    for (const char* text :
         {"{\"Scene\": {\"A\": \"1\",\n}}", "{\"Scene\" \"A\"}", "{\"Scene\": [1, 2", "{\"Scene\": {\"A\": tru}}"}) {
        const std::string msg = parse_error_of(text);
        EXPECT_NE(msg.find("parse error"), std::string::npos) << msg;
        EXPECT_EQ(msg.find("missing ','"), std::string::npos) << msg;
    }
}

TEST(LoaderErrors, MissingScene) {
    expect_error(R"({"Cameras": {}})", "/Scene");
    expect_error(R"([1, 2])", "/");
    expect_error(R"({"Scene": "text"})", "/Scene");
}

TEST(LoaderErrors, MissingCameras) {
    json j = sample();
    j["Scene"].erase("Cameras");
    expect_error(j.dump(), "/Scene/Cameras");
}

TEST(LoaderErrors, MissingCameraPosition) {
    json j = sample();
    j["Scene"]["Cameras"]["Camera"].erase("Position");
    expect_error(j.dump(), kCam + "/Position");
}

TEST(LoaderErrors, WrongType) {
    json j = sample();
    j["Scene"]["Cameras"]["Camera"]["Position"] = {{"x", "0"}};
    expect_error(j.dump(), kCam + "/Position");
    j = sample();
    j["Scene"]["Cameras"]["Camera"]["ImageName"] = 5;
    expect_error(j.dump(), kCam + "/ImageName");
    j = sample();
    j["Scene"]["Objects"]["Sphere"]["Radius"] = true;
    expect_error(j.dump(), "/Scene/Objects/Sphere/Radius");
    j = sample();
    j["Scene"]["Objects"]["Sphere"] = "not an object";
    expect_error(j.dump(), "/Scene/Objects/Sphere");
}

TEST(LoaderErrors, BadNumbers) {
    const std::pair<const char*, const char*> cases[] = {
        {"1 2 x", "non-numeric"},  {"1 2", "too short"},    {"1 2 3 4", "too long"},
        {"nan 0 0", "NaN"},        {"inf 0 0", "infinite"}, {"0 -inf 0", "infinite"},
        {"1e999 0 0", "overflow"}, {"", "empty"},           {"1,2,3", "commas"}};
    for (const auto& [value, why] : cases) {
        SCOPED_TRACE(std::string(why) + ": \"" + value + "\"");
        json j = sample();
        j["Scene"]["Cameras"]["Camera"]["Position"] = value;
        expect_error(j.dump(), kCam + "/Position");
    }
    json j = sample();
    j["Scene"]["Objects"]["Sphere"]["Radius"] = "inf";
    expect_error(j.dump(), "/Scene/Objects/Sphere/Radius");
    j = sample();
    j["Scene"]["Lights"]["PointLight"]["Intensity"] = "1000 nan 1000";
    expect_error(j.dump(), "/Scene/Lights/PointLight/Intensity");
    j = sample();
    j["Scene"]["VertexData"]["_data"] = "0 0 0 1 1 x";
    expect_error(j.dump(), "/Scene/VertexData");
}

TEST(LoaderErrors, BadResolution) {
    for (const char* res : {"0 800", "800 0", "-800 800", "800 -1", "800.5 800", "800"}) {
        SCOPED_TRACE(res);
        json j = sample();
        j["Scene"]["Cameras"]["Camera"]["ImageResolution"] = res;
        expect_error(j.dump(), kCam + "/ImageResolution");
    }
}

TEST(LoaderErrors, TooLargeResolutionRefusedBeforeAllocating) {
    // 10^10 pixels (30 GB of RGB) must be refused at load time.
    for (const char* res : {"100000 100000", "2147483647 2", "1e15 1"}) {
        SCOPED_TRACE(res);
        json j = sample();
        j["Scene"]["Cameras"]["Camera"]["ImageResolution"] = res;
        expect_error(j.dump(), kCam + "/ImageResolution");
    }
}

TEST(LoaderErrors, BadCameraVectors) {
    json j = sample();
    j["Scene"]["Cameras"]["Camera"]["Gaze"] = "0 0 0";
    expect_error(j.dump(), kCam + "/Gaze");
    j = sample();
    j["Scene"]["Cameras"]["Camera"]["Up"] = "0 0 0";
    expect_error(j.dump(), kCam + "/Up");
    // Up parallel (and anti-parallel) to the gaze (0, 0, -1): no image orientation.
    for (const char* up : {"0 0 2", "0 0 -1"}) {
        SCOPED_TRACE(up);
        j = sample();
        j["Scene"]["Cameras"]["Camera"]["Up"] = up;
        try {
            parse(j.dump());
            ADD_FAILURE() << "Up parallel to Gaze accepted";
        } catch (const rt::InputError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(kPath + ": ", 0), 0u) << msg;
            EXPECT_TRUE(msg.find(kCam + "/Up") != std::string::npos || msg.find(kCam + "/Gaze") != std::string::npos)
                << msg;
        }
    }
    // lookAt: GazePoint equal to Position.
    j = sample();
    j["Scene"]["Cameras"]["Camera"] = {
        {"_type", "lookAt"}, {"Position", "1 2 3"}, {"GazePoint", "1 2 3"},     {"Up", "0 1 0"},
        {"FovY", "45"},      {"NearDistance", "1"}, {"ImageResolution", "8 8"}, {"ImageName", "a.png"}};
    expect_error(j.dump(), kCam + "/GazePoint");
    // FovY out of range.
    j["Scene"]["Cameras"]["Camera"]["GazePoint"] = "0 0 0";
    j["Scene"]["Cameras"]["Camera"]["FovY"] = "180";
    expect_error(j.dump(), kCam + "/FovY");
    j["Scene"]["Cameras"]["Camera"]["FovY"] = "0";
    expect_error(j.dump(), kCam + "/FovY");
}

TEST(LoaderErrors, VertexIdsOutOfRange) {
    // VertexData has 9 vertices: valid ids are 1..9.
    for (const char* faces : {"3 1 2 1 3 0", "3 1 2 1 3 10", "3 1 2 1 3 -1", "3 1 2 1 3 2.5"}) {
        SCOPED_TRACE(faces);
        json j = sample();
        j["Scene"]["Objects"]["Mesh"]["Faces"]["_data"] = faces;
        expect_error(j.dump(), "/Scene/Objects/Mesh/Faces/_data");
    }
    json j = sample();
    j["Scene"]["Objects"]["Triangle"]["Indices"] = "5 6 10";
    expect_error(j.dump(), "/Scene/Objects/Triangle/Indices");
    j = sample();
    j["Scene"]["Objects"]["Sphere"]["Center"] = "0";
    expect_error(j.dump(), "/Scene/Objects/Sphere/Center");
    j = sample();
    j["Scene"]["Objects"]["Plane"]["Point"] = "10";
    expect_error(j.dump(), "/Scene/Objects/Plane/Point");
}

TEST(LoaderErrors, MaterialIdOutOfRange) {
    json j = sample();
    j["Scene"]["Objects"]["Sphere"]["Material"] = "2";
    expect_error(j.dump(), "/Scene/Objects/Sphere/Material");
    j = sample();
    j["Scene"]["Objects"]["Mesh"]["Material"] = "0";
    expect_error(j.dump(), "/Scene/Objects/Mesh/Material");
    j = sample();
    j["Scene"]["Objects"]["Triangle"].erase("Material");
    expect_error(j.dump(), "/Scene/Objects/Triangle/Material");
}

TEST(LoaderErrors, FaceCountNotMultipleOfThree) {
    json j = sample();
    j["Scene"]["Objects"]["Mesh"]["Faces"]["_data"] = "3 1 2 1 3";
    expect_error(j.dump(), "/Scene/Objects/Mesh/Faces/_data");
    j = sample();
    j["Scene"]["Objects"]["Triangle"]["Indices"] = "5 6";
    expect_error(j.dump(), "/Scene/Objects/Triangle/Indices");
}

TEST(LoaderErrors, SphereRadius) {
    for (const char* r : {"0", "-0.3", "-0"}) {
        SCOPED_TRACE(r);
        json j = sample();
        j["Scene"]["Objects"]["Sphere"]["Radius"] = r;
        expect_error(j.dump(), "/Scene/Objects/Sphere/Radius");
    }
}

TEST(LoaderErrors, UnknownMaterialType) {
    json j = sample();
    j["Scene"]["Materials"]["Material"]["_type"] = "glass";
    expect_error(j.dump(), "/Scene/Materials/Material/_type", "glass");
}

TEST(LoaderErrors, FacesWithoutData) {
    json j = sample();
    j["Scene"]["Objects"]["Mesh"]["Faces"].erase("_data");
    expect_error(j.dump(), "/Scene/Objects/Mesh/Faces");
}

TEST(LoaderErrors, MissingPlyFile) {
    // PLY paths are relative to the scene file's folder.
    json j = sample();
    j["Scene"]["Objects"]["Mesh"]["Faces"] = {{"_plyFile", "meshes/nowhere.ply"}};
    expect_error(j.dump(), "/Scene/Objects/Mesh/Faces", "/nonexistent/rt_loader_test/meshes/nowhere.ply");
}

TEST(LoaderErrors, PlyFilesAreReadAfterTheTreeIsWalked) {
    // describe_scene names the file and leaves it unread (the tree can be released
    // first); read_mesh_files then fails as scene_from_json does, at the same pointer.
    json j = sample();
    j["Scene"]["Objects"]["Mesh"]["Faces"] = {{"_plyFile", "meshes/nowhere.ply"}};
    rt::SceneDesc d = rt::describe_scene(j, kPath);
    ASSERT_FALSE(d.meshes.empty());  // the Mesh, first; the sample's Triangle after it
    EXPECT_EQ(d.meshes[0].ply_pointer, "/Scene/Objects/Mesh/Faces/_plyFile");
    EXPECT_EQ(d.meshes[0].source, "/nonexistent/rt_loader_test/meshes/nowhere.ply");
    EXPECT_TRUE(d.meshes[0].positions.empty());
    std::string two_steps, one_step;
    try {
        rt::read_mesh_files(d);
    } catch (const rt::InputError& e) {
        two_steps = e.what();
    }
    try {
        rt::scene_from_json(j, kPath);
    } catch (const rt::InputError& e) {
        one_step = e.what();
    }
    EXPECT_NE(two_steps.find(kPath + ": /Scene/Objects/Mesh/Faces/_plyFile: "), std::string::npos) << two_steps;
    EXPECT_EQ(two_steps, one_step);
}

TEST(LoaderErrors, NegativeMaxRecursionDepth) {
    json j = sample();
    j["Scene"]["MaxRecursionDepth"] = "-1";
    expect_error(j.dump(), "/Scene/MaxRecursionDepth");
    j["Scene"]["MaxRecursionDepth"] = "2.5";
    expect_error(j.dump(), "/Scene/MaxRecursionDepth");
}

TEST(LoaderErrors, ArrayElementPathsUseZeroBasedIndex) {
    json j = sample();
    json s1 = j["Scene"]["Objects"]["Sphere"];
    json s2 = s1;
    s2["_id"] = "2";
    s2["Radius"] = "-1";
    j["Scene"]["Objects"]["Sphere"] = json::array({s1, s2});
    expect_error(j.dump(), "/Scene/Objects/Sphere/1/Radius");

    j = sample();
    json c1 = j["Scene"]["Cameras"]["Camera"];
    json c0 = c1;
    c0.erase("Position");
    j["Scene"]["Cameras"]["Camera"] = json::array({c0, c1});
    expect_error(j.dump(), "/Scene/Cameras/Camera/0/Position");

    j = sample();
    json m = j["Scene"]["Objects"]["Mesh"];
    json m2 = m;
    m2["Faces"]["_data"] = "1 2 99";
    j["Scene"]["Objects"]["Mesh"] = json::array({m, m, m2});
    expect_error(j.dump(), "/Scene/Objects/Mesh/2/Faces/_data");
}

TEST(LoaderErrors, NegativeColours) {
    json j = sample();
    j["Scene"]["Lights"]["AmbientLight"] = "-1 0 0";
    expect_error(j.dump(), "/Scene/Lights/AmbientLight");
    j = sample();
    j["Scene"]["Materials"]["Material"]["DiffuseReflectance"] = "0.5 -0.5 0.5";
    expect_error(j.dump(), "/Scene/Materials/Material/DiffuseReflectance");
}

}  // namespace
