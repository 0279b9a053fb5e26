#!/usr/bin/env python3
"""Benchmark ./raytracer against refrender (the Embree-backed yardstick, ../shared/tools).

    python3 tests/bench/bench.py [--quick] [--runs N] [--threads N] [--scenes PATTERNS] ...
    make bench / make bench-quick          (extra arguments: BENCH_ARGS="...")

Scenes: every complete official scene (../shared/scenes/hw1/MANIFEST.tsv, column 4), then
our large ones, knot_<size>_{plain,glass,gold} (sizes 1M, 4M, 16M; --quick skips 16M), then
the other generated shapes at 1M (--shape-sizes): blob_{plain,glass}, terrain, city, soup
(docs/bench-scenes.md), generated into build/bench/scenes/ by build/bench/gen_mesh when
missing or older than it.

Every scene is measured twice, with culling on (--cull) and off (--no-cull), the same
setting on both sides (refrender culls through an Embree filter function, so the no-cull
ratio is the fairer per-ray figure); --cull-modes restricts this. Ours renders in double
unless --precision float (BENCH_ARGS="--precision float").

Method, per scene: one warm-up run of each program, then N timed runs of each (default 5,
--quick 3), alternating (ours, ref, ref, ours, ours, ref, ...), each a whole process with the
same thread count, writing its images into a fresh temporary folder; the median wall time is
quoted. Ours runs with -q on cheap scenes. Peak RSS comes from os.wait4 (see SPAWNER in
bench_process.py).
Our phase split (load, BVH build, render, PNG write) is read from our stderr line: for cheap
scenes (warm-up under --cheap seconds) the median of N separate non-quiet runs; otherwise
every timed run of ours is made without -q and the split is their median, like refrender's
(-q only drops one stderr line per image, so it costs nothing measurable).
Budget rules: a heavy scene (a warm-up, or first timed round, over --heavy seconds) gets at
most --heavy-runs timed runs; a scene whose mesh files an earlier non-cheap scene already
loaded (the _glass and _gold variants) skips the warm-up: the page cache is warm.
The ./raytracer binary is copied at the start, so a rebuild during the run changes nothing.

Writes build/bench/bench.md (the table, also printed to stdout) and build/bench/bench.json
(every run). Standard library only.

This file is the command line and the run's order; beside it: bench_common.py (settings,
messages), bench_process.py (running one process), bench_scenes.py (the scene list and
gen_mesh), bench_machine.py (machine, git, refrender probe), bench_measure.py (one scene's
runs), bench_report.py (the Markdown report).
"""
import argparse
import datetime
import fnmatch
import json
import os
import shutil
import sys
import tempfile
import time

import bench_process
from bench_common import CULL_MODES, DEFAULT_SHAPE_SIZES, DEFAULT_SIZES, REPO, log, loud
from bench_machine import git_state, loadavg, machine_info, refrender_problem, sha256
from bench_measure import bench_scene
from bench_process import Spawner, run_once
from bench_report import fmt_s, label, render_ratio, report
from bench_scenes import ensure_gen_mesh, ensure_generated, large_scenes, official_scenes


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=None, help="timed runs per program and scene (default 5, --quick 3)")
    ap.add_argument("--threads", type=int, default=len(os.sched_getaffinity(0)),
                    help="threads for both programs (default: all usable cores)")
    ap.add_argument("--quick", action="store_true", help="skip the 16M scenes; 3 runs unless --runs is given")
    ap.add_argument("--scenes", default=None,
                    help="comma-separated patterns (fnmatch or substring) of scene names, e.g. 'bunny,knot_1m*'")
    ap.add_argument("--sizes", default=",".join(DEFAULT_SIZES), help="knot mesh sizes (default 1M,4M,16M)")
    ap.add_argument("--shape-sizes", default=",".join(DEFAULT_SHAPE_SIZES),
                    help="sizes of the other generated shapes, blob/terrain/city/soup (default 1M; '' for none)")
    ap.add_argument("--cull-modes", default=",".join(CULL_MODES),
                    help="culling settings to measure every scene with, both programs (default cull,no-cull)")
    ap.add_argument("--raytracer", default=os.path.join(REPO, "raytracer"))
    ap.add_argument("--precision", choices=("double", "float"), default="double",
                    help="our precision (--precision of ./raytracer; default double)")
    ap.add_argument("--refrender", default=None, help="default: $RT_SHARED_DIR/tools/refrender or ../shared/tools/refrender")
    ap.add_argument("--gen-mesh", default=os.path.join(REPO, "build", "bench", "gen_mesh"))
    ap.add_argument("--out", default=os.path.join(REPO, "build", "bench"), help="where bench.md, bench.json and scenes/ go")
    ap.add_argument("--timeout", type=float, default=900, help="seconds before a run is killed (default 900)")
    ap.add_argument("--heavy", type=float, default=10,
                    help="a warm-up (or first run) longer than this makes a scene heavy (default 10 s)")
    ap.add_argument("--heavy-runs", type=int, default=3, help="timed runs of heavy scenes at most (default 3)")
    ap.add_argument("--cheap", type=float, default=1,
                    help="scenes whose warm-up is shorter get N separate phase-split runs (default 1 s)")
    ap.add_argument("--list", action="store_true", help="list the scenes and exit")
    a = ap.parse_args()
    if a.runs is None:
        a.runs = 3 if a.quick else 5
    if a.runs < 1 or a.threads < 1 or a.heavy_runs < 1:
        ap.error("--runs, --threads and --heavy-runs must be at least 1")
    sizes = [s.strip() for s in a.sizes.split(",") if s.strip()]
    shape_sizes = [s.strip() for s in a.shape_sizes.split(",") if s.strip()]
    cull_modes = [c.strip() for c in a.cull_modes.split(",") if c.strip()]
    if not cull_modes or any(c not in CULL_MODES for c in cull_modes):
        ap.error("--cull-modes takes cull, no-cull or both")
    if a.quick:
        sizes = [s for s in sizes if s.upper() != "16M"]

    shared = os.environ.get("RT_SHARED_DIR") or os.path.join(os.path.dirname(REPO), "shared")
    ref = a.refrender or os.path.join(shared, "tools", "refrender")
    scene_dir = os.path.join(a.out, "scenes")
    scenes = official_scenes(shared) + large_scenes(sizes, shape_sizes, scene_dir)
    if a.scenes:
        pats = [p.strip() for p in a.scenes.split(",") if p.strip()]
        scenes = [s for s in scenes if any(fnmatch.fnmatch(s["name"], p) or p in s["name"] for p in pats)]
    if a.list:
        for s in scenes:
            print(s["name"], s["path"])
        print(f"(each with --{' and --'.join(cull_modes)})")
        return 0
    if not scenes:
        log("no scenes selected")
        return 2

    if not (os.path.isfile(a.raytracer) and os.access(a.raytracer, os.X_OK)):
        log(f"bench: {a.raytracer} not found; build it first (make raytracer)")
        return 2
    os.makedirs(a.out, exist_ok=True)
    # Snapshot the binary: a rebuild during the benchmark must not change what is measured.
    snap_dir = tempfile.mkdtemp(prefix="rtbench-bin-")
    ours_bin = os.path.join(snap_dir, "raytracer")
    shutil.copy2(a.raytracer, ours_bin)

    bench_process.SPAWNER_PROC = Spawner()
    floor = run_once(["/bin/true"], 60, REPO)["maxrss"]

    problem = refrender_problem(ref)
    if problem:
        loud(f"REFRENDER CANNOT RUN: {problem}\n!! reporting our times only")
    ref_bin = None if problem else ref

    if any(s["kind"] == "large" for s in scenes):
        gen = ensure_gen_mesh(a.gen_mesh)
        bad = set()
        for s in scenes:
            if s["kind"] == "large" and s["base"] not in bad and not ensure_generated(s, gen, scene_dir):
                bad.add(s["base"])
        scenes = [s for s in scenes if s.get("base") not in bad]

    meta = {
        "cull_modes": cull_modes,
        "date": datetime.datetime.now().astimezone().isoformat(timespec="seconds"),
        "machine": machine_info(a.threads),
        "runs": a.runs,
        "heavy_runs": a.heavy_runs,
        "quick": a.quick,
        "raytracer": ("./" + os.path.relpath(os.path.abspath(a.raytracer), REPO)
                      if os.path.abspath(a.raytracer).startswith(REPO + os.sep) else a.raytracer),
        "raytracer_sha256": sha256(ours_bin),
        "precision": a.precision,
        "git": git_state(),
        "refrender": ref,
        "refrender_problem": problem,
        "loadavg_start": loadavg(),
        "rss_floor": floor,
    }
    log(f"bench: {len(scenes)} scenes x {len(cull_modes)} culling settings, {a.runs} runs each, {a.threads} threads, "
        f"{meta['machine']['cpu']}; load average {meta['loadavg_start']}")
    t_start = time.perf_counter()
    results, warmed = [], set()
    try:
        # Both culling settings of a scene back to back: the second finds its meshes in the page cache.
        jobs = [(s, c) for s in scenes for c in cull_modes]
        for i, (s, cull) in enumerate(jobs, 1):
            t0 = time.perf_counter()
            r, cheap, meshes = bench_scene(s, cull, a, ours_bin, ref_bin, warmed, meta["raytracer"])
            if not cheap:
                warmed |= meshes
            results.append(r)
            ratio = "" if r["ratio"] is None else f"  ratio {r['ratio']:.2f}"
            rr = render_ratio(r)
            rr = "" if rr is None else f", render ratio {rr:.2f}"
            log(f"[{i}/{len(jobs)}] {label(r)}: ours {fmt_s(r['ours_median'])} s"
                f"{'' if r['ours_ok'] else ' FAILED'}, ref {fmt_s(r['ref_median'])} s{ratio}{rr}"
                f"{' (heavy)' if r['heavy'] else ''} [{time.perf_counter() - t0:.0f}s]")
    except KeyboardInterrupt:
        log("interrupted: reporting the scenes done so far")
    finally:
        shutil.rmtree(snap_dir, ignore_errors=True)
        bench_process.SPAWNER_PROC.close()
    meta["elapsed"] = time.perf_counter() - t_start
    meta["loadavg_end"] = loadavg()

    md = report(results, meta)
    print(md, end="")
    with open(os.path.join(a.out, "bench.md"), "w", encoding="utf-8") as f:
        f.write(md)
    with open(os.path.join(a.out, "bench.json"), "w", encoding="utf-8") as f:
        json.dump({"meta": meta, "scenes": results}, f, indent=1)
    log(f"wrote {os.path.join(a.out, 'bench.md')} and bench.json")
    if problem:
        loud(f"REFRENDER CANNOT RUN: {problem} -- the table has our times only")
    return 1 if any(not r["ours_ok"] for r in results) else 0


if __name__ == "__main__":
    sys.exit(main())
