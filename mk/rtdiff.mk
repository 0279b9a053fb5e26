# rtdiff: compares two images, or two folders of images (issue 15), with the measure of
# the conformance tests (rt/image/image_diff.h). Built by `make` beside ./raytracer (in the
# submission tarball only by `make rtdiff`: docs/dist.md); the tests run it, so `make test`
# builds it first.
ifndef RT_TARBALL
all: rtdiff
endif
test: rtdiff
$(eval $(call helper_program,rtdiff,src/tools/rtdiff_main))
