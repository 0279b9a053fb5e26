// raytracer: runs the double or the float copy of the program (rt/app/program.h), as
// --precision says; that copy parses and checks every option, this one included.
// Built with RT_NO_FLOAT (make PRECISIONS=double), the program holds the double copy only
// and refuses --precision float with one error line, exit status 2 (a usage error).
#include <cstdio>
#include <cstring>

#include "rt/app/program.h"

namespace {

// True when the last --precision on the command line (before a "--") asks for float.
// Anything else, a bad value included, goes to the double copy, whose parser reports it.
bool wants_float(int argc, char** argv) {
    bool f = false;
    for (int i = 1; i < argc; ++i) {
        const char* a = argv[i];
        if (std::strcmp(a, "--") == 0) break;
        if (std::strcmp(a, "--precision") == 0 && i + 1 < argc)
            f = std::strcmp(argv[++i], "float") == 0;
        else if (std::strncmp(a, "--precision=", 12) == 0)
            f = std::strcmp(a + 12, "float") == 0;
    }
    return f;
}

}  // namespace

int main(int argc, char** argv) {
    if (!wants_float(argc, argv)) return rt::raytracer_cli(argc, argv);
#ifdef RT_NO_FLOAT
    std::fprintf(stderr,
                 "error: --precision float: this build has no float precision; "
                 "build it with make PRECISIONS=\"double float\"\n");
    return 2;
#else
    return rt_float::raytracer_cli(argc, argv);
#endif
}
