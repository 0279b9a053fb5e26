# make web: the renderer in a browser page (docs/web.md), built with Debian's Emscripten
# (apt-get install emscripten node-acorn libfast-float-dev) into build/web/:
#   index.html, app.js, raytracer.js (the JavaScript API), worker.js, scene_files.js, style.css,
#   rt.js + rt.wasm (the library in both precisions, src/web/web_main.cpp's exports),
#   scenes/ (the bundled scenes of scenes/, with scenes/index.json).
# `python3 -m http.server -d build/web` serves it. The WebAssembly build has no pugixml
# and no libdeflate (RT_NO_XML: XML scenes are refused; the page encodes PNGs itself),
# and no x86 SIMD: WebAssembly SIMD box lanes and scalar triangle tests, the same bytes (docs/exactness.md).
EMCXX       ?= em++
WEB         := build/web
WEB_OBJ     := build/web-obj
# Emscripten's optimiser runs on Node and needs acorn; Debian installs it here.
export NODE_PATH := $(if $(NODE_PATH),$(NODE_PATH):,)/usr/share/nodejs
# WEB_ARCH: target flags: WebAssembly SIMD (the compiler vectorises loops with it; docs/web.md, "Speed").
WEB_ARCH    ?= -msimd128
WEB_CXXFLAGS := $(WEB_ARCH) -O3 -std=c++17 -fexceptions -ffp-contract=off -DRT_NO_XML -DRT_NO_LIBDEFLATE \
                -Iinclude -I$(WEB_OBJ)/include -Wall -Wextra -Wno-unused-command-line-argument
# The packaged headers the library uses, seen without the rest of /usr/include (whose C
# library headers are not Emscripten's).
WEB_HEADERS := nlohmann stb fast_float
WEB_SRC := $(filter-out src/app/% src/cli/% src/convert/% src/tools/% src/image/diff_page.cpp src/web/%,$(LIB_SRC)) \
           src/web/session.cpp
WEB_ONCE := src/image/stb_impl.cpp src/image/stb_image_impl.cpp
WEB_DOUBLE_OBJ := $(WEB_SRC:%.cpp=$(WEB_OBJ)/double/%.o) $(WEB_OBJ)/once/src/web/web_main.o
WEB_FLOAT_OBJ  := $(patsubst %.cpp,$(WEB_OBJ)/float/%.o,$(filter-out $(WEB_ONCE),$(WEB_SRC)))
WEB_EXPORTS := _rtw_load,_rtw_scene,_rtw_render_part,_rtw_refine_part,_rtw_trace,_rtw_compare,_malloc,_free
WEB_LDFLAGS := $(WEB_ARCH) -O3 -fexceptions -sMODULARIZE=1 -sEXPORT_NAME=createRaytracerModule -sALLOW_MEMORY_GROWTH=1 \
               -sMAXIMUM_MEMORY=4GB -sENVIRONMENT=web,worker,node -sEXPORTED_FUNCTIONS=$(WEB_EXPORTS) \
               -sEXPORTED_RUNTIME_METHODS=FS,UTF8ToString,stringToUTF8,lengthBytesUTF8
WEB_ASSETS := index.html app.js raytracer.js worker.js scene_files.js style.css

.PHONY: web
web: $(WEB)/rt.js $(addprefix $(WEB)/,$(WEB_ASSETS)) $(WEB)/scenes/index.json

# Objects are rebuilt when the flags change (WEB_ARCH): they depend on a stamp named after them.
WEB_FLAGS_STAMP := $(WEB_OBJ)/flags-$(shell echo '$(WEB_CXXFLAGS) $(WEB_LDFLAGS)' | md5sum | cut -c1-12)
$(WEB_FLAGS_STAMP):
	@mkdir -p $(@D)
	@rm -f $(WEB_OBJ)/flags-*
	@touch $@

$(WEB_OBJ)/include/.stamp:
	@command -v $(EMCXX) >/dev/null || { echo "make web: $(EMCXX) not found (apt-get install emscripten node-acorn libfast-float-dev)"; exit 1; }
	@mkdir -p $(@D)
	@for h in $(WEB_HEADERS); do [ -d /usr/include/$$h ] || { echo "make web: /usr/include/$$h missing (apt-get install nlohmann-json3-dev libstb-dev libfast-float-dev)"; exit 1; }; ln -sfn /usr/include/$$h $(@D)/$$h; done
	@touch $@

$(WEB_OBJ)/double/%.o: %.cpp $(WEB_OBJ)/include/.stamp $(WEB_FLAGS_STAMP)
	@mkdir -p $(@D)
	$(EMCXX) $(WEB_CXXFLAGS) -MMD -MP -c $< -o $@
$(WEB_OBJ)/float/%.o: %.cpp $(WEB_OBJ)/include/.stamp $(WEB_FLAGS_STAMP)
	@mkdir -p $(@D)
	$(EMCXX) $(WEB_CXXFLAGS) $(FLOAT_CPPFLAGS) -MMD -MP -c $< -o $@
$(WEB_OBJ)/once/%.o: %.cpp $(WEB_OBJ)/include/.stamp $(WEB_FLAGS_STAMP)
	@mkdir -p $(@D)
	$(EMCXX) $(WEB_CXXFLAGS) -MMD -MP -c $< -o $@

$(WEB)/rt.js: $(WEB_DOUBLE_OBJ) $(WEB_FLOAT_OBJ) $(WEB_FLAGS_STAMP)
	@mkdir -p $(@D)
	$(EMCXX) $(WEB_LDFLAGS) $(WEB_DOUBLE_OBJ) $(WEB_FLOAT_OBJ) -o $@

$(WEB)/%: src/web/%
	@mkdir -p $(@D)
	cp $< $@

# The bundled scenes (scenes/*.json and the PLY files they name), and their list.
$(WEB)/scenes/index.json: $(wildcard scenes/*.json) $(shell find scenes -name '*.ply' 2>/dev/null)
	@mkdir -p $(@D)
	python3 src/web/bundle_scenes.py scenes $(@D)

-include $(shell find $(WEB_OBJ) -name '*.d' 2>/dev/null)

# The module under Node and the page in headless Chromium against the native build
# (tests/web/check_web.py; needs chromium, chromium-driver, python3-selenium, ../shared).
.PHONY: check-web
check-web: web raytracer rtdiff
	/usr/bin/python3 tests/web/check_web.py

# The page (one worker) against ./raytracer -j 1, and its time to a first image
# (tests/web/bench_web.py; report in build/bench/web.md).
.PHONY: bench-web
bench-web: web raytracer
	/usr/bin/python3 tests/web/bench_web.py $(BENCH_WEB_ARGS)
