// Helpers shared by the tests: where the course files are, temporary folders,
// running the ./raytracer binary, reading PNGs back and comparing images.
#pragma once
#include <string>
#include <vector>

#include "rt/image/image.h"

// The instruction-set level of the copy of the library these tests were compiled with
// (Makefile, TEST_ISA), which make test has ./raytracer run too (RT_ISA); the sanitized
// builds, outside the Makefile's copies, are "native".
#ifndef RT_ISA_NAME
#define RT_ISA_NAME "native"
#endif

// The course's shared files (scenes, references, spec): $RT_SHARED_DIR when set,
// else ../shared relative to the current directory (tests run from the repo root),
// as an absolute path; empty when the chosen folder does not exist.
std::string shared_dir();

// The message of a test skipped because shared_dir() is empty, after printing it to
// stderr in a banner: a missing shared folder is loud, never a silent pass.
std::string skipped_without_shared(const std::string& what);

// Whether the shared folder must be there: under CI=true (docs/ci.md) a test that needs it
// fails instead of skipping.
bool shared_required();

// At the top of a test that needs the course's files: skips it loudly (a banner on
// stderr, "[  SKIPPED ]" and the summary line's skipped count) when shared_dir() is
// empty, and fails instead under CI=true. A file missing from a shared folder that is
// there is a failure, not a skip.
#define SKIP_UNLESS_SHARED(what)                                                                           \
    do {                                                                                                   \
        if (shared_dir().empty()) {                                                                        \
            const std::string skip_message_ = skipped_without_shared(what);                                \
            if (shared_required()) FAIL() << skip_message_ << " (CI=true: the shared folder is required)"; \
            GTEST_SKIP() << skip_message_;                                                                 \
        }                                                                                                  \
    } while (false)

// A fresh, empty folder in the system's temporary folder (std::filesystem::temp_directory_path,
// $TMPDIR when set; mkdtemp). Throws std::runtime_error on failure.
std::string make_temp_dir();

// A make_temp_dir() folder removed with everything in it when the object dies.
// Set RT_KEEP_TEMP=1 to keep it for inspection.
class TempDir {
public:
    TempDir();
    ~TempDir();
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::string& path() const { return path_; }
    std::string operator/(const std::string& name) const { return path_ + "/" + name; }

private:
    std::string path_;
};

struct RunResult {
    int exit_code = -1;  // WEXITSTATUS, or 128 + signal number when killed by a signal
    std::string out, err;
};

// Runs the repo's ./raytracer (resolved to an absolute path from the directory the
// test program started in) with `args` after raytracer_args' --precision, in `cwd` when given, stdin from /dev/null,
// stdout and stderr captured. A run longer than `timeout_seconds` is killed
// (SIGALRM, exit_code 142). If the binary cannot be executed, exit_code is 127.
RunResult run_raytracer(const std::vector<std::string>& args, const std::string& cwd = "",
                        unsigned timeout_seconds = 120);

// The absolute path run_raytracer executes.
std::string raytracer_path();

// `args` after "--precision" and this test program's precision (the library copy it
// was compiled against: rt/core/real.h), so the CLI tests run the same precision as the rest.
std::vector<std::string> raytracer_args(const std::vector<std::string>& args);

// A file of this repository (e.g. "scenes/showcase.json") found from where the tests
// run: the repo root (make test) or a build folder below it (make check-asan).
// Returns `relative` itself when it is nowhere to be found.
std::string repo_file(const std::string& relative);

// run_raytracer for any program (an absolute path), e.g. rtconvert_path(): the repo's
// ./rtconvert, resolved like raytracer_path().
RunResult run_program(const std::string& exe, const std::vector<std::string>& args, const std::string& cwd = "",
                      unsigned timeout_seconds = 120);
std::string rtconvert_path();
std::string rtdiff_path();  // the repo's ./rtdiff

// Reads a PNG (any channel count) as 8-bit RGB. False when it cannot be read.
bool load_png(const std::string& path, rt::Image& out);

struct ImageDiff {
    int max_diff = 0;       // largest absolute difference of any channel, in levels
    double mean_diff = 0;   // mean absolute difference over all channel values
    double pct_over_1 = 0;  // percentage of pixels with some channel off by more than 1
    double psnr = 0;        // over all channels, dB; +inf when identical
};

// Per-channel comparison of two images of the same size: rt::compare_images at the
// tolerance of 1 level (rt/image/image_diff.h, the measure ./rtdiff prints). Images of different
// sizes compare as totally different: max_diff 256, mean_diff 255, pct_over_1 100, psnr 0.
ImageDiff compare(const rt::Image& a, const rt::Image& b);

// Writes `content` to `path` (truncating). Throws std::runtime_error on failure.
void write_text(const std::string& path, const std::string& content);

// Reads a whole file; throws std::runtime_error when it cannot be read.
std::string read_text(const std::string& path);

// Small file utilities.
bool file_exists(const std::string& path);
std::vector<std::string> split_lines(const std::string& text);  // no trailing empty line
bool contains(const std::string& text, const std::string& part);
// Regular files (and anything else that is not a folder) under `dir`, recursively,
// as sorted paths relative to `dir`.
std::vector<std::string> list_files(const std::string& dir);
