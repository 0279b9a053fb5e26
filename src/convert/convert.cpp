// rtconvert's library side: which conversion a pair of file names asks for, and the
// files each one writes. The conversions themselves: the scene readers of src/loader
// (XML or JSON -> tree, rt/loader/scene_tree.h), xml_writer.cpp (tree -> XML),
// obj_import.cpp, obj_export.cpp and ply_writer.cpp.
#include <filesystem>
#include <string>

#include "gltf_io.h"
#include "rt/convert/convert.h"
#include "rt/core/count_text.h"
#include "rt/core/error.h"
#include "rt/io/atomic_file.h"
#include "rt/io/files.h"
#include "rt/loader/load_scene.h"
#include "rt/loader/scene_tree.h"
#include "scene_import.h"
#include "xml_writer.h"

namespace fs = std::filesystem;

namespace rt {
namespace {

// "3 spheres, 1 plane, ": each kind but triangles, as rtconvert's note counts them.
std::string shape_counts(const SceneDesc& scene) {
    std::string s;
    for_each_shape_desc([&](auto k) {
        using D = decltype(k);
        s += count_of(scene.all<D>().size(), D::kNoun, D::kNouns) + ", ";
    });
    return s;
}

using ojson = nlohmann::ordered_json;

// The folder a file is in, absolute and normalised.
fs::path folder_of(const std::string& path) {
    std::error_code ec;
    fs::path p = fs::absolute(fs::path(path), ec).lexically_normal();
    return p.parent_path();
}

// A relative _plyFile of a scene in `from` made to resolve from `to` instead.
void rewrite_ply_paths(ojson& v, const fs::path& from, const fs::path& to) {
    if (v.is_array()) {
        for (ojson& e : v) rewrite_ply_paths(e, from, to);
    } else if (v.is_object()) {
        for (auto it = v.begin(); it != v.end(); ++it) {
            if (it.key() == "_plyFile" && it->is_string()) {
                const std::string rel = it->get<std::string>();
                if (rel.empty() || rel[0] == '/') continue;
                const fs::path target = (from / rel).lexically_normal();
                fs::path moved = target.lexically_relative(to);
                *it = moved.empty() ? target.string() : moved.string();
            } else {
                rewrite_ply_paths(*it, from, to);
            }
        }
    }
}

std::string tree_text(const ojson& tree, SceneFormat format, const std::string& path) {
    return format == SceneFormat::Xml ? json_tree_to_xml(tree, path) : tree.dump(2) + "\n";
}

// The output must not be the input (it would be overwritten before it is read back).
void check_distinct(const std::string& input, const std::string& output) {
    std::error_code ec;
    if (fs::exists(output, ec) && fs::equivalent(input, output, ec))
        throw InputError(output + ": is the input file; choose another output name");
}

}  // namespace

SceneFormat scene_format_of(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".json") return SceneFormat::Json;
    if (ext == ".xml") return SceneFormat::Xml;
    if (ext == ".obj") return SceneFormat::Obj;
    if (ext == ".gltf" || ext == ".glb") return SceneFormat::Gltf;
    return SceneFormat::Unknown;
}

std::string xml_to_json_text(const std::string& xml_text, const std::string& path) {
    return xml_to_json_tree(xml_text, path).dump(2) + "\n";
}

std::string json_to_xml_text(const std::string& json_text, const std::string& path) {
    return json_tree_to_xml(parse_json_tree<ojson>(json_text, path), path);
}

ConvertResult convert_file(const std::string& input, const std::string& output, const ConvertOptions& options) {
    const SceneFormat from = scene_format_of(input), to = scene_format_of(output);
    if (from == SceneFormat::Unknown)
        throw InputError(input + ": unknown input format (the name must end in .json, .xml, .obj, .gltf or .glb)");
    if (to == SceneFormat::Unknown)
        throw InputError(output + ": unknown output format (the name must end in .json, .xml, .obj, .gltf or .glb)");
    const bool model_in = from == SceneFormat::Obj || from == SceneFormat::Gltf;
    if (model_in && (to == SceneFormat::Obj || to == SceneFormat::Gltf))
        throw InputError(output + ": OBJ and glTF convert to and from scene files (.json, .xml), not to each other");
    check_distinct(input, output);
    ConvertResult result;
    const fs::path out_dir = folder_of(output);
    // Files written beside the output are named as the user named the output (relative
    // when it was), so that the list of written files reads alike.
    const fs::path out_folder = fs::path(output).parent_path();
    const std::string out_stem = fs::path(output).stem().string();

    if (to == SceneFormat::Gltf) {
        const SceneDesc scene = load_scene(input);
        result.warnings = scene.warnings;
        result.written = write_gltf(scene, output, options, result);
        return result;
    }

    if (to == SceneFormat::Obj) {
        SceneDesc scene = load_scene(input);
        result.warnings = scene.warnings;
        const std::string mtl_name = out_stem + ".mtl";
        const ObjText text = scene_to_obj(scene, mtl_name, options.sphere_segments);
        const std::string mtl_path = (out_folder / mtl_name).string();
        write_file_atomic(output, text.obj);
        write_file_atomic(mtl_path, text.mtl);
        result.written = {output, mtl_path};
        size_t triangles = 0;
        for (const MeshDesc& m : scene.meshes) triangles += m.indices.size() / 3;
        result.notes.push_back(count_of(scene.meshes.size(), "mesh", "meshes") + " (" +
                               count_of(triangles, "triangle") + "), " + shape_counts(scene) +
                               count_of(scene.materials.size(), "material"));
        return result;
    }

    if (model_in) {
        ConvertOptions o = options;
        if (o.width < 1 || o.height < 1) throw InputError(output + ": image size must be positive");
        // glTF names each camera's image itself (<stem>.png, or <stem>_<n>.png for several).
        if (o.image_name.empty() && from == SceneFormat::Obj) o.image_name = out_stem + ".png";
        SceneImport imp = from == SceneFormat::Obj ? import_obj(input, o, out_stem) : import_gltf(input, o, out_stem);
        // Never a scene the renderer refuses (its PLY files are checked as they are written).
        try {
            (void)describe_scene(nlohmann::json(imp.scene), output);
        } catch (const InputError& e) {
            throw InputError(input + ": cannot convert: the scene made of it would not load (" + e.what() + ")");
        }
        result.warnings = std::move(imp.warnings);
        result.notes = std::move(imp.notes);
        const std::string text = tree_text(imp.scene, to, output);
        result.written.push_back(output);
        for (const ImportedMesh& m : imp.meshes) {
            const std::string ply_path = (out_folder / m.ply_name).string();
            write_ply(ply_path, m.positions, m.indices);
            result.written.push_back(ply_path);
        }
        write_file_atomic(output, text);  // last, so that a scene file never names missing PLYs
        return result;
    }

    // JSON / XML -> JSON / XML: the tree, with PLY paths following the output.
    const std::string text = read_text_file(input);
    ojson tree = from == SceneFormat::Xml ? xml_to_json_tree(text, input) : parse_json_tree<ojson>(text, input);
    const fs::path in_dir = folder_of(input);
    if (in_dir != out_dir) rewrite_ply_paths(tree, in_dir, out_dir);
    const std::string out_text = tree_text(tree, to, input);
    // Not a check the conversion needs, but worth knowing: would the result render?
    try {
        const SceneDesc scene = scene_from_json(nlohmann::json(tree), output);
        (void)scene;
    } catch (const InputError& e) {
        result.warnings.push_back(std::string(e.what()) + " (converted all the same)");
    }
    write_file_atomic(output, out_text);
    result.written.push_back(output);
    return result;
}

}  // namespace rt
