// The converter's command line (./rtconvert): usage and help, bad input as one line that
// writes nothing, and a number overflow reported alike by ./rtconvert and ./raytracer.
#include <gtest/gtest.h>

// A build without pugixml or tinyobjloader (see mk/convert.mk) has none of this to test.
#if !defined(RT_NO_XML) && !defined(RT_NO_OBJ)

#include <filesystem>
#include <string>
#include <vector>

#include "test_support.h"

// ---- The command line ------------------------------------------------------------------

TEST(ConvertCli, UsageAndHelp) {
    RunResult r = run_program(rtconvert_path(), {"--help"});
    EXPECT_EQ(r.exit_code, 0);
    EXPECT_TRUE(contains(r.out, "usage: rtconvert"));
    r = run_program(rtconvert_path(), {"--version"});
    EXPECT_EQ(r.exit_code, 0);
    for (const std::vector<std::string>& args :
         std::vector<std::vector<std::string>>{{},
                                               {"a.xml"},
                                               {"a.xml", "b.json", "c.json"},
                                               {"--bogus", "a.xml", "b.json"},
                                               {"--shading", "wavy", "a.obj", "b.json"},
                                               {"--size", "10", "a.obj", "b.json"},
                                               {"--size"}}) {
        SCOPED_TRACE(::testing::PrintToString(args));
        r = run_program(rtconvert_path(), args);
        EXPECT_EQ(r.exit_code, 2) << r.err;
        EXPECT_TRUE(contains(r.err, "usage: rtconvert")) << r.err;
    }
}

TEST(ConvertCli, BadInputIsOneLineAndWritesNothing) {
    TempDir tmp;
    write_text(tmp / "broken.xml", "<Scene>\n  <Cameras>\n</Scene>\n");
    write_text(tmp / "broken.json", "{\"Scene\": [1, }");
    write_text(tmp / "huge.json", "{\"Scene\": 1e999}");
    write_text(tmp / "ok.json", "{\"Scene\": {}}");
    write_text(tmp / "bad.obj", "v 0 0 0\nf 1 2 3\n");
    // A GLB header (magic, version 2, length 1000) and four bytes of the 988 it promises.
    write_text(tmp / "cut.glb", std::string("glTF\x02\0\0\0\xe8\x03\0\0JSON", 16));
    struct Case {
        std::vector<std::string> args;
        std::string error;
    };
    for (const Case& c : std::vector<Case>{
             {{"broken.xml", "out.json"}, "broken.xml: line 3, column 3: start-end tags mismatch"},
             {{"broken.json", "out.xml"}, "broken.json: parse error at line 1, column 15: "},
             {{"huge.json", "out.xml"},
              "huge.json: line 1, column 11: number overflow parsing '1e999' (not a finite number)"},
             {{"bad.obj", "out.json"},
              "bad.obj: line 2: vertex index out of range in 'f 1 2 3' (the file has 1 vertices)"},
             {{"missing.xml", "out.json"}, "missing.xml: cannot open: No such file or directory"},
             {{"cut.glb", "out.json"}, "cut.glb: truncated: its GLB header says 1000 bytes, the file has 16"},
             {{"ok.json", "out.gltf"}, "ok.json: /Scene/Cameras: required key is missing"},
             {{"ok.json", "out.txt"},
              "out.txt: unknown output format (the name must end in .json, .xml, .obj, .gltf or .glb)"},
             {{"ok.json", "ok.json"}, "ok.json: is the input file; choose another output name"},
             {{"ok.json", "no/such/dir/out.xml"}, "no/such/dir/out.xml: cannot write: No such file or directory"},
         }) {
        SCOPED_TRACE(c.error);
        const RunResult r = run_program(rtconvert_path(), c.args, tmp.path());
        EXPECT_EQ(r.exit_code, 1);
        const std::vector<std::string> lines = split_lines(r.err);
        ASSERT_EQ(lines.size(), 1u) << r.err;
        EXPECT_EQ(lines[0].substr(0, c.error.size() + 7), "error: " + c.error);
        EXPECT_EQ(list_files(tmp.path()), (std::vector<std::string>{"bad.obj", "broken.json", "broken.xml", "cut.glb",
                                                                    "huge.json", "ok.json"}));
    }
}

// One function formats JSON parse errors for both programs (rt/loader/scene_tree.h): a number
// beyond the double range gets the same one-line message, with its line and column,
// from the renderer and from the converter.
TEST(ConvertCli, NumberOverflowIsTheSameMessageInBothPrograms) {
    TempDir tmp;
    write_text(tmp / "huge.json", "{\"Scene\": {\n  \"ShadowRayEpsilon\": 1e999}}\n");
    const std::string expected =
        "error: huge.json: line 2, column 23: number overflow parsing '1e999' (not a finite number)";
    const RunResult render = run_raytracer({"huge.json"}, tmp.path());
    const RunResult convert = run_program(rtconvert_path(), {"huge.json", "out.xml"}, tmp.path());
    for (const RunResult* r : {&render, &convert}) {
        EXPECT_EQ(r->exit_code, 1);
        EXPECT_EQ(split_lines(r->err), std::vector<std::string>{expected}) << r->err;
    }
    EXPECT_EQ(list_files(tmp.path()), std::vector<std::string>{"huge.json"});
}

// What rtconvert prints: counts with their nouns in the singular for one ("1 sphere"), and
// the files written named alike, relative where the output's name is.
TEST(ConvertCli, NotesCountInTheSingularAndWrittenPathsReadAlike) {
    TempDir tmp;
    write_text(tmp / "one.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    std::filesystem::create_directory(tmp / "out");
    const RunResult in = run_program(rtconvert_path(), {"one.obj", "out/one.json"}, tmp.path());
    ASSERT_EQ(in.exit_code, 0) << in.err;
    EXPECT_TRUE(contains(in.err, "1 face (0 polygons fan-split) -> 1 triangle in 1 mesh\n")) << in.err;
    size_t wrote = 0;
    for (const std::string& line : split_lines(in.err))
        if (line.rfind("wrote ", 0) == 0) {
            ++wrote;
            EXPECT_EQ(line.rfind("wrote out/one", 0), 0u) << line << "\n" << in.err;
        }
    EXPECT_EQ(wrote, 2u) << in.err;  // the scene and its PLY file

    write_text(tmp / "k.json", R"({"Scene": {
      "Cameras": {"Camera": {"Position": "0 0 5", "Gaze": "0 0 -1", "Up": "0 1 0", "NearPlane": "-1 1 -1 1",
                             "NearDistance": "1", "ImageResolution": "8 8", "ImageName": "k.png"}},
      "Materials": {"Material": {"AmbientReflectance": "1 1 1"}},
      "VertexData": "-1 -1 0  1 -1 0  0 1 0  0 0 -3",
      "Objects": {"Triangle": {"Material": "1", "Indices": "1 2 3"},
                  "Sphere": {"Material": "1", "Center": "4", "Radius": "0.5"}}}})");
    const RunResult out = run_program(rtconvert_path(), {"k.json", "out/k.obj"}, tmp.path());
    ASSERT_EQ(out.exit_code, 0) << out.err;
    EXPECT_TRUE(contains(out.err, "1 mesh (1 triangle), 1 sphere, 0 instances, 0 planes, 1 material\n")) << out.err;
    EXPECT_TRUE(contains(out.err, "wrote out/k.obj\nwrote out/k.mtl\n")) << out.err;
}

#endif  // !defined(RT_NO_XML) && !defined(RT_NO_OBJ)
