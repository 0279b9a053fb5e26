// ./rtdiff over folders with subfolders, and its manifest mode (--manifest): temporary
// course-like trees with renders that pass, fail, are missing, ambiguous or skipped, and
// malformed manifests.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rt/image/image.h"
#include "rtdiff_test_support.h"
#include "test_support.h"

using namespace rtdiff_test;

TEST_F(RtdiffTool, FoldersMatchImagesInSubfoldersByRelativePath) {
    TempDir a, b;
    for (const TempDir* d : {&a, &b}) {
        create_dirs(*d / "grass");
        create_dirs(*d / "raven/dragon");
    }
    rt::write_png(a_, a / "grass/grass_desert.png");
    rt::write_png(b_, b / "grass/grass_desert.png");
    rt::write_png(a_, a / "raven/dragon/dragon_new.png");
    rt::write_png(a_, b / "raven/dragon/dragon_new.png");
    rt::write_png(a_, a / "grass_desert.png");  // not the same relative path
    const RunResult r = run_program(rtdiff_path(), {"--html", tmp_ / "page", a.path(), b.path()});
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 6u) << r.out;
    EXPECT_EQ(lines[1].rfind("grass/grass_desert.png ", 0), 0u) << r.out;
    EXPECT_TRUE(contains(lines[1], "x 13..13 y 7..7")) << r.out;
    EXPECT_EQ(lines[3].rfind("raven/dragon/dragon_new.png ", 0), 0u) << r.out;
    EXPECT_EQ(lines[4], "1 image only in " + a.path() + " (not compared): grass_desert.png") << r.out;
    EXPECT_EQ(lines[5], "2 compared, 1 only in " + a.path() + ", 0 only in " + b.path()) << r.out;
    // The page's heatmaps keep the subfolders, so names in two subfolders cannot clash.
    EXPECT_TRUE(file_exists(tmp_ / "page/heatmaps/grass/grass_desert.png"));
    EXPECT_TRUE(contains(read_text(tmp_ / "page/index.html"), "src=\"heatmaps/grass/grass_desert.png\""));
}

namespace {

// Every line of `err` is ours: "error: ..." or "warning: ...".
bool only_errors_and_warnings(const std::string& err) {
    for (const std::string& l : split_lines(err))
        if (l.rfind("error: ", 0) != 0 && l.rfind("warning: ", 0) != 0) return false;
    return true;
}

}  // namespace

TEST_F(RtdiffTool, ManifestComparesEachSceneWithItsReference) {
    const ManifestTree t(tmp_.path());
    const rt::Image a = gradient(40, 40);
    rt::Image one = a, many = a;
    at(one, 5, 6, 2) += 9;                                    // 1 of 1600 pixels: 0.0625%, a pass
    for (int x = 0; x < 40; ++x) at(many, x, 20, 0) ^= 0x40;  // 2.5%: over 0.2%
    rt::write_png(a, t.refs + "/pass.png");
    rt::write_png(a, t.refs + "/second.png");
    rt::write_png(a, t.refs + "/fail.png");
    rt::write_png(a, t.refs + "/gone.png");
    rt::write_png(a, t.refs + "/sub/amb.png");
    const std::string out = tmp_ / "out";
    for (const char* d : {"/deep/er", "/x", "/y"}) create_dirs(out + d);
    rt::write_png(a, out + "/pass.png");
    rt::write_png(one, out + "/deep/er/second.png");  // found in a subfolder
    rt::write_png(many, out + "/fail.png");
    rt::write_png(a, out + "/x/amb.png");
    rt::write_png(a, out + "/y/amb.png");
    rt::write_png(a, out + "/inc.png");  // its scene is skipped even so
    const std::string m = t.manifest({
        "pass.json\tpass.png\treferences/hw9/pass.png\tcomplete",
        "cams.json\tsecond.png\treferences/hw9/second.png\tcomplete (a note)",
        "fail.json\tfail.png\treferences/hw9/fail.png\tcomplete",
        "gone.json\tgone.png\treferences/hw9/gone.png\tcomplete",
        "sub/amb.json\tamb.png\treferences/hw9/sub/amb.png\tcomplete",
        "inc.json\tinc.png\treferences/hw9/inc.png\tincomplete: missing inc.ply",
    });
    const RunResult r = run_program(rtdiff_path(), {"--manifest", m, out});
    EXPECT_EQ(r.exit_code, 1) << r.err;  // a FAIL, a missing and an ambiguous image
    const std::vector<std::string> lines = split_lines(r.out);
    ASSERT_EQ(lines.size(), 13u) << r.out;
    // Worst first: the failures, then the passes, then the skipped scenes.
    EXPECT_EQ(lines[1].rfind("FAIL       fail.png  ", 0), 0u) << r.out;
    EXPECT_TRUE(contains(lines[1], "2.5000")) << lines[1];
    EXPECT_EQ(lines[2].rfind("  worst pixel 0,20 off by 64: ", 0), 0u) << r.out;
    EXPECT_EQ(lines[3], "  trace it: ./raytracer --trace 0,20 " + t.scenes + "/fail.json") << r.out;
    EXPECT_EQ(lines[4],
              "missing    gone.png    not in " + out + " or its subfolders (render " + t.scenes + "/gone.json)")
        << r.out;
    EXPECT_EQ(lines[5], "ambiguous  amb.png     2 files under " + out + ": x/amb.png, y/amb.png") << r.out;
    EXPECT_EQ(lines[6].rfind("pass       second.png  ", 0), 0u) << r.out;
    EXPECT_TRUE(contains(lines[6], "0.0625")) << lines[6];
    EXPECT_EQ(lines[7], "  manifest: complete (a note)") << r.out;
    EXPECT_EQ(lines[8].rfind("  worst pixel 5,6 off by 9: ", 0), 0u) << r.out;
    // The scene's second camera writes second.png: the command says so.
    EXPECT_EQ(lines[9], "  trace it: ./raytracer --trace 5,6 --camera 2 " + t.scenes + "/cams.json") << r.out;
    EXPECT_EQ(lines[10].rfind("pass       pass.png  ", 0), 0u) << r.out;  // equal: no worst pixel
    EXPECT_EQ(lines[11], "skipped    inc.png     incomplete: missing inc.ply") << r.out;
    EXPECT_EQ(lines[12],
              "6 scenes: 2 pass, 1 FAIL, 1 missing, 1 ambiguous, 0 error, 1 skipped (inputs incomplete); a pass has "
              "at most 0.2% of its pixels off by more than 1")
        << r.out;
    // fail.json does not exist: a warning that the command is for the first camera.
    EXPECT_TRUE(contains(r.err, "warning: " + t.scenes + "/fail.json: cannot read it")) << r.err;
    EXPECT_TRUE(only_errors_and_warnings(r.err)) << r.err;

    // --fail-above moves the bar; missing and ambiguous images still fail.
    const RunResult loose = run_program(rtdiff_path(), {"--manifest", m, "--fail-above", "3", out});
    EXPECT_EQ(loose.exit_code, 1);
    EXPECT_TRUE(contains(loose.out, "6 scenes: 3 pass, 0 FAIL, 1 missing, 1 ambiguous")) << loose.out;
    // Passes and skipped scenes alone: exit status 0.
    const std::string ok = t.manifest({"pass.json\tpass.png\treferences/hw9/pass.png\tcomplete",
                                       "cams.json\tsecond.png\treferences/hw9/second.png\tcomplete",
                                       "inc.json\tinc.png\treferences/hw9/inc.png\tincomplete: missing inc.ply"});
    const RunResult good = run_program(rtdiff_path(), {"--manifest", ok, out});
    EXPECT_EQ(good.exit_code, 0) << good.out << good.err;
    EXPECT_EQ(good.err, "");
    // The page, inside the renders' folder, twice: its heatmaps are not taken for renders.
    for (int i = 0; i < 2; ++i) {
        const RunResult page = run_program(rtdiff_path(), {"--manifest", ok, "--html", out + "/diff", out});
        EXPECT_EQ(page.exit_code, 0) << page.out << page.err;
    }
    // A later run without --html does not take that page's heatmaps for renders either.
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", ok, out}).exit_code, 0);
    const std::string html = read_text(out + "/diff/index.html");
    EXPECT_TRUE(contains(html, "<th>verdict</th>")) << html;
    EXPECT_TRUE(contains(html, "<td class=l>skipped")) << html;
    EXPECT_TRUE(file_exists(out + "/diff/heatmaps/second.png"));
    for (const std::string& l : attributes(html, "src")) EXPECT_TRUE(file_exists(out + "/diff/" + url_decode(l))) << l;
}

TEST_F(RtdiffTool, ManifestBadInput) {
    const ManifestTree t(tmp_.path());
    const std::string out = tmp_ / "out";
    create_dirs(out);
    // A malformed line: one line on stderr naming the file and the line, nothing compared.
    const std::string m =
        t.manifest({"a.json\ta.png\treferences/hw9/a.png\tcomplete", "b.json\tb.png\tcomplete",
                    "c.json\ta.png\treferences/hw9/c.png\tcomplete", "d.json\td.jpg\treferences/hw9/d.png\tcomplete"});
    const RunResult r = run_program(rtdiff_path(), {"--manifest", m, out});
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(r.err, "error: " + m +
                         ":3: 4 tab-separated columns expected (scene, image, reference, inputs), found 3\n"
                         "error: " +
                         m + ":4: a.png is named on line 2 too\nerror: " + m + ":5: d.jpg: not a .png or .ppm name\n");
    // Every scene skipped: nothing compared, which is no success.
    const std::string skip = t.manifest({"a.json\ta.png\treferences/hw9/a.png\tincomplete: missing a.ply"});
    const RunResult none = run_program(rtdiff_path(), {"--manifest", skip, out});
    EXPECT_EQ(none.exit_code, 1);
    EXPECT_EQ(none.err, "error: " + skip + ": no scene with complete inputs\n");
    // No manifest, no folder, a reference missing.
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", tmp_ / "none.tsv", out}).err,
              "error: " + tmp_ / "none.tsv" + ": cannot open: No such file or directory\n");
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", skip, tmp_ / "nowhere"}).exit_code, 1);
    rt::write_png(a_, out + "/a.png");
    const std::string noref = t.manifest({"a.json\ta.png\treferences/hw9/a.png\tcomplete"});
    const RunResult bad = run_program(rtdiff_path(), {"--manifest", noref, out});
    EXPECT_EQ(bad.exit_code, 1);
    EXPECT_TRUE(contains(bad.out, "error      a.png  " + t.refs + "/a.png: no such file")) << bad.out;
    // Usage errors: a second folder, options of the other modes.
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", noref, out, out}).exit_code, 2);
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", noref}).exit_code, 2);
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", noref, "--scene", "s.json", out}).exit_code, 2);
    EXPECT_EQ(run_program(rtdiff_path(), {"--manifest", noref, "--only-common", out}).exit_code, 2);
}
