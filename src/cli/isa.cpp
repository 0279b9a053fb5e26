#include "rt/cli/isa.h"

#include <stdexcept>

namespace rtcli {

bool cpu_runs(const std::string& isa) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
#if defined(__clang__)
    // clang (the fuzz and sanitizer builds) does not know the level names: their features.
    const bool v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi") &&
                    __builtin_cpu_supports("bmi2") && __builtin_cpu_supports("popcnt") &&
                    __builtin_cpu_supports("sse4.2");
    if (isa == "avx2") return v3;
    if (isa == "avx512")
        return v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
               __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512dq") &&
               __builtin_cpu_supports("avx512vl");
#else
    if (isa == "avx2") return __builtin_cpu_supports("x86-64-v3");
    if (isa == "avx512") return __builtin_cpu_supports("x86-64-v4");
#endif
#else
    if (isa == "avx2" || isa == "avx512") return false;
#endif
    return true;
}

std::string cpu_levels() {
    std::string s = "x86-64";
    for (const char* isa : {"avx2", "avx512"})
        if (cpu_runs(isa)) s += std::string(" ") + isa;
    return s;
}

std::string choose_isa(const std::string& asked, const std::string* built, int count) {
    if (asked.empty() || asked == "auto") {
        std::string best = built[0];
        for (int i = 1; i < count; ++i)
            if (cpu_runs(built[i])) best = built[i];
        return best;
    }
    std::string names;
    for (int i = 0; i < count; ++i) {
        if (built[i] == asked) {
            if (cpu_runs(asked)) return asked;
            throw std::invalid_argument(asked + ": this CPU does not execute that level's instructions (it runs " +
                                        cpu_levels() + ")");
        }
        names += (i ? ", " : "") + built[i];
    }
    throw std::invalid_argument(asked + ": expected auto or a level this raytracer holds: " + names);
}

}  // namespace rtcli
