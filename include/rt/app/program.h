// The raytracer program, once per precision: the Makefile compiles the library twice,
// with Real = double in namespace rt and with Real = float in namespace rt_float
// (docs/precision.md), and main() runs one of the two for the whole run.
#pragma once

namespace rt {
// Parses the command line (--precision included, for --help and its checks), renders or
// traces, and returns the exit status (0 ok, 1 bad input or an image not written, 2 usage).
int raytracer_cli(int argc, char** argv);
}  // namespace rt

// The same function in the float copy (in that copy this redeclares its own rt::raytracer_cli).
namespace rt_float {
int raytracer_cli(int argc, char** argv);
}  // namespace rt_float
