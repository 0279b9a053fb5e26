# Tools that look for what the tests miss (included by the Makefile).
#
#   make check-asan    unit/CLI tests and a few renders under AddressSanitizer and
#                      UndefinedBehaviorSanitizer (g++), in build/asan
#   make fuzz          libFuzzer targets for the scene loader, the PLY reader and the glTF import
#                      (clang-14 + libclang-rt-14-dev), FUZZ_SECONDS each, in build/fuzz;
#                      the corpus grows in build/fuzz/corpus, crashes land in build/fuzz/artifacts
#   make fuzz-build    just build the fuzz targets
#   make memcheck      valgrind memcheck on small renders: no errors, no leaks, in build/memcheck
#
# Each build lives in its own folder and never touches build/native or ./raytracer.

.PHONY: check-asan fuzz fuzz-build fuzz-corpus memcheck

CHECK_WARN    := -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -MMD -MP -ffp-contract=off
# Renders used by check-asan and memcheck: small scenes of our own (always there) and,
# when the course files are present, a few official ones (spheres, mirrors, glass, a PLY).
CHECK_SHARED  := $(or $(RT_SHARED_DIR),$(wildcard ../shared))
CHECK_SCENES  := $(abspath scenes/showcase.json) build/check-scene/all_features.json \
                 $(if $(CHECK_SHARED),$(addprefix $(abspath $(CHECK_SHARED))/scenes/hw1/,simple.json spheres_mirror.json cornellbox_recursive.json scienceTree_glass.json))

# tests/fuzz/seeds/scene/all_features.json (every object and material type, both camera
# types) with its two PLY meshes beside it: an ascii one and a binary one.
build/check-scene/all_features.json: tests/fuzz/seeds/scene/all_features.json tests/fuzz/seeds/ply/ascii_quad.ply tests/fuzz/seeds/ply/little.ply
	@mkdir -p $(dir $@)
	cp tests/fuzz/seeds/ply/ascii_quad.ply $(dir $@)mesh.ply
	cp tests/fuzz/seeds/ply/little.ply $(dir $@)bin.ply
	cp $< $@

# ---- AddressSanitizer + UndefinedBehaviorSanitizer ------------------------------------
ASAN_DIR      := build/asan
# -g1: line tables only, all the sanitizers' reports need (file:line in each frame);
# full debug information makes each sanitized file much slower to compile (docs/ci.md).
ASAN_CXXFLAGS := -O1 -g1 -march=native -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all $(CHECK_WARN)
ASAN_LIB_OBJ  := $(LIB_SRC:%.cpp=$(ASAN_DIR)/%.o)
ASAN_FLOAT_OBJ := $(LIB_FLOAT_OBJ:$(BUILD)/%=$(ASAN_DIR)/%)
ASAN_TEST_OBJ := $(TEST_SRC:%.cpp=$(ASAN_DIR)/%.o)
ASAN_ENV      := ASAN_OPTIONS=detect_leaks=1:abort_on_error=0:strict_string_checks=1:detect_stack_use_after_return=1 \
                 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# The conformance tests and the tests named *EveryOfficialScene render all the course's
# scenes; under the sanitizers they would take most of CI's budget, so check-asan runs
# everything else plus the renders above. CHECK_ASAN_FILTER='*' runs them all.
CHECK_ASAN_FILTER ?= -Conformance*:*Conformance*:*EveryOfficialScene

$(ASAN_DIR)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(ASAN_CXXFLAGS) -c $< -o $@

$(ASAN_DIR)/float/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(FLOAT_CPPFLAGS) $(ASAN_CXXFLAGS) -c $< -o $@

$(ASAN_DIR)/pch/test_pch.h.gch: tests/test_pch.h
	$(call test_pch,$(ASAN_DIR)/pch/test_pch.h,$(CXX) $(CPPFLAGS) $(ASAN_CXXFLAGS))

$(ASAN_DIR)/tests/%.o: tests/%.cpp $(ASAN_DIR)/pch/test_pch.h.gch
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(ASAN_CXXFLAGS) -include $(ASAN_DIR)/pch/test_pch.h -c $< -o $@

# The archives are made by the Makefile's %.a rule, as every librt*.a.
$(ASAN_DIR)/librt.a: $(ASAN_LIB_OBJ)
$(ASAN_DIR)/librt_float.a: $(ASAN_FLOAT_OBJ)

# The CLI tests run "./raytracer" from the folder the test program starts in, so the
# sanitized renderer sits beside the sanitized test program and the tests start there.
$(ASAN_DIR)/raytracer: $(ASAN_DIR)/src/main.o $(ASAN_DIR)/librt_float.a $(ASAN_DIR)/librt.a
	$(CXX) $(ASAN_CXXFLAGS) -o $@ $^ $(LDLIBS)

$(ASAN_DIR)/rt_tests: $(ASAN_TEST_OBJ) $(ASAN_DIR)/librt.a
	$(CXX) $(ASAN_CXXFLAGS) -o $@ $^ -lgtest $(LDLIBS)

check-asan: $(ASAN_DIR)/raytracer $(ASAN_DIR)/rt_tests build/check-scene/all_features.json
	cd $(ASAN_DIR) && $(ASAN_ENV) $(if $(CHECK_SHARED),RT_SHARED_DIR=$(abspath $(CHECK_SHARED))) \
	    ./rt_tests --gtest_filter='$(CHECK_ASAN_FILTER)'
	@rm -rf $(ASAN_DIR)/renders && mkdir -p $(ASAN_DIR)/renders
	$(ASAN_ENV) $(ASAN_DIR)/raytracer -j 2 -o $(ASAN_DIR)/renders $(CHECK_SCENES)
	$(ASAN_ENV) $(ASAN_DIR)/raytracer --precision float -j 2 -o $(ASAN_DIR)/renders $(CHECK_SCENES)
	@echo "check-asan: tests and renders clean under ASan + UBSan"

# ---- libFuzzer --------------------------------------------------------------------------
FUZZ_DIR      := build/fuzz
FUZZ_CXX      ?= clang++-14
FUZZ_SECONDS  ?= 60
FUZZ_FLAGS    := -O1 -g -march=native -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize-recover=all $(CHECK_WARN)
FUZZ_LIB_OBJ  := $(LIB_SRC:%.cpp=$(FUZZ_DIR)/%.o)
FUZZ_TARGETS  := scene ply gltf
FUZZ_ENV      := ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Per-target libFuzzer options: input size limits and dictionaries.
FUZZ_OPTS_scene := -max_len=16384 -dict=tests/fuzz/scene.dict
FUZZ_OPTS_ply   := -max_len=4096 -dict=tests/fuzz/ply.dict
FUZZ_OPTS_gltf  := -max_len=16384

$(FUZZ_DIR)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(FUZZ_CXX) $(CPPFLAGS) $(FUZZ_FLAGS) -fsanitize=fuzzer-no-link -c $< -o $@

$(FUZZ_DIR)/librt.a: $(FUZZ_LIB_OBJ)

$(FUZZ_DIR)/fuzz_%: $(FUZZ_DIR)/tests/fuzz/fuzz_%.o $(FUZZ_DIR)/librt.a
	$(FUZZ_CXX) $(FUZZ_FLAGS) -fsanitize=fuzzer -o $@ $^ $(LDLIBS)

fuzz-build: $(FUZZ_TARGETS:%=$(FUZZ_DIR)/fuzz_%)

# Seed corpus: our own files (tests/fuzz/seeds, scenes/, the regression inputs) and,
# when present, the course's small scenes and PLY files. Existing corpus entries stay.
fuzz-corpus:
	@mkdir -p $(FUZZ_DIR)/corpus/scene $(FUZZ_DIR)/corpus/ply $(FUZZ_DIR)/corpus/gltf $(FUZZ_DIR)/artifacts
	@cp tests/fuzz/seeds/scene/* scenes/*.json $(FUZZ_DIR)/corpus/scene/
	@cp tests/fuzz/seeds/ply/* $(FUZZ_DIR)/corpus/ply/
	@cp tests/fuzz/seeds/gltf/* $(FUZZ_DIR)/corpus/gltf/
	@for f in tests/fuzz/regressions/scene/* ; do [ -f "$$f" ] && cp "$$f" $(FUZZ_DIR)/corpus/scene/ ; done ; true
	@for f in tests/fuzz/regressions/ply/* ; do [ -f "$$f" ] && cp "$$f" $(FUZZ_DIR)/corpus/ply/ ; done ; true
	@if [ -n "$(CHECK_SHARED)" ]; then \
	    find $(CHECK_SHARED)/scenes -name '*.json' -size -16k -exec cp {} $(FUZZ_DIR)/corpus/scene/ \; ; \
	    find $(CHECK_SHARED)/scenes -name '*.ply' -size -4k -exec cp {} $(FUZZ_DIR)/corpus/ply/ \; ; \
	fi; true

# Runs each target for FUZZ_SECONDS (make fuzz FUZZ_SECONDS=600); fails on any finding.
fuzz: fuzz-build fuzz-corpus
	@set -e; for t in $(FUZZ_TARGETS); do \
	    echo "fuzz_$$t: $(FUZZ_SECONDS) s"; \
	    $(FUZZ_ENV) nice $(FUZZ_DIR)/fuzz_$$t $(FUZZ_DIR)/corpus/$$t \
	        -max_total_time=$(FUZZ_SECONDS) -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
	        -artifact_prefix=$(FUZZ_DIR)/artifacts/$$t- $(FUZZ_OPTS_$$t) \
	        2> $(FUZZ_DIR)/fuzz_$$t.log || { tail -40 $(FUZZ_DIR)/fuzz_$$t.log; exit 1; }; \
	    grep -E 'stat::number_of_executed_units|fuzz_scene: ' $(FUZZ_DIR)/fuzz_$$t.log || true; \
	done

# ---- valgrind memcheck ------------------------------------------------------------------
# An -O1 -g build for this machine without AVX-512, which valgrind does not decode
# (AVX2 it does: the leaves' four-triangle tests run under it too).
MEMCHECK_DIR      := build/memcheck
MEMCHECK_CXXFLAGS := -O1 -g -march=native -mno-avx512f $(CHECK_WARN)
MEMCHECK_LIB_OBJ  := $(LIB_SRC:%.cpp=$(MEMCHECK_DIR)/%.o)
MEMCHECK_FLOAT_OBJ := $(LIB_FLOAT_OBJ:$(BUILD)/%=$(MEMCHECK_DIR)/%)
# Small renders: our showcase, the all-features scene (PLY meshes) and the course's
# simple.json (inline meshes, spheres).
MEMCHECK_SCENES   := $(abspath scenes/showcase.json) build/check-scene/all_features.json \
                     $(if $(CHECK_SHARED),$(abspath $(CHECK_SHARED))/scenes/hw1/simple.json)

$(MEMCHECK_DIR)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(MEMCHECK_CXXFLAGS) -c $< -o $@

$(MEMCHECK_DIR)/float/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(FLOAT_CPPFLAGS) $(MEMCHECK_CXXFLAGS) -c $< -o $@

$(MEMCHECK_DIR)/librt.a: $(MEMCHECK_LIB_OBJ)

$(MEMCHECK_DIR)/librt_float.a: $(MEMCHECK_FLOAT_OBJ)

$(MEMCHECK_DIR)/raytracer: $(MEMCHECK_DIR)/src/main.o $(MEMCHECK_DIR)/librt_float.a $(MEMCHECK_DIR)/librt.a
	$(CXX) $(MEMCHECK_CXXFLAGS) -o $@ $^ $(LDLIBS)

memcheck: $(MEMCHECK_DIR)/raytracer build/check-scene/all_features.json
	@rm -rf $(MEMCHECK_DIR)/renders && mkdir -p $(MEMCHECK_DIR)/renders
	valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --show-leak-kinds=all \
	    --errors-for-leak-kinds=all --track-origins=yes \
	    $(MEMCHECK_DIR)/raytracer -j 2 -o $(MEMCHECK_DIR)/renders $(MEMCHECK_SCENES)
	valgrind --tool=memcheck --error-exitcode=99 --leak-check=full --show-leak-kinds=all \
	    --errors-for-leak-kinds=all --track-origins=yes \
	    $(MEMCHECK_DIR)/raytracer --precision float -j 2 -o $(MEMCHECK_DIR)/renders $(MEMCHECK_SCENES)
	@echo "memcheck: no errors, no leaks"

-include $(ASAN_LIB_OBJ:.o=.d) $(ASAN_FLOAT_OBJ:.o=.d) $(ASAN_TEST_OBJ:.o=.d) $(ASAN_DIR)/src/main.d $(ASAN_DIR)/pch/test_pch.h.d
-include $(FUZZ_LIB_OBJ:.o=.d) $(FUZZ_DIR)/tests/fuzz/fuzz_scene.d $(FUZZ_DIR)/tests/fuzz/fuzz_ply.d
-include $(MEMCHECK_LIB_OBJ:.o=.d) $(MEMCHECK_FLOAT_OBJ:.o=.d) $(MEMCHECK_DIR)/src/main.d
