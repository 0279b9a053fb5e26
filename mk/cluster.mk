# make check-cluster: the cluster scripts of scripts/cluster/ (docs/animations.md, "On a
# cluster") run for real on this machine alone: a Slurm array of animation.sbatch and
# parallel.sh over ssh, each over 12 frames of camera_around_david compared byte for byte
# with one process's, and a shard given a missing scene file seen to fail by both
# (tests/cluster/check_cluster.sh). Needs root, slurm-wlm, munge, openssh-server and GNU
# parallel (.ci/run installs them) and ../shared; starts its own munged, slurmctld, slurmd
# and sshd in a network namespace of their own, and stops them. About 20 s.
.PHONY: check-cluster
check-cluster: raytracer
	tests/cluster/check_cluster.sh
