"""bench.py's scenes: the official ones from the course's manifest and the generated large
ones (gen_mesh, built and run when its output is missing or older than it)."""
import json
import os
import subprocess
import time

from bench_common import REPO, SHAPES, log, loud


def official_scenes(shared):
    manifest = os.path.join(shared, "scenes", "hw1", "MANIFEST.tsv")
    if not os.path.isfile(manifest):
        loud(f"official scenes not found: {manifest} is missing (set RT_SHARED_DIR); benchmarking our scenes only")
        return []
    seen, scenes = set(), []
    with open(manifest, encoding="utf-8") as f:
        for line in f:
            if line.startswith("#") or not line.strip():
                continue
            cols = line.rstrip("\n").split("\t")
            if len(cols) >= 4 and cols[3].strip() == "complete" and cols[0] not in seen:
                seen.add(cols[0])
                path = os.path.join(shared, "scenes", "hw1", cols[0])
                scenes.append({"name": cols[0][:-5] if cols[0].endswith(".json") else cols[0],
                               "path": path, "kind": "official"})
    return scenes


def large_scenes(sizes, shape_sizes, scene_dir):
    scenes = []
    for shape, variants in SHAPES.items():
        for size in (sizes if shape == "knot" else shape_sizes):
            base = f"{shape}_{size.lower()}"
            for v in variants:
                scenes.append({"name": f"{base}_{v}", "path": os.path.join(scene_dir, f"{base}_{v}.json"),
                               "kind": "large", "size": size, "base": base, "shape": shape})
    return scenes


def ensure_gen_mesh(path):
    if os.path.isfile(path) and os.access(path, os.X_OK):
        return path
    src_dir = os.path.join(REPO, "tests", "bench", "gen_mesh")
    srcs = sorted(os.path.join(src_dir, f) for f in os.listdir(src_dir) if f.endswith(".cpp"))
    os.makedirs(os.path.dirname(path), exist_ok=True)
    cxx = os.environ.get("CXX", "g++")
    cmd = [cxx, "-O2", "-std=c++17", "-ffp-contract=off", "-o", path] + srcs
    log("building gen_mesh: " + " ".join(cmd))
    subprocess.run(cmd, check=True)
    return path


def ensure_generated(scene, gen_mesh, scene_dir):
    """(Re)generates a large scene's mesh and JSONs when missing or older than gen_mesh."""
    ply = os.path.join(scene_dir, scene["base"] + ".ply")
    files = [ply] + [os.path.join(scene_dir, f"{scene['base']}_{v}.json") for v in SHAPES[scene["shape"]]]
    gen_time = os.path.getmtime(gen_mesh)
    if all(os.path.isfile(f) and os.path.getmtime(f) >= gen_time for f in files):
        return True
    os.makedirs(scene_dir, exist_ok=True)
    log(f"generating {scene['base']} ({scene['size']} triangles) ...")
    t0 = time.perf_counter()
    r = subprocess.run([gen_mesh, "--shape", scene["shape"], "--out-dir", scene_dir, "--name", scene["base"],
                        scene["size"]],
                       capture_output=True, text=True)
    if r.returncode != 0:
        loud(f"gen_mesh failed for {scene['base']}: {r.stderr.strip()}")
        return False
    log(f"  {r.stdout.strip()} [{time.perf_counter() - t0:.1f}s]")
    return True


def mesh_files(scene_path):
    """The PLY files a scene reads (a key for 'these inputs were already loaded')."""
    try:
        with open(scene_path, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, ValueError):
        return frozenset()
    found = []

    def walk(x):
        if isinstance(x, dict):
            for k, v in x.items():
                if k == "_plyFile" and isinstance(v, str):
                    found.append(os.path.normpath(os.path.join(os.path.dirname(scene_path), v)))
                else:
                    walk(v)
        elif isinstance(x, list):
            for v in x:
                walk(v)

    walk(doc)
    return frozenset(found)
