#include "test_support.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "rt/core/error.h"
#include "rt/image/image_diff.h"

namespace fs = std::filesystem;

namespace {

std::string current_dir() {
    std::error_code ec;
    fs::path p = fs::current_path(ec);
    return ec ? std::string(".") : p.string();
}

// The directory the test program started in (the repo root under `make test`),
// captured before any test can change directories.
const std::string g_start_dir = current_dir();

bool is_dir(const std::string& path) {
    std::error_code ec;
    return fs::is_directory(path, ec);
}

std::string absolute_of(const std::string& path) {
    std::error_code ec;
    fs::path p = fs::weakly_canonical(fs::absolute(path, ec), ec);
    return ec ? path : p.string();
}

}  // namespace

std::string shared_dir() {
    const char* env = std::getenv("RT_SHARED_DIR");
    std::string dir = (env && *env) ? std::string(env) : std::string("../shared");
    if (!is_dir(dir)) return "";
    return absolute_of(dir);
}

std::string skipped_without_shared(const std::string& what) {
    const std::string msg =
        "SKIPPED: the course's shared folder was not found (set RT_SHARED_DIR); " + what + " not tested";
    std::fprintf(stderr, "\n*** %s ***\n\n", msg.c_str());
    std::fflush(stderr);
    return msg;
}

bool shared_required() {
    const char* ci = std::getenv("CI");
    return ci && std::string(ci) == "true";
}

std::string make_temp_dir() {
    std::error_code ec;
    const fs::path base = fs::temp_directory_path(ec);
    std::string tmpl = (ec ? fs::path(".") : base).string() + "/rt_test_XXXXXX";
    if (!mkdtemp(tmpl.data())) throw std::runtime_error(std::string("mkdtemp: ") + std::strerror(errno));
    return tmpl;
}

TempDir::TempDir() : path_(make_temp_dir()) {}

TempDir::~TempDir() {
    const char* keep = std::getenv("RT_KEEP_TEMP");
    if (keep && *keep && std::string(keep) != "0") return;
    std::error_code ec;
    fs::remove_all(path_, ec);
}

std::string raytracer_path() { return g_start_dir + "/raytracer"; }

std::string repo_file(const std::string& relative) {
    for (const char* up : {"/", "/../", "/../../"}) {
        const std::string p = g_start_dir + up + relative;
        if (file_exists(p)) return p;
    }
    return relative;
}

std::vector<std::string> raytracer_args(const std::vector<std::string>& args) {
    std::vector<std::string> all = {"--precision", rt::kPrecisionName};
    all.insert(all.end(), args.begin(), args.end());
    return all;
}

RunResult run_raytracer(const std::vector<std::string>& args, const std::string& cwd, unsigned timeout_seconds) {
    return run_program(raytracer_path(), raytracer_args(args), cwd, timeout_seconds);
}

std::string rtconvert_path() { return g_start_dir + "/rtconvert"; }

std::string rtdiff_path() { return g_start_dir + "/rtdiff"; }

RunResult run_program(const std::string& exe, const std::vector<std::string>& args, const std::string& cwd,
                      unsigned timeout_seconds) {
    RunResult result;
    TempDir capture;
    const std::string out_path = capture / "stdout";
    const std::string err_path = capture / "stderr";

    // Everything the child needs is prepared before fork: only async-signal-safe
    // calls happen between fork and exec.
    std::vector<std::string> argv_storage;
    argv_storage.push_back(exe);
    argv_storage.insert(argv_storage.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (std::string& a : argv_storage) argv.push_back(a.data());
    argv.push_back(nullptr);

    int out_fd = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    int err_fd = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
    int in_fd = open("/dev/null", O_RDONLY | O_CLOEXEC);
    if (out_fd < 0 || err_fd < 0 || in_fd < 0) {
        result.err = std::string("run_raytracer: cannot open capture files: ") + std::strerror(errno);
        if (out_fd >= 0) close(out_fd);
        if (err_fd >= 0) close(err_fd);
        if (in_fd >= 0) close(in_fd);
        return result;
    }

    pid_t pid = fork();
    if (pid == 0) {
        if (dup2(in_fd, 0) < 0 || dup2(out_fd, 1) < 0 || dup2(err_fd, 2) < 0) _exit(127);
        if (!cwd.empty() && chdir(cwd.c_str()) != 0) {
            const char msg[] = "run_raytracer: chdir failed\n";
            ssize_t ignored = write(2, msg, sizeof msg - 1);
            (void)ignored;
            _exit(127);
        }
        alarm(timeout_seconds);  // survives exec: a hung renderer dies of SIGALRM
        execv(exe.c_str(), argv.data());
        const char msg[] = "run_program: cannot execute the program\n";
        ssize_t ignored = write(2, msg, sizeof msg - 1);
        (void)ignored;
        _exit(127);
    }
    close(out_fd);
    close(err_fd);
    close(in_fd);
    if (pid < 0) {
        result.err = std::string("run_raytracer: fork failed: ") + std::strerror(errno);
        return result;
    }

    int status = 0;
    while (waitpid(pid, &status, 0) < 0) {
        if (errno != EINTR) {
            result.err = std::string("run_raytracer: waitpid failed: ") + std::strerror(errno);
            return result;
        }
    }
    if (WIFEXITED(status))
        result.exit_code = WEXITSTATUS(status);
    else if (WIFSIGNALED(status))
        result.exit_code = 128 + WTERMSIG(status);

    try {
        result.out = read_text(out_path);
        result.err = read_text(err_path);
    } catch (const std::exception& e) {
        result.err += e.what();
    }
    return result;
}

bool load_png(const std::string& path, rt::Image& out) {
    try {
        out = rt::read_image(path);  // the library's reader, as ./rtdiff uses
        return true;
    } catch (const rt::InputError&) {
        return false;
    }
}

ImageDiff compare(const rt::Image& a, const rt::Image& b) {
    const rt::ImageComparison c = rt::compare_images(a, b, 1);
    ImageDiff d;
    d.max_diff = c.max_diff;
    d.mean_diff = c.mean_diff;
    d.pct_over_1 = c.pct_over;
    d.psnr = c.psnr;
    return d;
}

void write_text(const std::string& path, const std::string& content) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error("write_text: cannot open " + path);
    f.write(content.data(), std::streamsize(content.size()));
    f.close();
    if (!f) throw std::runtime_error("write_text: cannot write " + path);
}

std::string read_text(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("read_text: cannot open " + path);
    std::ostringstream ss;
    ss << f.rdbuf();
    return ss.str();
}

bool file_exists(const std::string& path) {
    std::error_code ec;
    return fs::exists(fs::symlink_status(path, ec));
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find('\n', start);
        if (end == std::string::npos) end = text.size();
        lines.push_back(text.substr(start, end - start));
        start = end + 1;
    }
    return lines;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

std::vector<std::string> list_files(const std::string& dir) {
    std::vector<std::string> files;
    std::error_code ec;
    if (!is_dir(dir)) return files;
    for (auto it = fs::recursive_directory_iterator(dir, ec); !ec && it != fs::recursive_directory_iterator();
         it.increment(ec)) {
        std::error_code ec2;
        if (it->is_directory(ec2)) continue;
        files.push_back(fs::relative(it->path(), dir, ec2).string());
    }
    std::sort(files.begin(), files.end());
    return files;
}
