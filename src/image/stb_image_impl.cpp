// stb_image's implementation (the PNG reader of the image comparison, rt/image_diff.h, which
// ./rtdiff and the tests use; ./raytracer reads no image), compiled here from the header of
// Debian's libstb-dev (or the tarball's third_party/stb/) instead of linking libstb. Apart
// from stb_impl.cpp (the writer), so that building ./raytracer alone does not compile it:
// it is most of the stb code's compile time.
#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wall"
#pragma GCC diagnostic ignored "-Wextra"
#pragma GCC diagnostic ignored "-Wpedantic"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#endif

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif
