#!/usr/bin/env python3
"""Assignment 2 benchmark (make bench-hw2; make bench runs it after bench.py).

1. The complete scenes of ../shared/scenes/hw2/MANIFEST.tsv: whole process, render phase and
   peak memory, medians of --runs runs. (refrender, the yardstick of bench.py, ignores
   Transformations and MeshInstance, so it renders other images: it is not timed here.)
2. The instancing stress scene: a grid of --grid x --grid copies of the 1M-triangle knot
   (gen_mesh's knot_1m.ply), the mesh itself and MeshInstances, against one 1M-triangle mesh
   (terrain_1m.ply) stretched over the same part of the same view: render time, memory, and
   the memory each instance adds.
3. One animation (default raven/camera_around_david, 360 frames): every frame by one
   process, against one process per frame, run one after the other (wall time).

Writes build/bench/hw2.md and prints it.
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # tests/
from shared_scenes import complete_rows  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def run(cmd, cwd=None):
    """Wall seconds, peak RSS of the child (bytes), and --stats of the run when asked."""
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: exit {p.returncode}: {p.stderr.strip()[-400:]}")
    return wall


def timed_render(rt, scene, out, runs, extra=()):
    """Medians over `runs` processes: wall seconds, render seconds (summed over cameras), peak RSS
    MiB, RSS MiB when the render ended (the render data; what loading freed handed back)."""
    walls, renders, rss, resident = [], [], [], []
    with tempfile.TemporaryDirectory() as tmp:
        stats = os.path.join(tmp, "stats.json")
        for _ in range(runs):
            walls.append(run([rt, "-q", "-o", out, "--stats", stats, *extra, scene]))
            with open(stats, encoding="utf-8") as f:
                images = json.load(f)["images"]
            renders.append(sum(im["seconds"]["render"] for im in images))
            rss.append(max(im["peak_rss_bytes"] for im in images) / 2**20)
            resident.append(max(im["render_rss_bytes"] for im in images) / 2**20)
    return statistics.median(walls), statistics.median(renders), statistics.median(rss), statistics.median(resident)


def hw2_scenes(shared):
    return [os.path.join(shared, "scenes", "hw2", rel) for rel, _, _ in complete_rows(shared, "hw2")]


def stress_scenes(scene_dir, grid, single=True):
    """Writes instances_<n>.json (grid x grid knots: the mesh and MeshInstances moved by
    translations) and instances_single.json (one 1M-triangle terrain stretched over the same
    area, unless `single` is false), both with the same camera; returns their paths (None for the
    one not written)."""
    spacing = 320.0  # the knot's box is about 284 x 240 x 272
    side = spacing * grid
    centre = side / 2
    camera = {"_id": "1", "_type": "lookAt", "Position": f"{centre} {-0.55 * side} {0.75 * side}",
              "GazePoint": f"{centre} {centre} 0", "Up": "0 0 1", "FovY": "50", "NearDistance": "1",
              "ImageResolution": "800 480"}
    power = 2e8 * grid * grid  # about 100 levels of diffuse on the grid
    lights = {"AmbientLight": "25 25 25",
              "PointLight": [{"_id": "1", "Position": f"{centre} {-side} {2 * side}",
                              "Intensity": f"{power} {power} {power}"}]}
    material = {"_id": "1", "AmbientReflectance": "0.15 0.12 0.1", "DiffuseReflectance": "0.55 0.42 0.32",
                "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "40"}
    translations = [{"_id": str(k + 1), "_data": f"{(k % grid) * spacing} {(k // grid) * spacing} 0"}
                    for k in range(grid * grid)]
    n = grid * grid
    many = {"Scene": {
        "Cameras": {"Camera": dict(camera, ImageName=f"instances_{n}.png")},
        "Lights": lights, "Materials": {"Material": material},
        "Transformations": {"Translation": translations},
        "Objects": {
            "Mesh": {"_id": "1", "Material": "1", "Transformations": "t1", "Faces": {"_plyFile": "knot_1m.ply"}},
            "MeshInstance": [{"_id": str(k + 1), "_baseMeshId": "1", "_resetTransform": "true",
                              "Transformations": f"t{k + 1}"} for k in range(1, n)]}}}
    # The same area filled by one 1M-triangle mesh: gen_mesh's terrain (x -1000..1000, y -200..5800,
    # heights -64..162, as tall as a knot) stretched over the grid.
    one = {"Scene": {
        "Cameras": {"Camera": dict(camera, ImageName="instances_single.png")},
        "Lights": lights, "Materials": {"Material": material},
        "Transformations": {"Scaling": {"_id": "1", "_data": f"{side / 2000} {side / 6000} 1"},
                            "Translation": {"_id": "1", "_data": f"{centre} {200 * side / 6000} 0"}},
        "Objects": {"Mesh": {"_id": "1", "Material": "1", "Transformations": "s1 t1",
                             "Faces": {"_plyFile": "terrain_1m.ply"}}}}}
    paths = []
    for name, doc in ((f"instances_{n}.json", many), ("instances_single.json", one)):
        if doc is one and not single:
            paths.append(None)
            continue
        path = os.path.join(scene_dir, name)
        with open(path, "w", encoding="utf-8") as f:
            json.dump(doc, f)
        paths.append(path)
    return paths


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--raytracer", default=os.path.join(REPO, "raytracer"))
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--grid", type=int, default=100, help="the stress grid's side (default 100: 10,000 knots)")
    ap.add_argument("--animation", default="raven/camera_around_david", help="folder of frames under scenes/hw2")
    ap.add_argument("--frames", type=int, default=0, help="time only the first N frames (default all)")
    ap.add_argument("--out", default=os.path.join(REPO, "build", "bench"))
    a = ap.parse_args()
    shared = os.environ.get("RT_SHARED_DIR") or os.path.join(os.path.dirname(REPO), "shared")
    rt = os.path.abspath(a.raytracer)
    scene_dir = os.path.join(a.out, "scenes")
    md = ["# Assignment 2 benchmark", "",
          f"- ours: {os.path.relpath(rt, REPO)}, {a.runs} runs each (medians), all cores; "
          f"{os.cpu_count()} hardware threads", ""]
    with tempfile.TemporaryDirectory() as out:
        md += ["## The complete scenes", "",
               "| scene | whole process s | render s | peak MiB |", "| --- | ---: | ---: | ---: |"]
        for scene in hw2_scenes(shared):
            w, r, m, _ = timed_render(rt, scene, out, a.runs)
            md.append(f"| {os.path.relpath(scene, os.path.join(shared, 'scenes', 'hw2'))} | {w:.3f} | {r:.3f} | "
                      f"{m:.1f} |")
            log(md[-1])

        for ply in ("knot_1m.ply", "terrain_1m.ply"):
            if not os.path.isfile(os.path.join(scene_dir, ply)):
                log(f"{os.path.join(scene_dir, ply)} is missing: run make bench-quick (or bench.py) once to generate it")
                return 2
        many, one = stress_scenes(scene_dir, a.grid)
        alone, _ = stress_scenes(scene_dir, 1, single=False)  # the base mesh without instances: the memory baseline
        n = a.grid * a.grid
        wm, rm, mm, em = timed_render(rt, many, out, a.runs)
        ws, rs, ms, es = timed_render(rt, one, out, a.runs)
        wb, rb, mb, eb = timed_render(rt, alone, out, a.runs)
        per = (mm - mb) * 2**20 / (n - 1)
        per_render = (em - eb) * 2**20 / (n - 1)
        md += ["", "## Instancing stress", "",
               f"{n:,} copies of the 1M-triangle knot (the mesh and {n - 1:,} MeshInstances), against one "
               f"1M-triangle mesh (gen_mesh's terrain) stretched over the same area, same camera, 800x480:", "",
               "| scene | whole process s | render s | peak MiB | resident at render MiB |",
               "| --- | ---: | ---: | ---: | ---: |",
               f"| {n:,} instances | {wm:.3f} | {rm:.3f} | {mm:.1f} | {em:.1f} |",
               f"| one mesh | {ws:.3f} | {rs:.3f} | {ms:.1f} | {es:.1f} |",
               f"| the knot alone | {wb:.3f} | {rb:.3f} | {mb:.1f} | {eb:.1f} |", "",
               f"Render time {rm / rs:.2f}x the single mesh's. Each added instance, against the knot alone: "
               f"{per_render:.0f} bytes of render data (resident at render), {per:.0f} bytes of peak memory."]
        log("\n".join(md[-7:]))

        folder = os.path.join(shared, "scenes", "hw2", a.animation)
        frames = sorted(os.path.join(folder, f) for f in os.listdir(folder) if f.endswith(".json"))
        if a.frames:
            frames = frames[:a.frames]
        t_one = run([rt, "-q", "-o", out, *frames])
        t0 = time.perf_counter()
        for f in frames:
            run([rt, "-q", "-o", out, f])
        t_each = time.perf_counter() - t0
        md += ["", "## An animation", "",
               f"{a.animation}: {len(frames)} frames, 800x800.", "",
               "| how | wall s | s per frame |", "| --- | ---: | ---: |",
               f"| one process, every frame | {t_one:.1f} | {t_one / len(frames):.3f} |",
               f"| one process per frame | {t_each:.1f} | {t_each / len(frames):.3f} |"]
        log("\n".join(md[-4:]))
    text = "\n".join(md) + "\n"
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "hw2.md"), "w", encoding="utf-8") as f:
        f.write(text)
    print(text, end="")
    return 0


if __name__ == "__main__":
    sys.exit(main())
