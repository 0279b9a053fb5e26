// raytracer: runs one copy of the program (rt/app/program.h): the precision --precision
// asks for, built for the instruction-set level --isa (or the environment's RT_ISA) names,
// by default the best this CPU executes (rt/cli/isa.h). The copy parses and checks every
// option, these included. The Makefile says which copies there are: RT_PRIMARY_ISA (in
// namespaces rt and rt_float), RT_WITH_AVX2 and RT_WITH_AVX512; RT_NO_FLOAT (make
// PRECISIONS=double) leaves float out, and --precision float is then refused (exit 2).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>

#include "rt/app/program.h"
#include "rt/cli/isa.h"

#ifndef RT_PRIMARY_ISA
#define RT_PRIMARY_ISA "native"
#endif
#ifdef RT_NO_FLOAT
#define RT_FLOAT_COPY(f) nullptr
#else
#define RT_FLOAT_COPY(f) f
#endif

namespace {

using Program = int (*)(int, char**);
struct Copy {
    std::string isa;
    Program run_double, run_float;
};
const Copy kCopies[] = {
    {RT_PRIMARY_ISA, rt::raytracer_cli, RT_FLOAT_COPY(rt_float::raytracer_cli)},
#ifdef RT_WITH_AVX2
    {"avx2", rt_avx2::raytracer_cli, RT_FLOAT_COPY(rt_float_avx2::raytracer_cli)},
#endif
#ifdef RT_WITH_AVX512
    {"avx512", rt_avx512::raytracer_cli, RT_FLOAT_COPY(rt_float_avx512::raytracer_cli)},
#endif
};
constexpr int kCount = sizeof kCopies / sizeof kCopies[0];

// The value of the last `--name V` or `--name=V` before a "--"; nullopt without one.
// A bad value is left to the copy's parser (precision) or reported below (isa).
std::optional<std::string> last_value(int argc, char** argv, const char* name) {
    const size_t n = std::strlen(name);
    std::optional<std::string> value;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (std::strcmp(a, "--") == 0) break;
        if (std::strcmp(a, name) == 0 && i + 1 < argc)
            value = argv[++i];
        else if (std::strncmp(a, name, n) == 0 && a[n] == '=')
            value = a + n + 1;
    }
    return value;
}

}  // namespace

int main(int argc, char** argv) {
    const std::optional<std::string> option = last_value(argc, argv, "--isa");
    const char* env = std::getenv("RT_ISA");
    const std::string asked = option ? *option : env ? env : "";
    std::string built[kCount];
    for (int i = 0; i < kCount; ++i) built[i] = kCopies[i].isa;
    std::string isa;
    try {
        isa = rtcli::choose_isa(asked, built, kCount);
    } catch (const std::invalid_argument& e) {
        std::fprintf(stderr, "error: %s%s\n", option ? "--isa " : "RT_ISA=", e.what());
        return 2;
    }
    const Copy* copy = kCopies;
    for (const Copy& c : kCopies)
        if (c.isa == isa) copy = &c;
    if (last_value(argc, argv, "--precision") != "float") return copy->run_double(argc, argv);
    if (!copy->run_float) {
        std::fprintf(stderr,
                     "error: --precision float: this build has no float precision; "
                     "build it with make PRECISIONS=\"double float\"\n");
        return 2;
    }
    return copy->run_float(argc, argv);
}
