# make check-march: the scalar kernels give the same images as the SIMD ones.
# Builds the baseline x86-64 target (MARCH=x86-64, no AVX instruction: checked in the
# binary's code), runs the whole test suite with it in both precisions, and compares its
# conformance renders with the native build's byte for byte, each precision with its own
# (the same PNG writer, so the same bytes mean the same pixels); the renders are in
# <dir>/<precision>/<assignment>/ (tests/test_conformance.cpp). .ci/run calls it after `make test`; ./raytracer and ./rtconvert are native
# again afterwards.
MARCH_CHECK_DIR := build/march-check

.PHONY: check-march
check-march:
	@rm -rf $(MARCH_CHECK_DIR) && mkdir -p $(MARCH_CHECK_DIR)
	$(MAKE) --no-print-directory -j$$(nproc) raytracer
	GTEST_FILTER='*Conformance*' RT_CONFORMANCE_OUT=$(abspath $(MARCH_CHECK_DIR))/native $(MAKE) --no-print-directory test
	$(MAKE) --no-print-directory -j$$(nproc) MARCH=x86-64 raytracer build/x86-64/rt_tests build/x86-64/rt_tests_float
	@if objdump -d --no-show-raw-insn raytracer | grep -qE '%[yz]mm'; then \
	    echo "check-march: the MARCH=x86-64 raytracer contains AVX instructions"; exit 1; fi
	RT_CONFORMANCE_OUT=$(abspath $(MARCH_CHECK_DIR))/x86-64 $(MAKE) --no-print-directory MARCH=x86-64 test
	$(MAKE) --no-print-directory check-march-compare
	$(MAKE) --no-print-directory -j$$(nproc) all

# The comparison step alone (on the renders check-march left in $(MARCH_CHECK_DIR)).
# Comparing nothing (no ../shared, or $$RT_SHARED_DIR not there) is no pass: it says
# "check-march: SKIPPED" loudly, and fails when CI=true.
.PHONY: check-march-compare
check-march-compare:
	@n=0; total=0; for f in $$(ls $(MARCH_CHECK_DIR)/native/*/*/*.png 2>/dev/null | grep -v "_diff.png$$"); do \
	    total=$$((total+1)); g=$$(echo "$$f" | sed 's|/native/|/x86-64/|'); \
	    cmp -s "$$f" "$$g" || { echo "check-march: $$f and $$g differ"; n=$$((n+1)); }; \
	done; \
	if [ $$total -eq 0 ]; then \
	    echo "********************************************************************"; \
	    echo "*** check-march: SKIPPED: 0 conformance renders to compare (the course's shared"; \
	    echo "*** folder, ../shared or \$$RT_SHARED_DIR, was not found): nothing was checked"; \
	    echo "********************************************************************"; \
	    if [ "$$CI" = true ]; then echo "check-march: FAIL: CI=true and nothing compared"; exit 1; fi; exit 0; \
	fi; \
	echo "check-march: $$((total-n)) of $$total conformance renders byte-identical between native and x86-64"; [ $$n -eq 0 ]
