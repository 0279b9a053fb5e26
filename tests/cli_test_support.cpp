// The command-line tests' shared helpers (cli_test_support.h).
#include "cli_test_support.h"

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "rt/image/image.h"
#include "test_support.h"

using json = nlohmann::ordered_json;

namespace cli_test {

namespace {

const char* const kSampleScene = R"({
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
        "ImageResolution": "16 16",
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
      "Material": [
        {
          "_id": "1",
          "AmbientReflectance": "1 1 1",
          "DiffuseReflectance": "1 1 1",
          "SpecularReflectance": "1 1 1",
          "PhongExponent": "1"
        },
        {
          "_id": "2",
          "_type": "mirror",
          "AmbientReflectance": "0.1 0.1 0.1",
          "DiffuseReflectance": "0.2 0.2 0.2",
          "SpecularReflectance": "0.5 0.5 0.5",
          "PhongExponent": "10",
          "MirrorReflectance": "0.7 0.7 0.7"
        }
      ]
    },
    "VertexData": {
      "_data": "-0.5 0.5 -2 -0.5 -0.5 -2 0.5 -0.5 -2 0.5 0.5 -2 0.75 0.75 -2 1 0.75 -2 0.875 1 -2 -0.875 1 -2 0 -0.5 0 -0.6 -0.3 -1.5",
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
      "Sphere": [
        {
          "_id": "1",
          "Material": "1",
          "Center": "8",
          "Radius": "0.3"
        },
        {
          "_id": "2",
          "Material": "2",
          "Center": "10",
          "Radius": "0.2"
        }
      ],
      "Plane": {
        "_id": "1",
        "Material": "1",
        "Point": "9",
        "Normal": "0 1 0"
      }
    }
  }
})";

}  // namespace

json sample_scene(const std::string& image, const std::string& resolution) {
    json j = json::parse(kSampleScene);
    j["Scene"]["Cameras"]["Camera"]["ImageName"] = image;
    j["Scene"]["Cameras"]["Camera"]["ImageResolution"] = resolution;
    return j;
}

json with_cameras(json j, const std::vector<std::pair<std::string, std::string>>& cams) {
    json proto = j["Scene"]["Cameras"]["Camera"];
    json arr = json::array();
    int id = 1;
    for (const auto& [name, res] : cams) {
        json c = proto;
        c["_id"] = std::to_string(id++);
        c["ImageName"] = name;
        c["ImageResolution"] = res;
        arr.push_back(c);
    }
    j["Scene"]["Cameras"]["Camera"] = arr;
    return j;
}

void set_at(json& j, const std::string& pointer, const json& value) { j[json::json_pointer(pointer)] = value; }

void erase_at(json& j, const std::string& pointer) {
    json::json_pointer p(pointer);
    j[p.parent_pointer()].erase(p.back());
}

std::string write_scene(const std::string& dir, const std::string& name, const json& j) {
    std::string path = dir + "/" + name;
    write_text(path, j.dump(2) + "\n");
    return path;
}

int count_lines_containing(const std::string& text, const std::string& needle) {
    int n = 0;
    for (const std::string& l : split_lines(text))
        if (contains(l, needle)) ++n;
    return n;
}

std::string dump(const RunResult& r) {
    return "\n--- exit " + std::to_string(r.exit_code) + " --- stderr ---\n" + r.err + "--- stdout ---\n" + r.out +
           "---";
}

std::string join(const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
    return "{" + s + "}";
}

::testing::AssertionResult is_png(const std::string& path, int width, int height) {
    rt::Image img;
    if (!load_png(path, img)) return ::testing::AssertionFailure() << path << " is not a readable PNG";
    if (img.width != width || img.height != height)
        return ::testing::AssertionFailure()
               << path << " is " << img.width << "x" << img.height << ", expected " << width << "x" << height;
    return ::testing::AssertionSuccess();
}

}  // namespace cli_test
