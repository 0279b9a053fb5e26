# ./raytracer is linked statically where it can be (docs/performance.md, "static linking"):
# each run then skips the dynamic loader's work for libstdc++, libm, libpugixml and
# libdeflate, about 4 ms a run, which the 19 official scene files pay 19 times. A probe
# links an empty program with -static and ./raytracer's libraries; without their static
# archives (the tarball on a machine with only g++, say) it is linked dynamically, as
# before. A static libc still picks its memcpy and the like for the CPU it runs on
# (IFUNC), so the binary runs on any x86-64 CPU either way (mk/march.mk checks it).
# `make RT_STATIC=` links dynamically. Included after mk/convert.mk and mk/png.mk, which
# add the libraries.

# ./raytracer reads no OBJ or glTF file (rtconvert does): tinyobjloader and libmeshoptimizer,
# which Debian packages without a static archive, and libdraco are not linked into it.
RAYTRACER_LDLIBS := $(filter-out -ltinyobjloader_double -lmeshoptimizer -ldraco,$(LDLIBS))
ifeq ($(origin RT_STATIC),undefined)
  RT_STATIC := $(shell printf 'int main() {}\n' | $(CXX) -x c++ - -static -o /dev/null $(RAYTRACER_LDLIBS) \
                 2>/dev/null && echo -static)
endif
