# PNG compression: src/image/stb_impl.cpp hands stb_image_write's zlib stream to
# libdeflate (libdeflate-dev) when the compiler finds <libdeflate.h>; otherwise (the
# submission tarball of `make dist` on a machine with only g++) it is built with
# RT_NO_LIBDEFLATE and stb's own compressor. Same pixels either way, different bytes.
# `make RT_HAVE_LIBDEFLATE=` builds without it here.
$(eval $(call optional_library,RT_HAVE_LIBDEFLATE,libdeflate.h,-ldeflate,RT_NO_LIBDEFLATE))
