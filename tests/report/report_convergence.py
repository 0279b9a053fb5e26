#!/usr/bin/env python3
"""make report's assignment 3 section: the speed/accuracy trade of distribution ray tracing,
measured on every complete hw3 scene (docs/sampling.md). Standard library only.

    python3 tests/report/report_convergence.py --bin ./raytracer --rtdiff ./rtdiff [--quick]
                                               [--only NAME] [--out DIR] [--work DIR]

For each scene: a converged image (the sobol sampler at CONVERGED x its NumSamples, cached
under --work/converged), renders at 1, 4, 16, 64, 256 samples per pixel and at its own count
with the default sampler, each with its time and its error against the converged image and
against the course's reference; every sampler at the scene's count; adaptive sampling
(--noise-target, sobol) against the default sampler at the scene's count; and each feature's
cost at equal samples. Errors: RMSE in output levels, and the share of 16x16 blocks whose mean
is off by more than 3 levels (rtdiff --mc). Times: the CPU seconds of the raytracer process
(user + sys, all its threads), which other load on the machine changes less than wall time.
Written to --out as convergence.md, convergence.json and convergence.svg (report.py puts
the same section into index.md and index.html).
"""
import argparse
import json
import math
import os
import re
import resource
import subprocess
import sys

from report_common import REPO, log, loud

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # tests/
from shared_scenes import complete_rows  # noqa: E402

SPP = [1, 4, 16, 64, 256]
SAMPLERS = ["random", "stratified", "sobol"]
# Adaptive sampling: noise targets tried from the loosest down, until the error is no more
# than the default sampler's at the scene's count.
TARGETS = [16, 12, 8, 6, 4, 3, 2, 1.5, 1, 0.75, 0.5, 0.35, 0.25, 0.18, 0.12, 0.08]
CONVERGED_SEED = 1000003


def parse_mc_line(line):
    """The figures of rtdiff --mc's result line: % blocks off, the mean difference and the
    RMSE. The RMSE is printed to 2 decimals, too coarse to compare two renders near the
    quantisation floor (0.09 against 0.09), so it is taken from the PSNR (2 decimals of dB:
    0.06% of the RMSE): RMSE = 255 / 10^(PSNR / 20)."""
    nums = re.findall(r"[-+]?\d+\.\d+|[-+]?inf", line)
    psnr = float(nums[6])
    rmse = 255.0 / 10 ** (psnr / 20) if psnr != float("inf") else 0.0
    return {"blocks": float(nums[0]), "mean": float(nums[4]), "rmse": rmse}


class Hw3Scene:
    def __init__(self, rel, path, image, ref):
        self.key = rel[:-5].replace("/", "_")
        self.rel, self.path, self.image, self.ref = rel, path, image, ref
        with open(path, encoding="utf-8") as f:
            self.doc = json.load(f)
        cams = self.doc["Scene"]["Cameras"]["Camera"]
        cam = cams[0] if isinstance(cams, list) else cams
        self.samples = int(cam.get("NumSamples", "1"))


def hw3_scenes(shared):
    return [Hw3Scene(rel, os.path.join(shared, "scenes", "hw3", rel), image, os.path.join(shared, ref))
            for rel, image, ref in complete_rows(shared, "hw3")]


class Study:
    def __init__(self, a):
        self.a = a
        self.runs = {}

    def render(self, scene, tag, args, path=None):
        """Renders `scene` (or the scene file `path` in its place) into work/tag; returns
        {png, cpu, seconds, spp}."""
        out = os.path.join(self.a.work, "conv", scene.key, tag)
        os.makedirs(out, exist_ok=True)
        stats = os.path.join(out, "stats.json")
        cmd = [os.path.abspath(self.a.bin), "-q", "-j", str(self.a.threads), "-o", out, "--stats", stats] + args
        cmd.append(path or scene.path)
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        p = subprocess.run(cmd, cwd=os.path.dirname(scene.path), capture_output=True, text=True,
                           timeout=self.a.timeout)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        if p.returncode != 0:
            raise RuntimeError(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()}")
        with open(stats, encoding="utf-8") as f:
            rec = json.load(f)["images"][0]
        r = {"png": os.path.join(out, scene.image),
             "cpu": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
             "seconds": rec["seconds"]["render"], "spp": rec["samples"]["per_pixel"]}
        self.runs[f"{scene.key}/{tag}"] = r
        log(f"  {scene.key} {tag}: {r['cpu']:.2f} s CPU, {r['spp']:.1f} spp")
        return r

    def compare(self, a_png, b_png):
        """rtdiff --mc's figures of A against B: % blocks off by > 3 levels, mean diff, RMSE."""
        p = subprocess.run([self.a.rtdiff, "--mc", a_png, b_png], capture_output=True, text=True)
        for line in p.stdout.splitlines():
            if line.rstrip().endswith("dB") or line.rstrip().endswith("inf"):
                return parse_mc_line(line)
        raise RuntimeError(f"rtdiff --mc {a_png} {b_png}: {p.stdout}{p.stderr}")

    def converged(self, scene):
        n = self.a.converged * scene.samples
        path = os.path.join(self.a.work, "converged", f"{scene.key}_sobol_{n}.png")
        if not os.path.isfile(path):
            log(f"  {scene.key}: converged image, sobol at {n} samples per pixel (cached in {path})")
            r = self.render(scene, f"converged_{n}", ["--sampler", "sobol", "--samples", str(n),
                                                      "--seed", str(CONVERGED_SEED)])
            os.makedirs(os.path.dirname(path), exist_ok=True)
            os.replace(r["png"], path)
        return path, n

    def measured(self, scene, tag, args, conv, path=None):
        r = self.render(scene, tag, args, path)
        r["vs_converged"] = self.compare(r["png"], conv)
        r["vs_reference"] = self.compare(r["png"], scene.ref) if os.path.isfile(scene.ref) else None
        return r

    def scene_study(self, scene):
        conv, n_conv = self.converged(scene)
        res = {"scene": scene.rel, "samples": scene.samples, "converged_samples": n_conv, "spp": [],
               "samplers": {}, "adaptive": [], "features": []}
        counts = sorted(set(SPP + [scene.samples]))
        if self.a.quick:
            counts = sorted(set([1, 16, scene.samples]))
        for n in counts:
            r = self.measured(scene, f"spp{n}", ["--samples", str(n)], conv)
            res["spp"].append(dict(r, n=n))
        base = next(r for r in res["spp"] if r["n"] == scene.samples)  # the default sampler, sobol
        for s in SAMPLERS:
            res["samplers"][s] = base if s == "sobol" else self.measured(scene, f"{s}{scene.samples}",
                                                                        ["--sampler", s], conv)
        res["adaptive"] = self.adaptive(scene, conv, base)
        res["features"] = self.features(scene, base)
        return res

    def adaptive(self, scene, conv, base):
        """Adaptive sampling (sobol), E from the loosest down until its error is no more than
        uniform sampling's at the scene's samples, `base` (the default sampler's)."""
        out = []
        for e in TARGETS:
            r = self.measured(scene, f"adaptive{e}", ["--sampler", "sobol", "--noise-target", str(e)], conv)
            out.append(dict(r, target=e))
            if r["vs_converged"]["rmse"] <= base["vs_converged"]["rmse"]:
                break
        return out

    def features(self, scene, base):
        """Each feature the scene uses, turned off, at the scene's own samples."""
        out = []
        for name, change in feature_switches(scene.doc):
            doc = json.loads(json.dumps(scene.doc))
            change(doc["Scene"])
            absolute_paths(doc, os.path.dirname(scene.path))
            path = os.path.join(self.a.work, "conv", scene.key, f"no_{name}.json")
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w", encoding="utf-8") as f:
                json.dump(doc, f)
            r = self.render(scene, f"no_{name}", [], path)
            out.append({"feature": name, "on": base["cpu"], "off": r["cpu"]})
        return out


def as_list(v):
    return v if isinstance(v, list) else [v]


def feature_switches(doc):
    """(name, function turning it off in the Scene object) for each feature `doc` uses."""
    s = doc["Scene"]
    out = []
    cams = as_list(s["Cameras"]["Camera"])
    if any(float(c.get("ApertureSize", 0)) > 0 for c in cams):
        def no_lens(sc):
            for c in as_list(sc["Cameras"]["Camera"]):
                c.pop("ApertureSize", None)
                c.pop("FocusDistance", None)
        out.append(("lens", no_lens))
    if "AreaLight" in s.get("Lights", {}):
        def no_area(sc):
            lights = sc["Lights"]
            points = as_list(lights.get("PointLight", []))
            for i, al in enumerate(as_list(lights.pop("AreaLight"))):
                size = float(al["Size"])
                power = " ".join(str(float(x) * size * size) for x in al["Radiance"].split())
                points.append({"_id": str(1000 + i), "Position": al["Position"], "Intensity": power})
            lights["PointLight"] = points
        out.append(("area light (as a point light)", no_area))
    objects = s.get("Objects", {})
    if any("MotionBlur" in o for kind in objects.values() for o in as_list(kind) if isinstance(o, dict)):
        def no_motion(sc):
            for kind in sc["Objects"].values():
                for o in as_list(kind):
                    if isinstance(o, dict):
                        o.pop("MotionBlur", None)
        out.append(("motion blur", no_motion))
    mats = as_list(s.get("Materials", {}).get("Material", []))
    if any(float(m.get("Roughness", 0)) > 0 for m in mats if isinstance(m, dict)):
        def no_rough(sc):
            for m in as_list(sc["Materials"]["Material"]):
                if isinstance(m, dict):
                    m.pop("Roughness", None)
        out.append(("roughness", no_rough))
    return out


def absolute_paths(node, folder):
    """PLY paths made absolute, so that a changed copy of a scene reads the same files."""
    if isinstance(node, dict):
        for k, v in node.items():
            if k == "_plyFile" and isinstance(v, str) and not os.path.isabs(v):
                node[k] = os.path.normpath(os.path.join(folder, v))
            else:
                absolute_paths(v, folder)
    elif isinstance(node, list):
        for v in node:
            absolute_paths(v, folder)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True)
    ap.add_argument("--rtdiff", required=True)
    ap.add_argument("--out", default=os.path.join(REPO, "report"))
    ap.add_argument("--work", default=os.path.join(REPO, "build", "report"))
    ap.add_argument("--shared", default=os.environ.get("RT_SHARED_DIR") or os.path.join(REPO, "..", "shared"))
    ap.add_argument("--threads", type=int, default=len(os.sched_getaffinity(0)))
    ap.add_argument("--quick", action="store_true", help="counts 1, 16 and the scene's; converged at 4x")
    ap.add_argument("--converged", type=int, default=0, help="converged image's samples, x NumSamples "
                    "(default 8, --quick 4)")
    ap.add_argument("--only", action="append", default=[], help="a scene's key (e.g. cornellbox_area)")
    ap.add_argument("--timeout", type=float, default=7200)
    ap.add_argument("--adaptive-only", action="store_true",
                    help="adaptive sampling against uniform random and uniform sobol only (adaptive.json)")
    a = ap.parse_args()
    a.converged = a.converged or (4 if a.quick else 8)
    from report_convergence_doc import write  # the tables and the plot
    scenes = hw3_scenes(os.path.abspath(a.shared))
    if a.only:
        scenes = [s for s in scenes if s.key in a.only]
    if not scenes:
        loud(f"no complete hw3 scenes at {a.shared} (set RT_SHARED_DIR)")
        return 1
    study = Study(a)
    results = []
    for s in scenes:
        log(f"convergence: {s.rel} ({s.samples} samples per pixel)")
        if a.adaptive_only:
            conv, _ = study.converged(s)
            res = {"scene": s.rel, "samples": s.samples, "adaptive": {}}
            for sampler in ("random", "sobol"):
                base = study.measured(s, f"uniform_{sampler}", ["--sampler", sampler], conv)
                res["adaptive"][sampler] = {"uniform": base, "adaptive": study.adaptive(s, conv, base)}
            results.append(res)
        else:
            results.append(study.scene_study(s))
    if a.adaptive_only:
        os.makedirs(a.out, exist_ok=True)
        with open(os.path.join(a.out, "adaptive.json"), "w", encoding="utf-8") as f:
            json.dump(results, f, indent=1)
        return 0
    os.makedirs(a.out, exist_ok=True)
    write(a, results)
    return 0


if __name__ == "__main__":
    sys.exit(main())
