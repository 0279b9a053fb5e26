# rtdiff: compares two images, or two folders of images (issue 15), with the measure of
# the conformance tests (rt/image_diff.h). Built by `make` beside ./raytracer; the tests
# run it, so `make test` builds it first.
.PHONY: clean-rtdiff
all: rtdiff
test: rtdiff
clean: clean-rtdiff

rtdiff: $(BUILD)/src/tools/rtdiff_main.o $(BUILD)/librt.a build/precision $(BUILD)/config
	$(CXX) $(CXXFLAGS) -o $@ $(filter-out build/precision $(BUILD)/config,$^) $(LDLIBS)

clean-rtdiff:
	rm -f rtdiff

-include $(BUILD)/src/tools/rtdiff_main.d

# check-asan (mk/check.mk) runs the tests from $(ASAN_DIR), so a sanitized rtdiff sits there too.
ifdef ASAN_DIR
$(ASAN_DIR)/rtdiff: $(ASAN_DIR)/src/tools/rtdiff_main.o $(ASAN_DIR)/librt.a
	$(CXX) $(ASAN_CXXFLAGS) -o $@ $^ $(LDLIBS)
check-asan: $(ASAN_DIR)/rtdiff
endif
