// The instruction-set levels ./raytracer holds a copy of the library for (Makefile,
// ISAS; docs/performance.md, "One binary, every CPU"): which of them this CPU executes,
// and which one a run uses. Outside namespace rt, compiled once (like rt/cli/options.h).
#pragma once
#include <string>

namespace rtcli {

// Whether this CPU (and its operating system) executes the copy of level `isa`:
// "x86-64" always; "avx2" with the x86-64-v3 features (AVX2, FMA, BMI1/2, ...);
// "avx512" with the x86-64-v4 ones (AVX-512 F, BW, CD, DQ, VL). Any other name is a
// single copy built for this machine (make MARCH=...): true.
bool cpu_runs(const std::string& isa);

// The known levels this CPU executes, lowest first, space-separated ("x86-64 avx2").
std::string cpu_levels();

// The copy a run uses, of the `built` levels (lowest first): the last the CPU executes
// when `asked` is empty or "auto", else `asked`. Throws std::invalid_argument with the
// reason (a name not built, or a level this CPU does not execute) otherwise.
std::string choose_isa(const std::string& asked, const std::string* built, int count);

}  // namespace rtcli
