// Animations (docs/animations.md): several scene files, one per frame, rendered by one
// process with each PLY file parsed and each mesh's BVH built once; --frames and --shard
// split them between processes, here through GNU parallel (Debian's `parallel`), and the
// shards together must be the whole animation, byte for byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "rt/app/run.h"
#include "rt/core/error.h"
#include "rt/scene_build/mesh_cache.h"
#include "test_support.h"

namespace {

TEST(Animation, SelectFramesAndShards) {
    const std::vector<std::string> files = {"f0", "f1", "f2", "f3", "f4", "f5", "f6"};
    using V = std::vector<std::string>;
    EXPECT_EQ(rt::select_frames(files, {}), files);
    EXPECT_EQ(rt::select_frames(files, {2, 4, 0, 1}), (V{"f2", "f3", "f4"}));
    EXPECT_EQ(rt::select_frames(files, {5, SIZE_MAX, 0, 1}), (V{"f5", "f6"}));
    EXPECT_EQ(rt::select_frames(files, {0, SIZE_MAX, 1, 3}), (V{"f1", "f4"}));
    EXPECT_EQ(rt::select_frames(files, {1, 5, 0, 2}), (V{"f1", "f3", "f5"}));  // shards count from A
    EXPECT_EQ(rt::select_frames(files, {0, SIZE_MAX, 6, 9}), (V{"f6"}));
    EXPECT_TRUE(rt::select_frames(files, {0, SIZE_MAX, 7, 9}).empty());
    EXPECT_TRUE(rt::select_frames(files, {9, SIZE_MAX, 0, 1}).empty());
    // The shards of any split are the selection, each frame once.
    for (size_t n = 1; n <= 9; ++n) {
        V all;
        for (size_t k = 0; k < n; ++k)
            for (const std::string& f : rt::select_frames(files, {1, 5, k, n})) all.push_back(f);
        std::sort(all.begin(), all.end());
        EXPECT_EQ(all, (V{"f1", "f2", "f3", "f4", "f5"})) << n << " shards";
    }
}

// An ASCII PLY: a pyramid, or a taller one (`tall`), so that the two contents differ.
std::string pyramid_ply(bool tall) {
    return std::string(
               "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
               "property float z\nelement face 6\nproperty list uchar int vertex_indices\nend_header\n"
               "-1 0 -1\n1 0 -1\n1 0 1\n-1 0 1\n0 ") +
           (tall ? "2" : "1") + " 0\n3 0 2 1\n3 0 3 2\n3 0 1 4\n3 1 2 4\n3 2 3 4\n3 3 0 4\n";
}

TEST(Animation, MeshCacheReadsAFileAgainWhenItsBytesChange) {
    TempDir tmp;
    const std::string ply = tmp / "p.ply";
    write_text(ply, pyramid_ply(false));
    rt::MeshCache cache;
    std::string k1, k2, k3;
    const auto a = cache.ply(ply, k1);
    const auto b = cache.ply(ply, k2);
    EXPECT_EQ(a, b);  // served, not parsed again
    EXPECT_EQ(k1, k2);
    write_text(ply, pyramid_ply(true));
    const auto c = cache.ply(ply, k3);
    EXPECT_NE(k3, k1);
    EXPECT_EQ(c->positions[4].y, 2);
    EXPECT_EQ(a->positions[4].y, 1);
    const rt::MeshCache::Counts n = cache.counts();
    EXPECT_EQ(n.ply_reads, 2u);
    EXPECT_EQ(n.ply_reuses, 1u);
}

// Frame f: the camera turned f * 10 degrees about the pyramids, the second pyramid (an
// instance of the first) turned f * 15 degrees about its own axis, the light moved.
std::string frame_scene(int f) {
    const std::string frame = std::to_string(f);
    return R"({"Scene": {"BackgroundColor": "10 10 30", "MaxRecursionDepth": "2",
      "Transformations": {"Rotation": [{"_id": "1", "_data": ")" +
           std::to_string(10 * f) + R"( 0 1 0"}, {"_id": "2", "_data": ")" + std::to_string(15 * f) +
           R"( 0 1 0"}], "Translation": {"_id": "1", "_data": "2.5 0 0"}},
      "Cameras": {"Camera": {"Position": "0 2 8", "Gaze": "0 -0.2 -1", "Up": "0 1 0", "Transformations": "r1",
        "NearPlane": "-1 1 -1 1", "NearDistance": "2", "ImageResolution": "40 40", "ImageName": "frame_)" +
           frame + R"(.png"}},
      "Lights": {"AmbientLight": "20 20 20", "PointLight": {"Position": "3 5 5", "Intensity": "3000 3000 3000",
        "Transformations": "r2"}},
      "Materials": {"Material": [{"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "0.8 0.5 0.2",
        "SpecularReflectance": "1 1 1", "PhongExponent": "20"},
        {"_id": "2", "_type": "mirror", "AmbientReflectance": "0.1 0.1 0.1", "DiffuseReflectance": "0.2 0.2 0.2",
        "MirrorReflectance": "0.6 0.6 0.6"}]},
      "VertexData": {"_data": "0 -0.01 0", "_type": "xyz"},
      "Objects": {"Mesh": {"_id": "1", "Material": "1", "_shadingMode": "smooth", "Faces": {"_plyFile": "p.ply"}},
                  "MeshInstance": {"_id": "2", "_baseMeshId": "1", "Material": "2", "Transformations": "r2 t1"},
                  "Plane": {"Material": "1", "Point": "1", "Normal": "0 1 0"}}}})";
}

TEST(Animation, ShardsThroughGnuParallelAreTheWholeAnimation) {
    TempDir tmp;
    write_text(tmp / "p.ply", pyramid_ply(false));
    const int frames = 8;
    std::vector<std::string> scenes;
    for (int f = 0; f < frames; ++f) {
        char name[32];
        std::snprintf(name, sizeof name, "frame_%02d.json", f);
        write_text(tmp / name, frame_scene(f));
        scenes.push_back(tmp / name);
    }
    // One process, every frame: each mesh file read once.
    std::vector<std::string> args = {"-o", tmp / "whole"};
    args.insert(args.end(), scenes.begin(), scenes.end());
    const RunResult whole = run_raytracer(args);
    ASSERT_EQ(whole.exit_code, 0) << whole.err;
    EXPECT_TRUE(contains(whole.err,
                         "8 scene files: 1 PLY file read once, then served 7 times; 1 mesh BVH built "
                         "once, then reused 7 times"))
        << whole.err;

    // Three shards through GNU parallel, which must be installed (.ci/run installs it).
    const RunResult which = run_program("/bin/sh", {"-c", "command -v parallel"});
    ASSERT_EQ(which.exit_code, 0) << "GNU parallel is not installed (apt-get install parallel)";
    std::string command = "parallel --will-cite --halt now,fail=1 " + raytracer_path();
    for (const std::string& a : raytracer_args({"-q", "-o", tmp / "shards", "--shard", "{}/3"})) command += " " + a;
    for (const std::string& s : scenes) command += " " + s;
    command += " ::: 0 1 2";
    const RunResult sharded = run_program("/bin/sh", {"-c", command});
    ASSERT_EQ(sharded.exit_code, 0) << command << "\n" << sharded.err;

    // Each frame alone, in a process of its own (no frame shares anything).
    for (const std::string& s : scenes) {
        const RunResult alone = run_raytracer({"-q", "-o", tmp / "alone", s});
        ASSERT_EQ(alone.exit_code, 0) << alone.err;
    }
    const std::vector<std::string> want = list_files(tmp / "whole");
    ASSERT_EQ(want.size(), size_t(frames));
    EXPECT_EQ(list_files(tmp / "shards"), want);
    EXPECT_EQ(list_files(tmp / "alone"), want);
    for (const std::string& f : want) {
        const std::string bytes = read_text(tmp.path() + "/whole/" + f);
        EXPECT_EQ(read_text(tmp.path() + "/shards/" + f), bytes) << f << ": the shards' frame differs";
        EXPECT_EQ(read_text(tmp.path() + "/alone/" + f), bytes) << f << ": the frame rendered alone differs";
    }
    // The frames are not all the same picture.
    EXPECT_NE(read_text(tmp.path() + "/whole/" + want.front()), read_text(tmp.path() + "/whole/" + want.back()));
}

// Frames 0 .. n-1 (frame_<f>.json, drawing p.ply) written into `tmp`; their names in it.
std::vector<std::string> write_frames(const TempDir& tmp, int n) {
    write_text(tmp / "p.ply", pyramid_ply(false));
    std::vector<std::string> names;
    for (int f = 0; f < n; ++f) {
        names.push_back("frame_" + std::to_string(f) + ".json");
        write_text(tmp / names.back(), frame_scene(f));
    }
    return names;
}

TEST(Animation, FramesAndShardOptions) {
    TempDir tmp;
    std::vector<std::string> scenes;
    for (const std::string& name : write_frames(tmp, 4)) scenes.push_back(tmp / name);
    auto run = [&](std::vector<std::string> args) {
        args.insert(args.end(), scenes.begin(), scenes.end());
        return run_raytracer(args);
    };
    const RunResult r = run({"-q", "-o", tmp / "a", "--frames", "1:2"});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(list_files(tmp / "a"), (std::vector<std::string>{"frame_1.png", "frame_2.png"}));
    const RunResult none = run({"-o", tmp / "b", "--shard", "3/5", "--frames", "0:2"});
    EXPECT_EQ(none.exit_code, 0) << none.err;
    EXPECT_EQ(split_lines(none.err),
              std::vector<std::string>{
                  "warning: no frame to render: 4 scene files given, none in this selection (frames 0:2, shard 3/5)"});
    for (const auto& bad : std::vector<std::vector<std::string>>{
             {"--shard", "3/3"}, {"--shard", "1"}, {"--frames", "5:2"}, {"--frames", "x:2"}, {"--shard", "0/0"}}) {
        const RunResult u = run(bad);
        EXPECT_EQ(u.exit_code, 2) << bad[0] << " " << bad[1] << "\n" << u.err;
        EXPECT_TRUE(contains(u.err, bad[0])) << u.err;
    }
}

// A wrong path fails every shard alike, before anything is rendered, whether or not the
// file is among the shard's frames; a shard without a frame warns and succeeds.
TEST(Animation, EveryShardChecksEveryFile) {
    TempDir tmp;
    const std::vector<std::string> scenes = write_frames(tmp, 3);
    const auto run = [&](std::vector<std::string> args, const std::vector<std::string>& files) {
        args.insert(args.end(), files.begin(), files.end());
        return run_raytracer(args, tmp.path());
    };
    std::vector<std::string> with_missing = scenes;
    with_missing.insert(with_missing.begin() + 1, "gone.json");
    for (const char* shard : {"0/4", "1/4", "2/4", "3/4", "5/8"}) {
        SCOPED_TRACE(shard);
        const RunResult r = run({"-q", "-o", "out", "--shard", shard}, with_missing);
        EXPECT_EQ(r.exit_code, 1) << r.err;
        EXPECT_EQ(split_lines(r.err),
                  std::vector<std::string>{"error: gone.json: cannot open: No such file or directory"});
        EXPECT_FALSE(file_exists(tmp / "out")) << "a shard rendered before the check";
    }
    // --frames alone checks too; a folder is not a scene file.
    const RunResult folder = run({"-o", "out", "--frames", "0:0"}, {scenes[0], "."});
    EXPECT_EQ(folder.exit_code, 1) << folder.err;
    EXPECT_EQ(split_lines(folder.err), std::vector<std::string>{"error: .: cannot open: Is a directory"});

    // A pattern the shell matched to nothing, as GNU parallel's shell passes it on.
    const RunResult which = run_program("/bin/sh", {"-c", "command -v parallel"});
    ASSERT_EQ(which.exit_code, 0) << "GNU parallel is not installed (apt-get install parallel)";
    std::string command = "cd " + tmp.path() + " && parallel --will-cite " + raytracer_path();
    for (const std::string& a : raytracer_args({"-o", "out", "--shard", "{}/3"})) command += " " + a;
    command += " 'raven/x/*.json' frame_0.json ::: 0 1 2";
    const RunResult glob = run_program("/bin/sh", {"-c", command});
    EXPECT_EQ(glob.exit_code, 3) << "every one of the 3 shards fails\n" << glob.err;
    const std::string line =
        "error: raven/x/*.json: cannot open: No such file or directory (no file matches this "
        "pattern, so the shell passed it on unexpanded; relative paths start from " +
        tmp.path() + ")";
    EXPECT_EQ(split_lines(glob.err), std::vector<std::string>(3, line)) << glob.err;

    // More shards than frames: the idle shards say so (an error under --strict), the others render.
    const RunResult idle = run({"-o", "out", "--shard", "5/8"}, scenes);
    EXPECT_EQ(idle.exit_code, 0) << idle.err;
    EXPECT_EQ(split_lines(idle.err),
              std::vector<std::string>{
                  "warning: no frame to render: 3 scene files given, none in this selection (frames 0:, shard 5/8)"});
    EXPECT_EQ(run({"-q", "-o", "out", "--shard", "5/8"}, scenes).err, "");
    const RunResult strict = run({"--strict", "-o", "out", "--shard", "5/8"}, scenes);
    EXPECT_EQ(strict.exit_code, 1) << strict.err;
    EXPECT_EQ(split_lines(strict.err),
              std::vector<std::string>{"error: no frame to render: 3 scene files given, none in this selection "
                                       "(frames 0:, shard 5/8); --strict makes it an error"});
    EXPECT_FALSE(file_exists(tmp / "out"));
    const RunResult busy = run({"-q", "-o", "out", "--shard", "2/8"}, scenes);
    EXPECT_EQ(busy.exit_code, 0) << busy.err;
    EXPECT_EQ(list_files(tmp / "out"), std::vector<std::string>{"frame_2.png"});
}

}  // namespace
