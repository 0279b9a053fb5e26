// Helpers of the run pipeline (src/app/run.cpp): the live progress line on a terminal
// and the process figures --stats reports.
#pragma once
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>

namespace rt {
namespace app {

// Peak resident memory of this process so far, in bytes (getrusage).
uint64_t peak_rss_bytes();
uint64_t resident_bytes();  // now (/proc/self/statm); 0 when unknown

// "model name" of the first CPU in /proc/cpuinfo, or "unknown".
std::string cpu_model();

// True when stderr is a terminal.
bool stderr_is_terminal();

// One carriage-return line on stderr: "label: 42% 1.2 s elapsed, ~1.7 s left".
// Does nothing unless enabled; clear() erases it (before the per-image summary line).
class ProgressLine {
public:
    explicit ProgressLine(bool enabled) : enabled_(enabled) {}
    ~ProgressLine() { clear(); }
    ProgressLine(const ProgressLine&) = delete;
    ProgressLine& operator=(const ProgressLine&) = delete;
    bool enabled() const { return enabled_; }
    void start(const std::string& label);
    void update(int done, int total);
    void clear();

private:
    bool enabled_;
    std::string label_;
    std::chrono::steady_clock::time_point t0_;
    size_t shown_ = 0;  // characters on the line now
};

}  // namespace app
}  // namespace rt
