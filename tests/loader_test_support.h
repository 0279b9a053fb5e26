// Shared by the JSON scene loader's tests (tests/test_loader_*.cpp): the spec's sample scene
// and parse_scene on text held in memory, as from a file that does not exist.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "rt/loader/load_scene.h"
#include "rt/loader/scene_desc.h"

namespace loader_test {

using nlohmann::json;

const std::string kPath = "/nonexistent/rt_loader_test/scene.json";

// Section 7 of the assignment, verbatim.
const char* const kSample = R"({
    "Scene": {
        "BackgroundColor": "0 0 0",
        "ShadowRayEpsilon": "1e-3",
        "IntersectionTestEpsilon": "1e-6",
        "Cameras": {
            "Camera": {
                "_id": "1",
                "Position": "0 0 0",
                "Gaze": "0 0 -1",
                "Up": "0 1 0",
                "NearPlane": "-1 1 -1 1",
                "NearDistance": "1",
                "ImageResolution": "800 800",
                "ImageName": "simple.png"
            }
        },
        "Lights": {
            "AmbientLight": "25 25 25",
            "PointLight": {
                "_id": "1",
                "Position": "0 0 0",
                "Intensity": "1000 1000 1000"
            }
        },
        "Materials": {
            "Material": {
                "_id": "1",
                "AmbientReflectance": "1 1 1",
                "DiffuseReflectance": "1 1 1",
                "SpecularReflectance": "1 1 1",
                "PhongExponent": "1"
            }
        },
        "VertexData": {
            "_data": "-0.5 0.5 -2 -0.5 -0.5 -2 0.5 -0.5 -2 0.5 0.5 -2 0.75 0.75 -2 1 0.75 -2 0.875 1 -2 -0.875 1 -2 0 -0.5 0",
            "_type": "xyz"
        },
        "Objects": {
            "Mesh": {
                "_id": "1",
                "Material": "1",
                "Faces": {
                    "_data": "3 1 2 1 3 4",
                    "_type": "triangle"
                }
            },
            "Triangle": {
                "_id": "1",
                "Material": "1",
                "Indices": "5 6 7"
            },
            "Sphere": {
                "_id": "1",
                "Material": "1",
                "Center": "8",
                "Radius": "0.3"
            },
            "Plane": {
                "_id": "1",
                "Material": "1",
                "Point": "9",
                "Normal": "0 1 0"
            }
        }
    }
})";

// `text` parsed as the file kPath; the sample scene as JSON, to edit.
inline rt::SceneDesc parse(const std::string& text) { return rt::parse_scene(text, kPath); }
inline json sample() { return json::parse(kSample); }

}  // namespace loader_test
