# raytracer: a recursive (Whitted) ray tracer for the CENG 795 JSON scene format.
#   make            build ./raytracer
#   make test       build and run the unit, property and conformance tests
#   make PRECISION=float   build with single-precision geometry and shading
CXX      ?= g++
CXXFLAGS ?= -O3 -march=native
# No fused multiply-add contraction: the watertight triangle test needs its edge
# functions evaluated exactly alike for both triangles sharing an edge, which
# contraction breaks (rays slipped through the diagonal of simple.json's quad).
CXXFLAGS += -ffp-contract=off
CXXFLAGS += -std=c++17 -Wall -Wextra -Wpedantic -Wshadow -MMD -MP
CPPFLAGS += -Iinclude
LDLIBS   += -lpthread

# Headers packaged in the submission tarball (make dist) live in third_party/;
# on a Debian machine they come from nlohmann-json3-dev and libstb-dev.
ifneq ($(wildcard third_party/stb/stb_image_write.h),)
  CPPFLAGS += -Ithird_party
  STB_IMPL := src/image/stb_impl.cpp
else
  LDLIBS += -lstb
endif

ifeq ($(PRECISION),float)
  CPPFLAGS += -DRT_REAL_FLOAT
  BUILD := build/float
else
  BUILD := build/double
endif

LIB_SRC  := $(filter-out src/main.cpp src/image/stb_impl.cpp,$(shell find src -name '*.cpp' | sort)) $(STB_IMPL)
LIB_OBJ  := $(LIB_SRC:%.cpp=$(BUILD)/%.o)
TEST_SRC := $(shell find tests -name '*.cpp' 2>/dev/null | sort)
TEST_OBJ := $(TEST_SRC:%.cpp=$(BUILD)/%.o)

.PHONY: all test unit clean
all: raytracer

raytracer: $(BUILD)/src/main.o $(BUILD)/librt.a
	$(CXX) $(CXXFLAGS) -o $@ $^ $(LDLIBS)

$(BUILD)/librt.a: $(LIB_OBJ)
	@rm -f $@
	ar rcs $@ $^

$(BUILD)/%.o: %.cpp
	@mkdir -p $(dir $@)
	$(CXX) $(CPPFLAGS) $(CXXFLAGS) -c $< -o $@

$(BUILD)/rt_tests: $(TEST_OBJ) $(BUILD)/librt.a
	$(CXX) $(CXXFLAGS) -o $@ $^ -lgtest $(LDLIBS)

# Tests read the course files from ../shared (or $$RT_SHARED_DIR); the CLI tests
# run ./raytracer, so it is built first.
test: raytracer $(BUILD)/rt_tests
	$(BUILD)/rt_tests

clean:
	rm -rf build raytracer

-include $(LIB_OBJ:.o=.d) $(TEST_OBJ:.o=.d) $(BUILD)/src/main.d
