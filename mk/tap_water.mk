# make tap-water: assignment 3's tap_water animation (docs/animations.md, "Assignment 3's
# tap_water"). The 24 frames of ../shared/scenes/hw3/tap_water (1000x1000, 64 samples) are
# rendered through --shard by GNU parallel, one single-threaded shard per core, and encoded
# with ffmpeg (tap.mp4, 2.5 frames a second: the animation's speed); then each frame is
# compared with the course's video (tests/animation/compare_video.py) and the render time is
# projected to the whole animation (tests/animation/render_time.py). Heavy (minutes of every
# core): not part of make test. Everything goes to TAP_OUT:
#   frames/tap_NNNN.png, tap.mp4, stats_K.json (--stats of shard K), time.txt (the shards'
#   wall and CPU seconds), compare/ (decoded frames), compare.md, time.md
#   make tap-water TAP_SAMPLES=4     a quick run at 4 samples per pixel
#   make tap-water-compare           compare and project again, without rendering
TAP_SHARED  ?= $(or $(RT_SHARED_DIR),../shared)
TAP_SCENES   = $(TAP_SHARED)/scenes/hw3/tap_water/json/*.json
TAP_VIDEO    = $(TAP_SHARED)/references/hw3/tap_water/tap.mp4
TAP_OUT     ?= build/tap_water
TAP_SHARDS  ?= $(shell nproc)
TAP_SAMPLES ?=
# The animation has 286 frames; the projection is for this many machines like this one.
TAP_MACHINES ?= 1,8,64

.PHONY: tap-water tap-water-compare
# bash, for its `time` of the whole parallel run (the CPU seconds of every shard).
tap-water: SHELL := /bin/bash
tap-water: raytracer rtdiff
	@test -f $(TAP_VIDEO) || { echo "make tap-water: $(TAP_VIDEO) not found (the course's shared folder: RT_SHARED_DIR)"; exit 1; }
	rm -rf $(TAP_OUT) && mkdir -p $(TAP_OUT)/frames
	TIMEFORMAT='wall %R user %U sys %S'; { time parallel --will-cite --halt now,fail=1 \
	    ./raytracer -q -j 1 $(if $(TAP_SAMPLES),--samples $(TAP_SAMPLES)) --stats $(TAP_OUT)/stats_{}.json \
	    -o $(TAP_OUT)/frames --shard {}/$(TAP_SHARDS) '$(TAP_SCENES)' ::: $$(seq 0 $$(($(TAP_SHARDS) - 1))) 2>&3; \
	  } 3>&2 2>$(TAP_OUT)/time.txt
	ffmpeg -v error -y -framerate 2.5 -pattern_type glob -i '$(TAP_OUT)/frames/tap_*.png' \
	    -c:v libx264 -crf 23 -pix_fmt yuv420p $(TAP_OUT)/tap.mp4
	$(MAKE) --no-print-directory tap-water-compare

tap-water-compare: rtdiff
	python3 tests/animation/compare_video.py --frames $(TAP_OUT)/frames \
	    --video $(TAP_VIDEO) --work $(TAP_OUT)/compare --report $(TAP_OUT)/compare.md
	python3 tests/animation/render_time.py --time $(TAP_OUT)/time.txt --total-frames 286 \
	    --machines $(TAP_MACHINES) --report $(TAP_OUT)/time.md $(TAP_OUT)/stats_*.json
