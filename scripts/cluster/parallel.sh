#!/bin/bash
# An animation as GNU parallel jobs, one shard of its frames per job, on this machine or,
# given parallel's options, over ssh. From the repository's folder:
#   scripts/cluster/parallel.sh
#   SHARDS=16 scripts/cluster/parallel.sh --sshlogin 8/host1,8/host2
# Over ssh, the repository and the scenes must be at the same path on every host (a shared
# folder), and the frames are written there. From the environment:
#   FRAMES   the scene files, one per frame: a glob, quoted so that each job's shell expands
#            it, or several globs or names separated by spaces (camera_around_david's by default)
#   OUT      the folder the frames are written to (frames)
#   SHARDS   the shard count, one job each (this machine's core count)
#   THREADS  each job's threads (1: single-threaded shards, as many as the job slots, fill
#            the cores with no idle tail)
# The exit status is parallel's: 0, or the number of shards that failed.
set -euo pipefail
FRAMES=${FRAMES:-../shared/scenes/hw2/raven/camera_around_david/*.json}
OUT=${OUT:-frames}
SHARDS=${SHARDS:-$(nproc)}
THREADS=${THREADS:-1}
exec parallel --workdir . "$@" ./raytracer -q -j "$THREADS" -o "$OUT" --shard {}/"$SHARDS" "$FRAMES" ::: $(seq 0 $((SHARDS - 1)))
