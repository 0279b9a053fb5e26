# Benchmarks against refrender (../shared/tools): tests/bench/bench.py (its modules bench_*.py beside it),
# the scene generator tests/bench/gen_mesh/ (main.cpp, one .cpp per shape, gen_mesh.h).
#   make bench                          every complete official scene + knot_{1m,4m,16m}_{plain,glass,gold}
#                                       + blob_1m_{plain,glass}, terrain_1m, city_1m, soup_1m (docs/bench-scenes.md),
#                                       each with --cull and with --no-cull on both sides, 5 runs
#   make bench-quick                    the same without the 16M scenes, 3 runs
#   make bench BENCH_ARGS="--scenes bunny,knot_1m --runs 3 --threads 2 --cull-modes no-cull"   (see bench.py --help)
# Generated scenes go to build/bench/scenes/, the report to build/bench/bench.{md,json}.
BENCH_GEN  := build/bench/gen_mesh
BENCH_GEN_SRC := $(sort $(wildcard tests/bench/gen_mesh/*.cpp))
BENCH_ARGS ?=

$(BENCH_GEN): $(BENCH_GEN_SRC) tests/bench/gen_mesh/gen_mesh.h
	@mkdir -p $(dir $@)
	$(CXX) -O2 -std=c++17 -ffp-contract=off -Wall -Wextra -o $@ $(BENCH_GEN_SRC)

.PHONY: bench bench-quick bench-hw2
bench: raytracer $(BENCH_GEN)
	python3 tests/bench/bench.py --raytracer ./raytracer --gen-mesh $(BENCH_GEN) $(BENCH_ARGS)
	python3 tests/bench/assignment2.py --raytracer ./raytracer

# Assignment 2 (tests/bench/assignment2.py): its scenes, the 10,000-instance stress scene
# against one 1M-triangle mesh over the same area, and an animation in one process against a process per frame; needs
# build/bench/scenes/{knot,terrain}_1m.ply (make bench-quick generates them). Report: build/bench/hw2.md.
#   make bench-hw2 HW2_ARGS="--frames 36 --grid 50"
HW2_ARGS ?=
bench-hw2: raytracer
	python3 tests/bench/assignment2.py --raytracer ./raytracer $(HW2_ARGS)

bench-quick: raytracer $(BENCH_GEN)
	python3 tests/bench/bench.py --raytracer ./raytracer --gen-mesh $(BENCH_GEN) --quick $(BENCH_ARGS)

# BVH build only: median build time, the tree's SAH cost and how full its nodes are
# (tests/bench/bvh_bench.cpp), for the double tree and the float one.
#   make bench-bvh BVH_SCENE=build/bench/scenes/knot_4m_plain.json
BVH_BENCH := build/bench/bvh_bench
BVH_BENCH_FLOAT := build/bench/bvh_bench_float
BVH_SCENE ?= build/bench/scenes/knot_4m_plain.json
# Built against the copy the tests use (TEST_ISA: this CPU's best level).
$(BVH_BENCH): tests/bench/bvh_bench.cpp $(TEST_BUILD)/librt.a $(TEST_ONCE)
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(ISA_DOUBLE_$(TEST_ISA)) $(CXXFLAGS) $(ISA_FLAGS_$(TEST_ISA)) -o $@ $^ $(LDLIBS)
$(BVH_BENCH_FLOAT): tests/bench/bvh_bench.cpp $(TEST_BUILD)/librt_float.a $(TEST_BUILD)/librt.a $(TEST_ONCE)
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(ISA_FLOAT_$(TEST_ISA)) $(CXXFLAGS) $(ISA_FLAGS_$(TEST_ISA)) -o $@ $^ $(LDLIBS)

.PHONY: bench-bvh
bench-bvh: $(BVH_BENCH) $(BVH_BENCH_FLOAT)
	$(BVH_BENCH) --runs 5 $(BVH_SCENE)
	$(BVH_BENCH_FLOAT) --runs 5 $(BVH_SCENE)
