// The scene loader's entry points (rt/loader/load_scene.h): the file's name picks the reader
// (JSON or the course's XML), each reader produces the same JSON tree
// (rt/loader/scene_tree.h), and scene_from_json turns that tree into a SceneDesc.
#include "rt/loader/load_scene.h"
#include "rt/io/files.h"
#include "rt/io/memory.h"
#include "rt/loader/scene_tree.h"

namespace rt {

bool is_xml_path(const std::string& path) { return lower_extension(path) == ".xml"; }

SceneDesc parse_scene(const std::string& json_text, const std::string& path, PlyCache* meshes) {
    return scene_from_json(parse_json_tree<nlohmann::json>(json_text, path), path, meshes);
}

SceneDesc parse_scene_xml(const std::string& xml_text, const std::string& path, PlyCache* meshes) {
    return scene_from_json(nlohmann::json(xml_to_json_tree(xml_text, path)), path, meshes);
}

SceneDesc load_scene(const std::string& path, PlyCache* meshes) {
    // The text is released once parsed, and the tree once walked: neither is needed
    // while the meshes are read and their BVHs built (the peak of a large scene's load).
    SceneDesc desc;
    {
        nlohmann::json tree;
        {
            const std::string text = read_text_file(path);
            tree = is_xml_path(path) ? nlohmann::json(xml_to_json_tree(text, path))
                                     : parse_json_tree<nlohmann::json>(text, path);
        }
        desc = describe_scene(tree, path, meshes);
    }
    release_free_memory();
    read_mesh_files(desc, meshes);
    return desc;
}

}  // namespace rt
