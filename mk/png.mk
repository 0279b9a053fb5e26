# PNG compression: src/image/stb_impl.cpp hands stb_image_write's zlib stream to
# libdeflate (libdeflate-dev) when the compiler finds <libdeflate.h>; otherwise (the
# submission tarball of `make dist` on a machine with only g++) it is built with
# RT_NO_LIBDEFLATE and stb's own compressor. Same pixels either way, different bytes.
# `make RT_HAVE_LIBDEFLATE=` builds without it here.
ifeq ($(origin RT_HAVE_LIBDEFLATE),undefined)
  RT_HAVE_LIBDEFLATE := $(shell printf '\043include <libdeflate.h>\n' | $(CXX) -x c++ -E -o /dev/null - 2>/dev/null && echo 1)
endif
ifeq ($(RT_HAVE_LIBDEFLATE),1)
  override LDLIBS += -ldeflate
else
  override CPPFLAGS += -DRT_NO_LIBDEFLATE
endif
