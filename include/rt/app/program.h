// The raytracer program, once per copy of the library: the Makefile compiles it once per
// precision (Real = double in namespace rt, Real = float in rt_float: docs/precision.md)
// and per instruction-set level (ISAS: the primary level in those namespaces, the others
// in rt_<level> and rt_float_<level>: docs/performance.md), and main() runs one copy for
// the whole run.
#pragma once

// Declares `ns::raytracer_cli`: parses the command line (--precision and --isa included,
// for --help and their checks), renders or traces, and returns the exit status (0 ok, 1
// bad input or an image not written, 2 usage). In a copy whose namespace the Makefile
// renames, RT_PROGRAM(rt) declares that copy's own function.
#define RT_PROGRAM(ns)                        \
    namespace ns {                            \
    int raytracer_cli(int argc, char** argv); \
    }

RT_PROGRAM(rt)
RT_PROGRAM(rt_float)
RT_PROGRAM(rt_avx2)
RT_PROGRAM(rt_float_avx2)
RT_PROGRAM(rt_avx512)
RT_PROGRAM(rt_float_avx512)
