# make check-march: the scalar kernels give the same images as the SIMD ones.
# Builds the baseline x86-64 target (MARCH=x86-64, no AVX instruction: checked in the
# binary's code), runs the whole test suite with it in both precisions, and compares its
# conformance renders with the native build's byte for byte, each precision with its own
# (the same PNG writer, so the same bytes mean the same pixels). .ci/run calls it after `make test`; ./raytracer and ./rtconvert are native
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
	@n=0; for f in $$(ls $(MARCH_CHECK_DIR)/native/*/*.png | grep -v "_diff.png$$"); do \
	    g=$$(echo "$$f" | sed 's|/native/|/x86-64/|'); \
	    cmp -s "$$f" "$$g" || { echo "check-march: $$f and $$g differ"; n=$$((n+1)); }; \
	done; total=$$(ls $(MARCH_CHECK_DIR)/native/*/*.png | grep -vc "_diff.png$$"); \
	if [ $$total -eq 0 ]; then echo "check-march: no conformance renders (is ../shared there?)"; fi; \
	echo "check-march: $$((total-n)) of $$total conformance renders byte-identical between native and x86-64"; [ $$n -eq 0 ]
	$(MAKE) --no-print-directory -j$$(nproc) all
