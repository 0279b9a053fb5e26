// Helper threads that may fail to start.
#pragma once
#include <system_error>
#include <thread>

namespace rt {

// Starts f on a new thread; when no thread can be started (a resource limit),
// runs f here instead and returns an empty thread: a helper that cannot start
// costs time, never the process (an exception from a thread started by a
// helper thread would end it). Join the result when joinable().
template <class F>
std::thread start_or_run(const F& f) {
    try {
        return std::thread(f);
    } catch (const std::system_error&) {
        f();
        return std::thread();
    }
}

}  // namespace rt
