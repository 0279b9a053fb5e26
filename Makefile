# raytracer: a recursive (Whitted) ray tracer for the CENG 795 JSON scene format.
#   make            build ./raytracer
#   make test       build and run the unit, property and conformance tests, once for each
#                   precision (double, then float: ./raytracer --precision float)
#   make CXXFLAGS="-O2 -g"  choose optimisation and debug flags; the flags below that the
#                           code needs are appended to any CXXFLAGS, CPPFLAGS or LDLIBS
#                           given on the command line (override), never replaced
#   make ISAS=x86-64        hold only the baseline x86-64 copy (no AVX: the scalar kernels);
#                           the default holds x86-64, avx2 and avx512 and picks one at start
#   make MARCH=native       one copy built for this CPU alone (-march=native), no choice
#   make PRECISIONS=double  build ./raytracer without its float copy (half the compiling;
#                           --precision float then exits with an error); the default is
#                           "double float", except in the submission tarball (docs/dist.md)
CXX      ?= g++
CXXFLAGS ?= -O3
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

# One binary for every x86-64 CPU (docs/performance.md, "One binary, every CPU"): the
# library is compiled once per instruction-set level of ISAS, each copy in its own
# namespace and object folder build/<level>, and main.cpp runs the best copy this CPU
# executes (or the one --isa / RT_ISA names). The levels: x86-64 (baseline, no AVX: the
# scalar kernels), avx2 (-march=x86-64-v3) and avx512 (-march=x86-64-v4). The first level
# is the primary copy: namespace rt, and the code compiled once (ONCE_SRC) and the helper
# programs are its. MARCH=ARCH builds a single copy with -march=ARCH (native: this CPU's
# every instruction, for this CPU only). The tarball builds one copy for the machine it
# is built on (mk/tarball.conf).
ifdef MARCH
  ISAS := $(MARCH)
endif
ISAS ?= $(if $(RT_TARBALL),native,x86-64 avx2 avx512)
PRIMARY_ISA := $(firstword $(ISAS))
EXTRA_ISAS  := $(wordlist 2,$(words $(ISAS)),$(ISAS))
ifneq ($(filter-out avx2 avx512,$(EXTRA_ISAS)),)
  $(error ISAS="$(ISAS)": after the first level, only avx2 and avx512 can be added)
endif
isa_march_avx2   := x86-64-v3
isa_march_avx512 := x86-64-v4
# isa_march(level): its -march value; isa_suffix(level): its namespaces' suffix (rt_avx2,
# rt_float_avx2; none for the primary copy).
isa_march  = $(or $(isa_march_$(1)),$(1))
isa_suffix = $(if $(filter $(1),$(PRIMARY_ISA)),,_$(1))

# The tests run against the best copy this CPU executes (TEST_ISA=x86-64: the scalar
# kernels'), read from the CPU's flags as main.cpp's check reads them.
CPU_FLAGS := $(shell grep -m1 '^flags' /proc/cpuinfo 2>/dev/null)
isa_runs_avx2   = $(if $(filter-out $(CPU_FLAGS),avx avx2 fma bmi1 bmi2 movbe f16c abm),,1)
isa_runs_avx512 = $(if $(filter-out $(CPU_FLAGS),avx512f avx512bw avx512cd avx512dq avx512vl),,$(isa_runs_avx2))
TEST_ISA ?= $(lastword $(PRIMARY_ISA) $(foreach i,$(EXTRA_ISAS),$(if $(isa_runs_$(i)),$(i))))
ifeq ($(filter $(TEST_ISA),$(ISAS)),)
  $(error TEST_ISA=$(TEST_ISA) is not one of ISAS="$(ISAS)")
endif

# Objects live in build/<level>; BUILD is the primary copy's folder, TEST_BUILD the tests'.
BUILD := build/$(PRIMARY_ISA)
TEST_BUILD := build/$(TEST_ISA)

# One program, both precisions (docs/precision.md). Each level's library is compiled twice:
# as written, with Real = double, in namespace rt (objects in build/<level>/src); and, when
# PRECISIONS has float, with Real = float (-DRT_REAL_FLOAT), every token `rt` renamed
# rt_float (objects in build/<level>/float/src), so that the copies link into one program
# without a clash (isa_copy, below, adds the level's suffix). main.cpp picks one copy per run
# (--precision, --isa); nothing else branches on them. The only code outside namespace rt,
# compiled once, in the primary double copy: stb's (stb_impl.cpp, the writer;
# stb_image_impl.cpp, the reader), the command-line helpers (namespace rtcli, cli/), tinygltf's
# and the glTF codecs' (namespace rtgltf, convert/gltf_io.cpp, convert/gltf_codec*.cpp) and rtdiff's modes (namespace rtdiff, src/tools/),
# which use neither Real nor a level's instructions. FLOAT_CPPFLAGS: the sanitized and
# WebAssembly builds' float copy.
FLOAT_CPPFLAGS := -DRT_REAL_FLOAT -Drt=rt_float
ONCE_SRC := src/image/stb_impl.cpp src/image/stb_image_impl.cpp src/cli/options.cpp src/cli/isa.cpp src/convert/gltf_io.cpp src/convert/gltf_codec% src/tools/%

# Every src/**/*.cpp is library code except program entry points (main.cpp, *_main.cpp).
# The library is two archives per precision: librt.a, what ./raytracer links, and
# librt_tools.a, the code only the helper programs and the tests use (TOOL_SRC: the scene
# converter, the image comparison, its heatmap, its PNG reader and rtdiff's modes), so that building
# ./raytracer alone compiles none of it. The float tools' few references to stb's reader
# are resolved by the double librt_tools.a.
LIB_SRC  := $(filter-out src/main.cpp %_main.cpp,$(shell find src -name '*.cpp' | sort))
TOOL_SRC := $(filter src/convert/% src/image/image_diff.cpp src/image/block_diff.cpp src/image/diff_page.cpp \
                      src/image/diff_heatmap.cpp src/image/bitmap_font.cpp src/image/stb_image_impl.cpp \
                      src/tools/%,$(LIB_SRC))
RENDER_SRC := $(filter-out $(TOOL_SRC),$(LIB_SRC))
# copy_dir(level,float): a copy's object folder; copy_obj(level,float,sources): its objects
# of those sources (the ONCE_SRC ones in the primary double copy only).
copy_dir = build/$(1)$(if $(2),/float)
copy_obj = $(patsubst %.cpp,$(call copy_dir,$(1),$(2))/%.o,$(if $(or $(2),$(call isa_suffix,$(1))),$(filter-out $(ONCE_SRC),$(3)),$(3)))
# The primary copy's objects (the sanitized builds in mk/check.mk mirror these).
LIB_OBJ  := $(call copy_obj,$(PRIMARY_ISA),,$(LIB_SRC))
LIB_FLOAT_OBJ := $(call copy_obj,$(PRIMARY_ISA),float,$(LIB_SRC))
# The test programs are built from tests/*.cpp only; subfolders (fuzz targets, benchmarks)
# have their own rules. The same tests run against each precision's library.
TEST_SRC := $(sort $(wildcard tests/*.cpp))
TEST_OBJ := $(TEST_SRC:%.cpp=$(TEST_BUILD)/%.o)
TEST_FLOAT_OBJ := $(TEST_SRC:%.cpp=$(TEST_BUILD)/float/%.o)
# The test programs' own code is compiled at TEST_OPT (after CXXFLAGS, so it wins): it
# compiles in about 60% of -O3's time, and CI builds four copies (docs/ci.md). The library
# they test keeps CXXFLAGS. `make TEST_OPT=` compiles the tests with CXXFLAGS alone.
TEST_OPT ?= -O1
# Each test file starts with tests/test_pch.h (GoogleTest, nlohmann/json), precompiled
# once per object folder with the test files' own flags (test_pch, below).
TEST_PCH       := $(TEST_BUILD)/pch/test_pch.h
TEST_FLOAT_PCH := $(TEST_BUILD)/float/pch/test_pch.h

.PHONY: all test unit clean
all: raytracer

# build/target names the copies ./raytracer was last linked from, how (static or not,
# mk/static.mk) and with which precisions; it changes (and forces a relink) only when
# ISAS, RT_STATIC or PRECISIONS does.
build/target: FORCE
	@mkdir -p build
	@echo '$(ISAS) $(RT_STATIC) $(PRECISIONS)' | cmp -s - $@ || echo '$(ISAS) $(RT_STATIC) $(PRECISIONS)' > $@

# $(eval $(call isa_copy,LEVEL)): the rules of one level's copy, double and float, in
# build/LEVEL: its config file (the compile and link lines; a change rebuilds what it
# affects instead of mixing objects of two configurations), library and test objects, and
# archives. A copy's flags: -march of its level, RT_ISA_NAME (what --version and --stats
# report), and for every copy but the primary double one, RT_SECONDARY_COPY (the program-
# wide definitions, operator new, are the primary's) and its namespace (-Drt=...).
define isa_copy
ISA_FLAGS_$(1) := -march=$(call isa_march,$(1)) -DRT_ISA_NAME='"$(1)"'
ISA_DOUBLE_$(1) := $(if $(call isa_suffix,$(1)),-DRT_SECONDARY_COPY -Drt=rt$(call isa_suffix,$(1)))
ISA_FLOAT_$(1) := -DRT_REAL_FLOAT -DRT_SECONDARY_COPY -Drt=rt_float$(call isa_suffix,$(1))

build/$(1)/config: FORCE
	@mkdir -p build/$(1)
	@printf '%s\n' '$$(CXX) $$(CPPFLAGS) $$(CXXFLAGS) $$(ISA_FLAGS_$(1))' '$$(LDLIBS)' 'tests: $$(TEST_OPT)' | cmp -s - $$@ || \
	    printf '%s\n' '$$(CXX) $$(CPPFLAGS) $$(CXXFLAGS) $$(ISA_FLAGS_$(1))' '$$(LDLIBS)' 'tests: $$(TEST_OPT)' > $$@

build/$(1)/src/%.o: src/%.cpp build/$(1)/config
	@mkdir -p $$(dir $$@)
	$$(CXX) $$(CPPFLAGS) $$(ISA_DOUBLE_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) -c $$< -o $$@

build/$(1)/float/src/%.o: src/%.cpp build/$(1)/config
	@mkdir -p $$(dir $$@)
	$$(CXX) $$(CPPFLAGS) $$(ISA_FLOAT_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) -c $$< -o $$@

build/$(1)/pch/test_pch.h.gch: tests/test_pch.h build/$(1)/config
	$$(call test_pch,build/$(1)/pch/test_pch.h,$$(CXX) $$(CPPFLAGS) $$(ISA_DOUBLE_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) $$(TEST_OPT))

build/$(1)/float/pch/test_pch.h.gch: tests/test_pch.h build/$(1)/config
	$$(call test_pch,build/$(1)/float/pch/test_pch.h,$$(CXX) $$(CPPFLAGS) $$(ISA_FLOAT_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) $$(TEST_OPT))

build/$(1)/tests/%.o: tests/%.cpp build/$(1)/pch/test_pch.h.gch build/$(1)/config
	@mkdir -p $$(dir $$@)
	$$(CXX) $$(CPPFLAGS) $$(ISA_DOUBLE_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) $$(TEST_OPT) -include build/$(1)/pch/test_pch.h -c $$< -o $$@

build/$(1)/float/tests/%.o: tests/%.cpp build/$(1)/float/pch/test_pch.h.gch build/$(1)/config
	@mkdir -p $$(dir $$@)
	$$(CXX) $$(CPPFLAGS) $$(ISA_FLOAT_$(1)) $$(CXXFLAGS) $$(ISA_FLAGS_$(1)) $$(TEST_OPT) -include build/$(1)/float/pch/test_pch.h -c $$< -o $$@

build/$(1)/librt.a: $(call copy_obj,$(1),,$(RENDER_SRC))
build/$(1)/librt_tools.a: $(call copy_obj,$(1),,$(TOOL_SRC))
build/$(1)/librt_float.a: $(call copy_obj,$(1),float,$(RENDER_SRC))
build/$(1)/librt_float_tools.a: $(call copy_obj,$(1),float,$(TOOL_SRC))

-include $(patsubst %.o,%.d,$(call copy_obj,$(1),,$(LIB_SRC)) $(call copy_obj,$(1),float,$(LIB_SRC)))
endef
$(foreach i,$(ISAS),$(eval $(call isa_copy,$(i))))

# Every archive (these and mk/*.mk's) is its objects, remade whole: ar would keep the
# members of sources since removed.
%.a:
	@rm -f $@
	ar rcs $@ $^

# main.cpp knows the copies from RT_PRIMARY_ISA and RT_WITH_<LEVEL> (rt/app/program.h).
# Without float it is compiled with RT_NO_FLOAT and refuses --precision float.
MAIN_FLAGS := -DRT_PRIMARY_ISA='"$(PRIMARY_ISA)"' $(foreach i,$(EXTRA_ISAS),-DRT_WITH_$(subst avx,AVX,$(i))) \
              $(if $(RT_FLOAT),,-DRT_NO_FLOAT)
MAIN_OBJ := $(BUILD)/src/main-program.o
$(MAIN_OBJ): src/main.cpp $(BUILD)/config build/target
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(MAIN_FLAGS) $(CXXFLAGS) $(ISA_FLAGS_$(PRIMARY_ISA)) -MMD -MP -c $< -o $@

# The copies in ISAS order, the primary first: a function the copies share outside their
# namespaces (a standard library template, say) is then linked from the baseline copy, the
# one every CPU runs; the primary archive again at the end for the ONCE_SRC code.
# Linked statically where the static libraries are at hand (mk/static.mk).
COPY_LIBS := $(foreach i,$(ISAS),$(if $(RT_FLOAT),build/$(i)/librt_float.a) build/$(i)/librt.a) $(BUILD)/librt.a
# No copy but the primary one may run code before main() (rt/cli/parser.h): a static
# initializer of the avx512 copy would run, and die, on every CPU without AVX-512.
EXTRA_LIBS := $(foreach i,$(EXTRA_ISAS),build/$(i)/librt.a $(if $(RT_FLOAT),build/$(i)/librt_float.a))
raytracer: $(MAIN_OBJ) $(COPY_LIBS) build/target $(foreach i,$(ISAS),build/$(i)/config)
	@if [ -n "$(EXTRA_LIBS)" ] && nm -A $(EXTRA_LIBS) | grep '_GLOBAL__sub_I'; then \
	    echo "error: the objects above construct namespace-scope objects at start; in a copy for $(EXTRA_ISAS)"; \
	    echo "       that code runs on every CPU before main() chooses a copy: make them function-local statics"; \
	    exit 1; fi
	$(CXX) $(CXXFLAGS) $(ISA_FLAGS_$(PRIMARY_ISA)) $(RT_STATIC) -o $@ $(MAIN_OBJ) $(COPY_LIBS) $(RAYTRACER_LDLIBS)

.PHONY: FORCE
FORCE:

# test_pch(header, compile command without -c/-o): the test files' precompiled header at
# <header>.gch, beside a copy of tests/test_pch.h (g++ takes the .gch when the flags match
# and falls back to the copy otherwise).
define test_pch
	@mkdir -p $(dir $(1))
	cp tests/test_pch.h $(1)
	$(2) -x c++-header $(1) -o $(1).gch
endef

# The test programs link TEST_ISA's copy (the primary archive last, for the ONCE_SRC code).
TEST_ONCE := $(if $(call isa_suffix,$(TEST_ISA)),$(BUILD)/librt_tools.a $(BUILD)/librt.a)
$(TEST_BUILD)/rt_tests: $(TEST_OBJ) $(TEST_BUILD)/librt_tools.a $(TEST_BUILD)/librt.a $(TEST_ONCE) $(TEST_BUILD)/config
	$(CXX) $(CXXFLAGS) $(ISA_FLAGS_$(TEST_ISA)) -o $@ $(filter-out $(TEST_BUILD)/config,$^) -lgtest $(LDLIBS)

$(TEST_BUILD)/rt_tests_float: $(TEST_FLOAT_OBJ) $(TEST_BUILD)/librt_float_tools.a $(TEST_BUILD)/librt_float.a \
                         $(TEST_BUILD)/librt_tools.a $(TEST_BUILD)/librt.a $(TEST_ONCE) $(TEST_BUILD)/config
	$(CXX) $(CXXFLAGS) $(ISA_FLAGS_$(TEST_ISA)) -o $@ $(filter-out $(TEST_BUILD)/config,$^) -lgtest $(LDLIBS)

# Tests read the course files from ../shared (or $$RT_SHARED_DIR); the CLI tests
# run ./raytracer (with --precision of the suite's own, and --isa TEST_ISA through RT_ISA),
# so it is built first.
# TEST_PRECISIONS=float runs one suite only; it defaults to the precisions ./raytracer holds.
TEST_PRECISIONS ?= $(PRECISIONS)
ifeq ($(filter float,$(TEST_PRECISIONS)):$(RT_FLOAT),float:)
  $(error TEST_PRECISIONS has float, PRECISIONS not: the float tests run ./raytracer --precision float)
endif
test: raytracer $(if $(filter double,$(TEST_PRECISIONS)),$(TEST_BUILD)/rt_tests) \
                $(if $(filter float,$(TEST_PRECISIONS)),$(TEST_BUILD)/rt_tests_float)
	$(if $(filter double,$(TEST_PRECISIONS)),@echo "== the tests in double precision ($(TEST_ISA) kernels)" && RT_ISA=$(TEST_ISA) $(TEST_BUILD)/rt_tests)
	$(if $(filter float,$(TEST_PRECISIONS)),@echo "== the tests in float precision ($(TEST_ISA) kernels)" && RT_ISA=$(TEST_ISA) $(TEST_BUILD)/rt_tests_float)

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

-include $(TEST_OBJ:.o=.d) $(TEST_FLOAT_OBJ:.o=.d) $(MAIN_OBJ:.o=.d) $(TEST_PCH).d $(TEST_FLOAT_PCH).d
