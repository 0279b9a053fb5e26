# rtconvert: the scene converter (XML <-> JSON, OBJ + MTL -> JSON + PLY, scene -> OBJ + MTL,
# glTF <-> JSON + PLY).
# XML support is in the library (the renderer reads .xml scenes too), so everything
# links pugixml (libpugixml-dev) and tinyobjloader's double-precision build
# (libtinyobjloader-dev).
#
# Both are optional: where the compiler cannot find a header (the submission tarball of
# `make dist` on a machine with only g++), the library is built without it (RT_NO_XML:
# XML scenes are refused with one error line; RT_NO_OBJ: OBJ import likewise) and
# ./rtconvert is not built. `make RT_HAVE_PUGIXML= RT_HAVE_TINYOBJ=` builds that way here.
# In the submission tarball plain `make` never builds ./rtconvert; `make rtconvert` does,
# where both libraries are found (docs/dist.md). tinygltf is optional too (RT_NO_GLTF).
$(eval $(call optional_library,RT_HAVE_PUGIXML,pugixml.hpp,-lpugixml,RT_NO_XML))
$(eval $(call optional_library,RT_HAVE_TINYOBJ,tiny_obj_loader.h,-ltinyobjloader_double,RT_NO_OBJ))
# glTF: tinygltf (libtinygltf-dev), header-only here (src/convert/gltf_io.cpp compiles its
# code), so nothing to link; without it (RT_NO_GLTF) glTF files are refused with one line.
$(eval $(call optional_library,RT_HAVE_TINYGLTF,tiny_gltf.h,,RT_NO_GLTF))
# The compressed files glTF pipelines write (src/convert/gltf_codecs.h): EXT_meshopt_compression
# through libmeshoptimizer (libmeshoptimizer-dev), KHR_draco_mesh_compression through libdraco
# (libdraco-dev). Without one (the tarball, say), a file that requires it is refused with one
# line naming the extension. Only ./rtconvert and the tests use them (mk/static.mk).
$(eval $(call optional_library,RT_HAVE_MESHOPT,meshoptimizer.h,-lmeshoptimizer,RT_NO_MESHOPT))
$(eval $(call optional_library,RT_HAVE_DRACO,draco/compression/decode.h,-ldraco,RT_NO_DRACO))

ifeq ($(RT_HAVE_PUGIXML)$(RT_HAVE_TINYOBJ),11)
ifndef RT_TARBALL
all: rtconvert
endif
# The converter tests run ./rtconvert.
test: rtconvert
endif
$(eval $(call helper_program,rtconvert,src/convert/convert_main))

# glTF round trips of every complete official scene (tests/gltf/check_gltf.py, docs/gltf.md):
# check-gltf through ./rtconvert alone, byte-identical images, then every export through the
# Khronos glTF Validator and a few through glTF Transform's pipelines (tests/gltf/check_tools.py:
# npm packages pinned by tests/gltf/package-lock.json, installed into build/npm by npm ci,
# Node.js and npm from Debian); check-blender through Debian's
# Blender too (its glTF importer and exporter, headless), within 0.5% of pixels, and a scene
# built in Blender against the same scene written in the course's format. Tables in build/gltf/.
.PHONY: check-gltf check-blender
check-gltf: raytracer rtconvert rtdiff
	/usr/bin/python3 tests/gltf/check_gltf.py
	/usr/bin/python3 tests/gltf/check_tools.py
check-blender: raytracer rtconvert rtdiff
	/usr/bin/python3 tests/gltf/check_gltf.py --blender
