# rtdiff: compares two images, or two folders of images (issue 15), with the measure of
# the conformance tests (rt/image_diff.h). Built by `make` beside ./raytracer; the tests
# run it, so `make test` builds it first.
all: rtdiff
test: rtdiff
$(eval $(call helper_program,rtdiff,src/tools/rtdiff_main))
