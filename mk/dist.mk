# make dist: raytracer.tar.gz, the submission, which builds on a machine with only g++
# and make:  tar -xf raytracer.tar.gz && make && ./raytracer scene.json
#
# It holds Makefile, mk/, include/, src/, scenes/ and README.md (the files git knows of,
# committed or not, minus ignored ones), plus third_party/: the headers this build uses,
# copied now from the Debian packages (nlohmann/ from nlohmann-json3-dev, CLI/ from
# libcli11-dev, stb/stb_image_write.h and stb/stb_image.h from libstb-dev, tiny_gltf.h from
# libtinygltf-dev, header-only: `make rtconvert` reads and writes glTF with it) with their
# copyright files. The browser page's files (src/web/, include/rt/web/, mk/web.mk) are left
# out: the submission builds ./raytracer, and they would only lengthen its build.
# The Makefile sees third_party/stb/stb_image_write.h and compiles with -Ithird_party
# (src/image/stb_impl.cpp and stb_image_impl.cpp build the stb code there as everywhere);
# libdeflate is not copied: where it is missing, mk/png.mk falls back to stb's own PNG compressor (same
# pixels, larger files, slower writes), and mk/convert.mk leaves out XML scenes and
# ./rtconvert where pugixml and tinyobjloader are missing.
# The repository's own third_party/ is never filled (it is gitignored).
# The tarball also holds mk/tarball.conf (RT_TARBALL := 1, read by the Makefile): there
# plain `make` builds ./raytracer alone, in double precision only (PRECISIONS=double);
# `make PRECISIONS="double float"` adds the float copy, `make rtdiff` the image comparer.
#
# make dist-check: builds the tarball in a fresh folder with the packaged headers and
# libraries hidden (tests/dist/check_dist.sh), times that plain `make` against
# DIST_BUILD_LIMIT seconds, then renders scenes/showcase.json.
# The limit: plain `make` of the tarball takes about 90 s on an idle 2-core
# machine (docs/dist.md); the limit leaves room for a loaded or slower one.
DIST_BUILD_LIMIT ?= 180
DIST_TAR    := raytracer.tar.gz
DIST_STAGE  := build/dist/stage
DIST_FILES   = $(filter-out src/web/% include/rt/web/% mk/web.mk,$(shell \
               if git rev-parse --is-inside-work-tree >/dev/null 2>&1; then \
                   git ls-files -co --exclude-standard -- Makefile README.md mk include src scenes | sort -u; \
               else find Makefile README.md mk include src scenes -type f | sort; fi))
DIST_NLOHMANN := /usr/include/nlohmann
DIST_STB      := /usr/include/stb
DIST_CLI11    := /usr/include/CLI
DIST_TINYGLTF := /usr/include/tiny_gltf.h

.PHONY: dist dist-check
dist:
	@test -f $(DIST_NLOHMANN)/json.hpp || { echo "make dist: $(DIST_NLOHMANN)/json.hpp missing (apt-get install nlohmann-json3-dev)"; exit 1; }
	@test -f $(DIST_CLI11)/CLI.hpp || { echo "make dist: $(DIST_CLI11)/CLI.hpp missing (apt-get install libcli11-dev)"; exit 1; }
	@test -f $(DIST_STB)/stb_image_write.h -a -f $(DIST_STB)/stb_image.h || { echo "make dist: $(DIST_STB)/stb_image*.h missing (apt-get install libstb-dev)"; exit 1; }
	@test -f $(DIST_TINYGLTF) || { echo "make dist: $(DIST_TINYGLTF) missing (apt-get install libtinygltf-dev)"; exit 1; }
	@rm -rf $(DIST_STAGE) && mkdir -p $(DIST_STAGE)/third_party/stb
	@for f in $(DIST_FILES); do [ -f "$$f" ] && { mkdir -p "$(DIST_STAGE)/$$(dirname "$$f")"; cp -p "$$f" "$(DIST_STAGE)/$$f"; }; done; true
	@cp -R $(DIST_NLOHMANN) $(DIST_STAGE)/third_party/nlohmann
	@cp -R $(DIST_CLI11) $(DIST_STAGE)/third_party/CLI
	@cp $(DIST_STB)/stb_image_write.h $(DIST_STB)/stb_image.h $(DIST_STAGE)/third_party/stb/
	@mkdir -p $(DIST_STAGE)/third_party/tinygltf && cp $(DIST_TINYGLTF) $(DIST_STAGE)/third_party/
	@cp /usr/share/doc/nlohmann-json3-dev/copyright $(DIST_STAGE)/third_party/nlohmann/COPYRIGHT 2>/dev/null || true
	@cp /usr/share/doc/libcli11-dev/copyright $(DIST_STAGE)/third_party/CLI/COPYRIGHT 2>/dev/null || true
	@cp /usr/share/doc/libstb-dev/copyright $(DIST_STAGE)/third_party/stb/COPYRIGHT 2>/dev/null || true
	@cp /usr/share/doc/libtinygltf-dev/copyright $(DIST_STAGE)/third_party/tinygltf/COPYRIGHT 2>/dev/null || true
	@{ [ -f third_party/README.md ] && cat third_party/README.md; echo; \
	   echo "Copied by make dist on $$(date -u +%Y-%m-%d) from:"; echo; \
	   dpkg-query -W -f '- $${Package} $${Version}\n' nlohmann-json3-dev libcli11-dev libstb-dev libtinygltf-dev 2>/dev/null || echo "- $(DIST_NLOHMANN), $(DIST_CLI11), $(DIST_STB), $(DIST_TINYGLTF)"; \
	 } > $(DIST_STAGE)/third_party/README.md
	@printf '%s\n' '# Written by make dist: this folder is the submission tarball (docs/dist.md in the' \
	    '# repository). Plain make builds ./raytracer alone, double precision only.' \
	    'RT_TARBALL := 1' > $(DIST_STAGE)/mk/tarball.conf
	@rm -f $(DIST_TAR)
	tar --sort=name --owner=0 --group=0 --numeric-owner -czf $(DIST_TAR) -C $(DIST_STAGE) .
	@echo "$(DIST_TAR): $$(tar -tzf $(DIST_TAR) | grep -vc '/$$') files, $$(du -k $(DIST_TAR) | cut -f1) KiB"

dist-check: dist
	DIST_BUILD_LIMIT=$(DIST_BUILD_LIMIT) sh tests/dist/check_dist.sh $(DIST_TAR)
