#!/usr/bin/env python3
"""make report: the blog companion. Renders every complete official scene and our own
scenes with back-face culling off and on, several runs each, and measures what each
speed/accuracy switch costs. Standard library only.

    python3 tests/report/report.py --bin B --imgdiff B [--gen-mesh B]
                                   [--out report] [--runs 3] [--repeat 1] [--threads N] [--quick]
    make report / make report-quick          (extra arguments: REPORT_ARGS="...")

Writes into --out (default report/, gitignored):
  index.md, index.html  the tables, the chart and the images side by side
  chart.svg             render time per image, culling off and on
  report.json           every run's figures (the raytracer's --stats records) and every comparison
  img/                  our renders, the references, and pictures of what culling changes

Method. Every run is a whole ./raytracer process with --stats, -q and -j THREADS, writing
into a fresh folder; the images of a configuration's first run are kept. Times are the
raytracer's own figures (render = tracing only; BVH build separately), the median over
--runs processes (default 3; --quick: 1, fewer BVH variants, no generated 1M-triangle mesh),
each rendering every image --repeat times (raytracer --repeat; default 1; --quick: 3).
Runs are interleaved: round 1 of every configuration of a study, then round 2, ...
A ratio of two times is marked "within noise" when the fastest and slowest of all the
renders of one configuration (every process, every repeat) overlap the other's: the
spread of the runs covers the difference.
Accuracy: pixels off by more than one level against the course's reference image (the
conformance tests' measure), and pixels changed against our default double-precision
render (for our scenes, which have no reference), counted by build/report/imgdiff.

Studies (each switch is a raytracer option, see README "Measurements"):
  culling      --no-cull against the default --cull, every scene (the blog table)
  precision    --precision float against double, every scene, alone and with --no-cull,
               and simple.json / spheres.json moved 1e2, 1e3 and 1e4 away from the origin
  epsilon      --epsilon-scale 0.1 and 10: pixels newly darker (acne) and brighter (leaks)
  weak rays    --min-weight 0 (every ray traced to MaxRecursionDepth) against the default 1e-4
  depth        --max-depth 0..8 on the scenes with mirrors, conductors or glass:
               time against the pixels that still change from depth d-1 to d
  bvh          --bvh-leaf, --bvh-bins, --bvh-split median on the scenes of 5000+ triangles
               (and a generated 1M-triangle mesh): build time against render time
  assignment 3 every complete hw3 scene: error against a converged image and the reference
               over samples and time, the samplers, adaptive sampling, each feature's cost
               (report_convergence.py; with --rtdiff)
"""
# This file is the command line, the configurations and the order of the studies' runs;
# beside it: report_common.py (repository, messages), report_scenes.py (the scene sets),
# report_runner.py (the runs and imgdiff), report_timing.py (timings, ratios, numbers),
# report_doc.py (Markdown and HTML), report_chart.py (the SVG chart), report_machine.py,
# report_write.py (the comparisons, tables and files).
import argparse
import os
import shutil
import sys
import time

from report_common import REPO, log, loud
from report_convergence import Study, hw3_scenes
from report_convergence_doc import section, svg_plot
from report_runner import Differ, Runner
from report_scenes import big_scene, far_scenes, official_scenes, our_scenes
from report_write import Writeup


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="the raytracer")
    ap.add_argument("--imgdiff", required=True)
    ap.add_argument("--rtdiff", default="", help="rtdiff, for assignment 3's section (without: no section)")
    ap.add_argument("--gen-mesh", default="")
    ap.add_argument("--out", default=os.path.join(REPO, "report"))
    ap.add_argument("--work", default=os.path.join(REPO, "build", "report"))
    ap.add_argument("--shared", default=os.environ.get("RT_SHARED_DIR") or os.path.join(REPO, "..", "shared"))
    ap.add_argument("--runs", type=int, default=0, help="processes per configuration (default 3, --quick 1)")
    ap.add_argument("--repeat", type=int, default=0,
                    help="renders per image in each process, raytracer --repeat (default 1, --quick 3)")
    ap.add_argument("--threads", type=int, default=len(os.sched_getaffinity(0)))
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--timeout", type=float, default=600)
    a = ap.parse_args()
    runs = a.runs or (1 if a.quick else 3)
    repeat = a.repeat or (3 if a.quick else 1)
    t_start = time.perf_counter()

    for b in (a.bin, a.imgdiff):
        if not os.access(b, os.X_OK):
            sys.exit(f"report.py: {b} is not an executable")
    os.makedirs(a.work, exist_ok=True)
    shared = os.path.abspath(a.shared)
    official = official_scenes(shared) if os.path.isdir(shared) else []
    if not official:
        loud(f"no official scenes at {shared} (set RT_SHARED_DIR): the report covers our scenes only")
    ours = our_scenes()
    far = far_scenes(shared, a.work) if official else []
    big = big_scene(a.gen_mesh, a.work) if a.gen_mesh and os.access(a.gen_mesh, os.X_OK) and not a.quick else None
    main_set = official + ours

    configs = {
        "double": [],
        "nocull": ["--no-cull"],
        "float": ["--precision", "float"],
        "float_nocull": ["--precision", "float", "--no-cull"],
        "eps0.1": ["--epsilon-scale", "0.1"],
        "eps10": ["--epsilon-scale", "10"],
        "minw0": ["--min-weight", "0"],
        # Each study times its own default runs, interleaved with its variants, so that a
        # change in the machine's load between studies cannot pass for an effect.
        "double_prec": [],
        "eps1": [],
        "depth_default": [],
        "minw_default": [],
    }
    depths = list(range(0, 9))
    for d in depths:
        configs[f"depth{d}"] = ["--max-depth", str(d)]
    bvh_variants = [("leaf 1", ["--bvh-leaf", "1"]), ("leaf 2", ["--bvh-leaf", "2"]), ("leaf 4", ["--bvh-leaf", "4"]),
                    ("leaf 8, 16 bins, SAH (default)", None), ("leaf 16", ["--bvh-leaf", "16"]),
                    ("leaf 32", ["--bvh-leaf", "32"]), ("8 bins", ["--bvh-bins", "8"]),
                    ("4 bins", ["--bvh-bins", "4"]), ("object median, no SAH", ["--bvh-split", "median"])]
    if a.quick:
        bvh_variants = [v for v in bvh_variants if v[0] in ("leaf 1", "leaf 4", "leaf 8, 16 bins, SAH (default)",
                                                            "leaf 16", "object median, no SAH")]
    bvh_configs = []
    for name, opts in bvh_variants:
        cfg = "bvh_default" if opts is None else "bvh_" + "_".join(opts).replace("--", "")
        configs[cfg] = opts or []
        bvh_configs.append((name, cfg))

    # A copy of the binary: a rebuild during the run changes nothing.
    bins_dir = os.path.join(a.work, "run-bin")
    os.makedirs(bins_dir, exist_ok=True)
    copy = os.path.join(bins_dir, "raytracer")
    shutil.copy2(a.bin, copy)
    configs = {name: (copy, o) for name, o in configs.items()}

    R = Runner(configs, a.threads, repeat, a.work, a.timeout)
    D = Differ(a.imgdiff)
    log(f"report: {len(official)} official scenes, {len(ours)} of ours, {runs} run(s) of --repeat {repeat} each, "
        f"-j {a.threads}")

    # --- 1. culling off/on -------------------------------------------------------------
    R.measure(["nocull", "double"], main_set, runs, "culling")
    # --- 2. precision --------------------------------------------------------------------
    R.measure(["double_prec", "float", "float_nocull"], main_set, runs, "precision")
    R.measure(["double", "float"], far, 1, "far from the origin")
    # --- 3. epsilon ------------------------------------------------------------------------
    R.measure(["eps0.1", "eps1", "eps10"], main_set, runs, "epsilon")
    # --- 3b. --min-weight 0: every ray to MaxRecursionDepth -------------------------------
    R.measure(["minw0", "minw_default"], main_set, runs, "min-weight")
    # --- 4. depth ---------------------------------------------------------------------------
    depth_set = [s for s in main_set if s.reflective]
    R.measure([f"depth{d}" for d in depths] + ["depth_default"], depth_set, runs, "depth")
    # --- 5. BVH ------------------------------------------------------------------------------
    bvh_set = [s for s in main_set if R.ok("double", s) and
               max((R.record("double", s, im)["primitives"]["triangles"] for im in R.images("double", s)),
                   default=0) >= 5000]
    if big:
        bvh_set.append(big)
    R.measure([c for _, c in bvh_configs], bvh_set, runs, "bvh")

    w = Writeup(a, R, D, runs, repeat, configs, official, main_set, far, big, depths, depth_set, bvh_set,
                bvh_configs, t_start)
    w.intro()
    w.culling()
    w.trade()
    w.far_from_origin()
    w.epsilon()
    w.depth()
    w.bvh()
    # --- 6. assignment 3: samples, time and error (report_convergence.py) -----------------
    if a.rtdiff and official:
        hw3 = hw3_scenes(shared)
        study = Study(argparse.Namespace(bin=copy, rtdiff=a.rtdiff, work=a.work, threads=a.threads,
                                         timeout=a.timeout, quick=a.quick, converged=4 if a.quick else 8))
        results = [study.scene_study(s) for s in hw3]
        section(w.doc, results, 4 if a.quick else 8)
        with open(os.path.join(a.out, "convergence.svg"), "w", encoding="utf-8") as f:
            f.write(svg_plot(results))
        w.data["convergence"] = results
    return w.write()


if __name__ == "__main__":
    sys.exit(main())
