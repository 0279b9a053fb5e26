// Helper threads: the one way the library starts and joins threads (the mesh
// conversion, the BVH build, the leaf-order copy, the render's tile pool).
#pragma once
#include <system_error>
#include <thread>
#include <utility>

namespace rt {

// Runs f on a new thread beside the caller, joined by join() or at the latest by
// the destructor (so an exception on the calling thread never meets a joinable
// std::thread). When no thread can be started (a resource limit), f runs right
// away on the calling thread instead: a helper that cannot start costs time, never
// the process (an exception from a thread started by a helper thread would end it).
class HelperThread {
public:
    HelperThread() = default;
    template <class F>
    explicit HelperThread(const F& f) {
        try {
            thread_ = std::thread(f);
        } catch (const std::system_error&) {
            f();
        }
    }
    HelperThread(HelperThread&& o) noexcept = default;
    HelperThread& operator=(HelperThread&& o) noexcept {
        join();
        thread_ = std::move(o.thread_);
        return *this;
    }
    ~HelperThread() { join(); }
    void join() {
        if (thread_.joinable()) thread_.join();
    }

private:
    std::thread thread_;
};

// Runs a on a helper thread beside b on this one; both are done on return.
template <class A, class B>
void in_parallel(const A& a, const B& b) {
    HelperThread helper(a);
    b();
}

}  // namespace rt
