// stb_image's implementation (the PNG reader of the image comparison, rt/image/image_diff.h, which
// ./rtdiff and the tests use; ./raytracer reads no image), compiled here from the header of
// Debian's libstb-dev (or the tarball's third_party/stb/) instead of linking libstb. Apart
// from stb_impl.cpp (the writer), so that building ./raytracer alone does not compile it:
// it is most of the stb code's compile time.
#include "stb_warnings_off.h"

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include "stb_warnings_on.h"
