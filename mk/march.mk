# make check-march: every copy of the kernels gives the same images (docs/performance.md,
# "One binary, every CPU"). The whole test suite in both precisions against the primary
# copy (TEST_ISA=$(PRIMARY_ISA): baseline x86-64, the scalar kernels; `make test` ran it
# against this CPU's best copy; assignment 3's images at their full NumSamples, minutes of
# scalar kernels, are left to check_levels.py at a few samples), then tests/march/check_levels.py: every level this CPU
# executes renders every complete official scene and ours to the same bytes in both
# precisions (./raytracer --isa), and under qemu-x86_64 -cpu Nehalem (a CPU without AVX)
# the binary picks the baseline copy, refuses the others and renders the same bytes.
# Renders in build/march-check/. .ci/run calls it after `make test`.
.PHONY: check-march
check-march:
	$(MAKE) --no-print-directory -j$$(nproc) raytracer
	GTEST_FILTER='-HW3/ConformanceImage.*' $(MAKE) --no-print-directory -j$$(nproc) TEST_ISA=$(PRIMARY_ISA) test
	python3 tests/march/check_levels.py
