"""Render phase of each copy of the kernels (--isa), against another raytracer binary
(say a single-copy `make MARCH=native` build), on a few official scenes: medians over
alternating rounds of `--repeat N`, all in one run on one machine (docs/performance.md,
"One binary, every CPU").

    python3 tests/bench/isa_levels.py --other /path/to/raytracer-native [--rounds 5] [--repeat 7]
"""
import argparse
import os
import re
import statistics
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import RAYTRACER, isa_levels, shared_dir  # noqa: E402

SCENES = ["hw1/bunny_with_plane.json", "hw1/scienceTree_glass.json", "hw1/spheres.json",
          "hw1/cornellbox_recursive.json", "hw1/raven/rt_utahteapot_mug_ceng.json", "hw2/metal_glass_plates.json"]


def render_median(cmd, scene, repeat, threads):
    with tempfile.TemporaryDirectory() as out:
        r = subprocess.run(cmd + ["-j", str(threads), "--repeat", str(repeat), "-o", out, scene],
                           capture_output=True, text=True)
    m = re.search(r"render ([0-9.]+)s", r.stderr)
    if r.returncode != 0 or not m:
        sys.exit(f"{' '.join(cmd)} {scene}: {r.stderr.strip()}")
    return float(m.group(1))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--other", help="another raytracer binary to time beside the copies")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    shared = shared_dir()
    if not shared:
        sys.exit("isa_levels: the course's scenes (../shared or $RT_SHARED_DIR) not found")
    _, levels = isa_levels()
    progs = ([("other", [a.other])] if a.other else []) + [("auto", [RAYTRACER])] + \
        [(lv, [RAYTRACER, "--isa", lv]) for lv in levels]
    print(f"render phase, median of {a.rounds} alternating rounds of --repeat {a.repeat}, {a.threads} threads (s)")
    print("| scene | " + " | ".join(n for n, _ in progs) + " |")
    print("| --- |" + " ---: |" * len(progs))
    for scene in SCENES:
        path = os.path.join(shared, "scenes", scene)
        times = {n: [] for n, _ in progs}
        for _ in range(a.rounds):
            for n, cmd in progs:
                times[n].append(render_median(cmd, path, a.repeat, a.threads))
        print(f"| {scene} | " + " | ".join(f"{statistics.median(times[n]):.4f}" for n, _ in progs) + " |",
              flush=True)


if __name__ == "__main__":
    main()
