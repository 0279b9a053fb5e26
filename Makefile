# raytracer: a recursive (Whitted) ray tracer for the CENG 795 JSON scene format.
#   make            build ./raytracer
#   make test       build and run the unit, property and conformance tests, once for each
#                   precision (double, then float: ./raytracer --precision float)
#   make CXXFLAGS="-O2 -g"  choose optimisation and debug flags; the flags below that the
#                           code needs are appended to any CXXFLAGS, CPPFLAGS or LDLIBS
#                           given on the command line (override), never replaced
#   make MARCH=x86-64       build for baseline x86-64 (no AVX: the scalar kernels) in its own
#                           object folder; the default MARCH=native uses this CPU's SIMD
#   make PRECISIONS=double  build ./raytracer without its float copy (half the compiling;
#                           --precision float then exits with an error); the default is
#                           "double float", except in the submission tarball (docs/dist.md)
CXX      ?= g++
MARCH    ?= native
CXXFLAGS ?= -O3 -march=$(MARCH)
# No fused multiply-add contraction: the watertight triangle test needs its edge
# functions evaluated exactly alike for both triangles sharing an edge, which
# contraction breaks (rays slipped through the diagonal of simple.json's quad).
# Appended last, so it wins over a -ffp-contract in the user's CXXFLAGS.
override CXXFLAGS += -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -Wswitch-enum -Werror=switch-enum -MMD -MP -ffp-contract=off
override CPPFLAGS += -Iinclude
override LDLIBS   += -lpthread

# Headers packaged in the submission tarball (make dist) live in third_party/;
# on a Debian machine they come from nlohmann-json3-dev and libstb-dev. The stb code is
# compiled in (src/image/stb_impl.cpp, see mk/png.mk), never linked from libstb.
ifneq ($(wildcard third_party/stb/stb_image_write.h),)
  override CPPFLAGS += -Ithird_party
endif

# The submission tarball (make dist, docs/dist.md) holds mk/tarball.conf, which sets
# RT_TARBALL := 1: there plain `make` builds ./raytracer alone, in double precision only.
-include mk/tarball.conf

# The precisions ./raytracer holds: "double float" (both copies of the library, below) or
# "double" (one copy, half the compiling). The tests of a precision need it (TEST_PRECISIONS).
PRECISIONS ?= $(if $(RT_TARBALL),double,double float)
ifneq ($(sort $(PRECISIONS)),$(sort double $(filter float,$(PRECISIONS))))
  $(error PRECISIONS="$(PRECISIONS)": double, or double float)
endif
RT_FLOAT := $(filter float,$(PRECISIONS))

# PRECISION=float once built a second, single-precision program; ./raytracer now holds the
# precisions PRECISIONS names.
ifdef PRECISION
  $(warning PRECISION=$(PRECISION) is ignored: one ./raytracer renders the precisions of PRECISIONS, see --precision)
endif

# Objects live in build/<target>: build/native by default, build/x86-64 for MARCH=x86-64.
BUILD := build/$(MARCH)

# One program, both precisions (docs/precision.md). The library is compiled twice: as
# written, with Real = double, in namespace rt (objects in $(BUILD)/src); and, when
# PRECISIONS has float, with Real = float (-DRT_REAL_FLOAT), every token `rt` renamed
# rt_float (objects in $(BUILD)/float/src), so that both copies link into one program without
# a clash. main.cpp picks one copy per run (--precision); nothing else branches on the
# precision. The only code outside namespace rt, compiled once, in the double copy: stb's
# (stb_impl.cpp, the writer; stb_image_impl.cpp, the reader) and the command-line helpers
# (namespace rtcli, cli/options.cpp) and tinygltf's (namespace rtgltf, convert/gltf_io.cpp),
# which do not use Real.
FLOAT_CPPFLAGS := -DRT_REAL_FLOAT -Drt=rt_float
ONCE_SRC := src/image/stb_impl.cpp src/image/stb_image_impl.cpp src/cli/options.cpp src/convert/gltf_io.cpp

# Every src/**/*.cpp is library code except program entry points (main.cpp, *_main.cpp).
# The library is two archives per precision: librt.a, what ./raytracer links, and
# librt_tools.a, the code only the helper programs and the tests use (TOOL_SRC: the scene
# converter, the image comparison, its heatmap and its PNG reader), so that building
# ./raytracer alone compiles none of it. The float tools' few references to stb's reader
# are resolved by the double librt_tools.a.
LIB_SRC  := $(filter-out src/main.cpp %_main.cpp,$(shell find src -name '*.cpp' | sort))
TOOL_SRC := $(filter src/convert/% src/image/image_diff.cpp src/image/diff_page.cpp src/image/diff_heatmap.cpp \
                      src/image/bitmap_font.cpp src/image/stb_image_impl.cpp,$(LIB_SRC))
LIB_OBJ  := $(LIB_SRC:%.cpp=$(BUILD)/%.o)
LIB_FLOAT_OBJ := $(patsubst %.cpp,$(BUILD)/float/%.o,$(filter-out $(ONCE_SRC),$(LIB_SRC)))
TOOL_OBJ := $(TOOL_SRC:%.cpp=$(BUILD)/%.o)
TOOL_FLOAT_OBJ := $(patsubst %.cpp,$(BUILD)/float/%.o,$(filter-out $(ONCE_SRC),$(TOOL_SRC)))
RENDER_OBJ := $(filter-out $(TOOL_OBJ),$(LIB_OBJ))
RENDER_FLOAT_OBJ := $(filter-out $(TOOL_FLOAT_OBJ),$(LIB_FLOAT_OBJ))
# The test programs are built from tests/*.cpp only; subfolders (fuzz targets, benchmarks)
# have their own rules. The same tests run against each precision's library.
TEST_SRC := $(sort $(wildcard tests/*.cpp))
TEST_OBJ := $(TEST_SRC:%.cpp=$(BUILD)/%.o)
TEST_FLOAT_OBJ := $(TEST_SRC:%.cpp=$(BUILD)/float/%.o)
# The test programs' own code is compiled at TEST_OPT (after CXXFLAGS, so it wins): it
# compiles in about 60% of -O3's time, and CI builds four copies (docs/ci.md). The library
# they test keeps CXXFLAGS. `make TEST_OPT=` compiles the tests with CXXFLAGS alone.
TEST_OPT ?= -O1
# Each test file starts with tests/test_pch.h (GoogleTest, nlohmann/json), precompiled
# once per object folder with the test files' own flags (test_pch, below).
TEST_PCH       := $(BUILD)/pch/test_pch.h
TEST_FLOAT_PCH := $(BUILD)/float/pch/test_pch.h

.PHONY: all test unit clean
all: raytracer

# build/target names the object folder ./raytracer was last linked from, how (static or
# not, mk/static.mk) and with which precisions; it changes (and forces a relink) only when
# MARCH, RT_STATIC or PRECISIONS does.
build/target: FORCE
	@mkdir -p build
	@echo '$(BUILD) $(RT_STATIC) $(PRECISIONS)' | cmp -s - $@ || echo '$(BUILD) $(RT_STATIC) $(PRECISIONS)' > $@

# $(BUILD)/config holds the compile and link lines of this configuration (compiler, flags,
# optional libraries found or not: see mk/convert.mk); it changes only when they do, and
# every object and program of $(BUILD) depends on it, so a change of configuration
# rebuilds what it affects instead of mixing objects of two configurations.
$(BUILD)/config: FORCE
	@mkdir -p $(BUILD)
	@printf '%s\n' '$(CXX) $(CPPFLAGS) $(CXXFLAGS)' '$(LDLIBS)' 'tests: $(TEST_OPT)' | cmp -s - $@ || \
	    printf '%s\n' '$(CXX) $(CPPFLAGS) $(CXXFLAGS)' '$(LDLIBS)' 'tests: $(TEST_OPT)' > $@

# The float library first: its few references to stb are resolved by librt.a after it.
# Without float, main.cpp is compiled with RT_NO_FLOAT (main-double.o) and refuses
# --precision float. Linked statically where the static libraries are at hand (mk/static.mk).
MAIN_OBJ := $(BUILD)/src/main$(if $(RT_FLOAT),,-double).o
raytracer: $(MAIN_OBJ) $(if $(RT_FLOAT),$(BUILD)/librt_float.a) $(BUILD)/librt.a build/target $(BUILD)/config
	$(CXX) $(CXXFLAGS) $(RT_STATIC) -o $@ $(filter-out build/target $(BUILD)/config,$^) $(RAYTRACER_LDLIBS)

$(BUILD)/src/main-double.o: src/main.cpp $(BUILD)/config
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) -DRT_NO_FLOAT $(CXXFLAGS) -c $< -o $@

.PHONY: FORCE
FORCE:

$(BUILD)/librt.a: $(RENDER_OBJ)
$(BUILD)/librt_tools.a: $(TOOL_OBJ)
$(BUILD)/librt_float.a: $(RENDER_FLOAT_OBJ)
$(BUILD)/librt_float_tools.a: $(TOOL_FLOAT_OBJ)

# Every archive (these and mk/*.mk's) is its objects, remade whole: ar would keep the
# members of sources since removed.
%.a:
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/%.o: %.cpp $(BUILD)/config
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

# Make prefers this rule to the one above for $(BUILD)/float/... (the shorter stem).
$(BUILD)/float/%.o: %.cpp $(BUILD)/config
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(FLOAT_CPPFLAGS) $(CXXFLAGS) -c $< -o $@

# test_pch(header, compile command without -c/-o): the test files' precompiled header at
# <header>.gch, beside a copy of tests/test_pch.h (g++ takes the .gch when the flags match
# and falls back to the copy otherwise).
define test_pch
	@mkdir -p $(dir $(1))
	cp tests/test_pch.h $(1)
	$(2) -x c++-header $(1) -o $(1).gch
endef

# The test files: rules with shorter stems than the two above, so make prefers them.
$(TEST_PCH).gch: tests/test_pch.h $(BUILD)/config
	$(call test_pch,$(TEST_PCH),$(CXX) $(CPPFLAGS) $(CXXFLAGS) $(TEST_OPT))

$(TEST_FLOAT_PCH).gch: tests/test_pch.h $(BUILD)/config
	$(call test_pch,$(TEST_FLOAT_PCH),$(CXX) $(CPPFLAGS) $(FLOAT_CPPFLAGS) $(CXXFLAGS) $(TEST_OPT))

$(BUILD)/tests/%.o: tests/%.cpp $(TEST_PCH).gch $(BUILD)/config
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) $(TEST_OPT) -include $(TEST_PCH) -c $< -o $@

$(BUILD)/float/tests/%.o: tests/%.cpp $(TEST_FLOAT_PCH).gch $(BUILD)/config
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(FLOAT_CPPFLAGS) $(CXXFLAGS) $(TEST_OPT) -include $(TEST_FLOAT_PCH) -c $< -o $@

$(BUILD)/rt_tests: $(TEST_OBJ) $(BUILD)/librt_tools.a $(BUILD)/librt.a $(BUILD)/config
	$(CXX) $(CXXFLAGS) -o $@ $(filter-out $(BUILD)/config,$^) -lgtest $(LDLIBS)

$(BUILD)/rt_tests_float: $(TEST_FLOAT_OBJ) $(BUILD)/librt_float_tools.a $(BUILD)/librt_float.a \
                         $(BUILD)/librt_tools.a $(BUILD)/librt.a $(BUILD)/config
	$(CXX) $(CXXFLAGS) -o $@ $(filter-out $(BUILD)/config,$^) -lgtest $(LDLIBS)

# Tests read the course files from ../shared (or $$RT_SHARED_DIR); the CLI tests
# run ./raytracer (with --precision of the suite's own), so it is built first.
# TEST_PRECISIONS=float runs one suite only; it defaults to the precisions ./raytracer holds.
TEST_PRECISIONS ?= $(PRECISIONS)
ifeq ($(filter float,$(TEST_PRECISIONS)):$(RT_FLOAT),float:)
  $(error TEST_PRECISIONS has float, PRECISIONS not: the float tests run ./raytracer --precision float)
endif
test: raytracer $(if $(filter double,$(TEST_PRECISIONS)),$(BUILD)/rt_tests) \
                $(if $(filter float,$(TEST_PRECISIONS)),$(BUILD)/rt_tests_float)
	$(if $(filter double,$(TEST_PRECISIONS)),@echo "== the tests in double precision" && $(BUILD)/rt_tests)
	$(if $(filter float,$(TEST_PRECISIONS)),@echo "== the tests in float precision" && $(BUILD)/rt_tests_float)

clean:
	rm -rf build raytracer

# $(eval $(call optional_library,VAR,HEADER,LDLIBS,MACRO)): an optional library. VAR is 1 when
# the compiler finds <HEADER> (asked once; `make VAR=` builds without it), and then LDLIBS are
# linked; otherwise the code is compiled with -DMACRO and does without (mk/convert.mk, mk/png.mk).
define optional_library
ifeq ($$(origin $(1)),undefined)
  $(1) := $$(shell printf '\043include <$(2)>\n' | $$(CXX) $$(CPPFLAGS) -x c++ -E -o /dev/null - 2>/dev/null && echo 1)
endif
ifeq ($$($(1)),1)
  override LDLIBS += $(3)
else
  override CPPFLAGS += -D$(4)
endif
endef

# $(eval $(call helper_program,NAME,MAIN)): a program beside ./raytracer (rtconvert, rtdiff):
# NAME linked from $(BUILD)/MAIN.o and the library, `make clean` removes it, and the tests
# under the sanitizers (check-asan, mk/check.mk, included before it) get a sanitized NAME too.
define helper_program
$(1): $$(BUILD)/$(2).o $$(BUILD)/librt_tools.a $$(BUILD)/librt.a build/target $$(BUILD)/config
	$$(CXX) $$(CXXFLAGS) -o $$@ $$(filter-out build/target $$(BUILD)/config,$$^) $$(LDLIBS)

.PHONY: clean-$(1)
clean: clean-$(1)
clean-$(1):
	rm -f $(1)

-include $$(BUILD)/$(2).d

ifdef ASAN_DIR
$$(ASAN_DIR)/$(1): $$(ASAN_DIR)/$(2).o $$(ASAN_DIR)/librt.a
	$$(CXX) $$(ASAN_CXXFLAGS) -o $$@ $$^ $$(LDLIBS)
check-asan: $$(ASAN_DIR)/$(1)
endif
endef

# Further targets (benchmarks, sanitizers, fuzzing, converters) live in mk/*.mk.
-include $(sort $(wildcard mk/*.mk))

-include $(LIB_OBJ:.o=.d) $(LIB_FLOAT_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(TEST_FLOAT_OBJ:.o=.d) $(BUILD)/src/main.d \
         $(BUILD)/src/main-double.d $(TEST_PCH).d $(TEST_FLOAT_PCH).d
