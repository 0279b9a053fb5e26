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
quoted. Ours runs with -q on cheap scenes. Peak RSS comes from os.wait4 (see SPAWNER below).
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
"""
import argparse
import datetime
import fnmatch
import hashlib
import json
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DEFAULT_SIZES = ["1M", "4M", "16M"]
# Generated shapes (gen_mesh --shape) and their scene variants; the knot runs at --sizes,
# the others at --shape-sizes.
SHAPES = {"knot": ["plain", "glass", "gold"], "blob": ["plain", "glass"], "terrain": ["plain"],
          "city": ["plain"], "soup": ["plain"]}
DEFAULT_SHAPE_SIZES = ["1M"]
CULL_MODES = ["cull", "no-cull"]  # the flag passed to both programs

OURS_LINE = re.compile(
    r"^(?P<image>.*): (?P<w>\d+)x(?P<h>\d+), (?P<precision>double|float), (?P<tris>\d+) triangles?, "
    r"(?P<spheres>\d+) spheres?, "
    r"load (?P<load>[\d.eE+-]+)s, bvh (?P<bvh>[\d.eE+-]+)s, render (?P<render>[\d.eE+-]+)s, "
    r"write (?P<write>[\d.eE+-]+)s(, \d+ warnings?)?\s*$")
REF_LINE = re.compile(
    r"^(?P<image>\S+) parse=(?P<parse>[\d.eE+-]+)s bvh=(?P<bvh>[\d.eE+-]+)s render=(?P<render>[\d.eE+-]+)s "
    r"rays=(?P<rays>\d+) rays/s=(?P<rps>[\d.eE+-]+)")


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def loud(msg):
    bar = "!" * 78
    log(f"\n{bar}\n!! {msg}\n{bar}\n")


# ---------------------------------------------------------------- running one process

# Peak RSS comes from os.wait4, and Linux carries a process's high-water RSS across exec:
# a program forked from this interpreter would report at least this interpreter's RSS.
# So processes are started by a lean helper interpreter (python3 -S, a few MiB), which
# forks, execs, waits (os.wait4) and reports; its own size is the floor of every reading
# (measured with /bin/true, and stated in the report).
SPAWNER = r"""
import os, signal, sys, time
def main():
    inp, out = sys.stdin.buffer, sys.stdout
    while True:
        line = inp.readline()
        if not line:
            return
        f = line.rstrip(b"\n").split(b"\0")
        timeout, cwd, so, se, argv = float(f[0]), f[1], f[2], f[3], f[4:]
        t0 = time.perf_counter()
        pid = os.fork()
        if pid == 0:
            try:
                os.setsid()
                os.chdir(cwd)
                os.dup2(os.open("/dev/null", os.O_RDONLY), 0)
                os.dup2(os.open(so, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644), 1)
                os.dup2(os.open(se, os.O_WRONLY | os.O_CREAT | os.O_TRUNC, 0o644), 2)
                os.execv(argv[0], argv)
            except BaseException as e:
                os.write(2, ("cannot run %r: %s\n" % (argv[0], e)).encode())
            os._exit(127)
        killed = []
        def kill(*_):
            killed.append(1)
            try:
                os.killpg(pid, signal.SIGKILL)
            except OSError:
                pass
        signal.signal(signal.SIGALRM, kill)
        signal.setitimer(signal.ITIMER_REAL, timeout)
        _, status, ru = os.wait4(pid, 0)
        wall = time.perf_counter() - t0
        signal.setitimer(signal.ITIMER_REAL, 0)
        out.write("%d %.6f %d %.6f %d\n" % (os.waitstatus_to_exitcode(status), wall, ru.ru_maxrss,
                                            ru.ru_utime + ru.ru_stime, 1 if killed else 0))
        out.flush()
main()
"""


class Spawner:
    def __init__(self):
        self.proc = subprocess.Popen([sys.executable, "-S", "-E", "-c", SPAWNER], stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE)

    def run(self, argv, timeout, cwd, out_path, err_path):
        fields = [repr(float(timeout)), cwd, out_path, err_path] + list(argv)
        if any("\0" in x or "\n" in x for x in fields):
            raise ValueError(f"argument with a NUL or newline: {fields!r}")
        self.proc.stdin.write(b"\0".join(os.fsencode(x) for x in fields) + b"\n")
        self.proc.stdin.flush()
        reply = self.proc.stdout.readline().split()
        if len(reply) != 5:
            raise RuntimeError("process spawner died")
        return int(reply[0]), float(reply[1]), int(reply[2]) * 1024, float(reply[3]), reply[4] == b"1"

    def close(self):
        self.proc.stdin.close()
        self.proc.wait()


SPAWNER_PROC = None


def run_once(cmd, timeout, cwd):
    """Runs cmd as a whole process; returns wall seconds, peak RSS, CPU seconds, output."""
    tmp = tempfile.mkdtemp(prefix="rtbench-")
    outdir = os.path.join(tmp, "out")
    os.mkdir(outdir)
    cmd = [outdir if a == "{outdir}" else a for a in cmd]
    out_path, err_path = os.path.join(tmp, "stdout"), os.path.join(tmp, "stderr")
    try:
        rc, wall, maxrss, cpu, timed_out = SPAWNER_PROC.run(cmd, timeout, cwd, out_path, err_path)
        with open(out_path, "rb") as f:
            stdout = f.read(1 << 20).decode("utf-8", "replace")
        with open(err_path, "rb") as f:
            stderr = f.read(1 << 20).decode("utf-8", "replace")
        return {"wall": wall, "rc": rc, "timed_out": timed_out, "maxrss": maxrss, "cpu": cpu,
                "stdout": stdout, "stderr": stderr}
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def ok(r):
    return r is not None and r["rc"] == 0 and not r["timed_out"]


def failure_text(r):
    if r["timed_out"]:
        return f"timed out after {r['wall']:.1f}s"
    rc = r["rc"]
    what = f"killed by signal {-rc}" if rc < 0 else f"exit status {rc}"
    tail = " | ".join(r["stderr"].strip().splitlines()[-3:])
    return f"{what}: {tail}" if tail else what


def parse_ours(stderr):
    lines = [m.groupdict() for m in map(OURS_LINE.match, stderr.splitlines()) if m]
    if not lines:
        return None
    # load and bvh are per scene file (repeated on each image's line); render and write per image.
    return {
        "images": len(lines),
        "triangles": int(lines[0]["tris"]),
        "spheres": int(lines[0]["spheres"]),
        "load": float(lines[0]["load"]),
        "bvh": float(lines[0]["bvh"]),
        "render": sum(float(x["render"]) for x in lines),
        "write": sum(float(x["write"]) for x in lines),
    }


def parse_ref(stdout):
    lines = [m.groupdict() for m in map(REF_LINE.match, stdout.splitlines()) if m]
    if not lines:
        return None
    return {
        "images": len(lines),
        "parse": float(lines[0]["parse"]),
        "bvh": float(lines[0]["bvh"]),
        "render": sum(float(x["render"]) for x in lines),
        "rays": sum(int(x["rays"]) for x in lines),
    }


def median(xs):
    return statistics.median(xs) if xs else None


def median_phases(phase_list):
    phase_list = [p for p in phase_list if p]
    if not phase_list:
        return None
    return {k: (median([p[k] for p in phase_list]) if isinstance(phase_list[0][k], float) else phase_list[0][k])
            for k in phase_list[0]}


# ---------------------------------------------------------------- scenes

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


# ---------------------------------------------------------------- machine

def cpu_model():
    """The CPU's model name (tests/report/report.py uses it too)."""
    cpu = platform.processor() or "unknown"
    try:
        with open("/proc/cpuinfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    return cpu


def machine_info(threads):
    cpu = cpu_model()
    mem = None
    try:
        with open("/proc/meminfo", encoding="utf-8") as f:
            for line in f:
                if line.startswith("MemTotal:"):
                    mem = int(line.split()[1]) * 1024
    except OSError:
        pass
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "usable_cores": len(os.sched_getaffinity(0)),
        "threads": threads,
        "memory_bytes": mem,
        "kernel": platform.release(),
        "python": platform.python_version(),
    }


def loadavg():
    try:
        with open("/proc/loadavg", encoding="utf-8") as f:
            return " ".join(f.read().split()[:3])
    except OSError:
        return "?"


def git_state():
    try:
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=REPO, capture_output=True,
                              text=True).stdout.strip()
        dirty = subprocess.run(["git", "status", "--porcelain", "--untracked-files=no"], cwd=REPO,
                               capture_output=True, text=True).stdout.strip()
        return head + ("+dirty" if dirty else "") if head else "unknown"
    except OSError:
        return "unknown"


def sha256(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


PROBE_SCENE = {"Scene": {
    "Cameras": {"Camera": {"_id": "1", "Position": "0 0 0", "Gaze": "0 0 -1", "Up": "0 1 0",
                           "NearPlane": "-1 1 -1 1", "NearDistance": "1", "ImageResolution": "8 8",
                           "ImageName": "probe.png"}},
    "Lights": {"AmbientLight": "25 25 25", "PointLight": {"_id": "1", "Position": "0 0 0",
                                                          "Intensity": "1000 1000 1000"}},
    "Materials": {"Material": {"_id": "1", "AmbientReflectance": "1 1 1", "DiffuseReflectance": "1 1 1",
                               "SpecularReflectance": "0 0 0", "PhongExponent": "1"}},
    "VertexData": {"_data": "0 0 -5", "_type": "xyz"},
    "Objects": {"Sphere": {"_id": "1", "Material": "1", "Center": "1", "Radius": "1"}}}}


def refrender_problem(ref):
    """None when refrender renders a tiny scene, else why not."""
    if not os.path.isfile(ref):
        return f"{ref} does not exist"
    if not os.access(ref, os.X_OK):
        return f"{ref} is not executable"
    tmp = tempfile.mkdtemp(prefix="rtbench-probe-")
    try:
        scene = os.path.join(tmp, "probe.json")
        with open(scene, "w", encoding="utf-8") as f:
            json.dump(PROBE_SCENE, f)
        try:
            r = subprocess.run([ref, "--threads", "1", "--outdir", tmp, scene], capture_output=True, text=True,
                               timeout=60)
        except (OSError, subprocess.TimeoutExpired) as e:
            return f"{ref} cannot run: {e}"
        if r.returncode != 0 or not os.path.isfile(os.path.join(tmp, "probe.png")):
            msg = (r.stderr or r.stdout).strip().splitlines()
            hint = (" (runtime packages: apt-get install -y libembree3-3 libstb0)"
                    if r.returncode == 127 or "shared libraries" in r.stderr else "")
            return f"{ref} failed on a tiny scene, status {r.returncode}: {msg[0] if msg else ''}{hint}"
        return None
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


# ---------------------------------------------------------------- the benchmark of one scene

def bench_scene(scene, cull, a, ours_bin, ref_bin, warmed, ours_shown):
    """One scene under one culling setting (cull: "cull" or "no-cull", the flag for both)."""
    name = scene["name"] + ("" if cull == "cull" else " (no-cull)")  # in messages and notes
    flag = "--" + cull
    prec = ["--precision", a.precision]
    ours_cmd = [ours_bin, "-q", "-j", str(a.threads)] + prec + [flag, "-o", "{outdir}", scene["path"]]
    ours_loud_cmd = [ours_bin, "-j", str(a.threads)] + prec + [flag, "-o", "{outdir}", scene["path"]]
    ref_cmd = ([ref_bin, "--threads", str(a.threads), flag, "--outdir", "{outdir}", scene["path"]]
               if ref_bin else None)
    res = {"name": scene["name"], "cull": cull, "kind": scene["kind"], "path": scene["path"],
           "ours_cmd": " ".join([ours_shown] + ours_cmd[1:]).replace("{outdir}", "OUTDIR"),
           "ref_cmd": " ".join(ref_cmd).replace("{outdir}", "OUTDIR") if ref_cmd else None,
           "ours_runs": [], "ref_runs": [], "phase_runs": [], "notes": []}
    meshes = mesh_files(scene["path"])
    ours_ok, ref_ok = True, ref_cmd is not None

    def record(r):
        return {k: r[k] for k in ("wall", "rc", "timed_out", "maxrss", "cpu")}

    # Warm-up (ours without -q: the stderr line is a phase sample).
    # No warm-up for a scene whose meshes an earlier, non-cheap scene loaded: the page
    # cache is warm, and in a run of seconds nothing else needs warming.
    skip_warmup = bool(meshes) and meshes <= warmed
    warm_ours = warm_ref = None
    if skip_warmup:
        res["notes"].append("no warm-up (its mesh was loaded by an earlier scene)")
    else:
        warm_ours = run_once(ours_loud_cmd, a.timeout, REPO)
        res["ours_warmup"] = record(warm_ours)
        if not ok(warm_ours):
            ours_ok = False
            res["ours_error"] = failure_text(warm_ours)
            loud(f"{name}: raytracer failed ({res['ours_error']}); command: {res['ours_cmd'].replace(' -q', '')}")
        if ref_ok:
            warm_ref = run_once(ref_cmd, a.timeout, REPO)
            res["ref_warmup"] = record(warm_ref)
            if not ok(warm_ref):
                ref_ok = False
                res["ref_error"] = failure_text(warm_ref)
                log(f"{name}: refrender failed ({res['ref_error']})")
    warm_times = [r["wall"] for r in (warm_ours, warm_ref) if r is not None]
    heavy = max(warm_times) > a.heavy if warm_times else None  # else decided after the first round
    runs = min(a.runs, a.heavy_runs) if heavy else a.runs
    cheap = warm_ours is not None and ok(warm_ours) and warm_ours["wall"] < a.cheap

    ref_phases = []
    k = 0
    while k < runs:
        if k == 1 and heavy is None:
            first = [x["wall"] for x in res["ours_runs"][:1] + res["ref_runs"][:1]]
            heavy = bool(first) and max(first) > a.heavy
            runs = min(a.runs, a.heavy_runs) if heavy else a.runs
            if k >= runs:
                break
        order = ["ours", "ref"] if k % 2 == 0 else ["ref", "ours"]
        for who in order:
            if who == "ours" and ours_ok:
                loud_run = not cheap  # the phase split of non-cheap scenes
                r = run_once(ours_loud_cmd if loud_run else ours_cmd, a.timeout, REPO)
                res["ours_runs"].append(dict(record(r), quiet=not loud_run))
                if not ok(r):
                    ours_ok = False
                    res["ours_error"] = failure_text(r)
                    loud(f"{name}: raytracer failed ({res['ours_error']}); command: {res['ours_cmd']}")
                elif loud_run:
                    res["phase_runs"].append(parse_ours(r["stderr"]))
            elif who == "ref" and ref_ok:
                r = run_once(ref_cmd, a.timeout, REPO)
                res["ref_runs"].append(record(r))
                if not ok(r):
                    ref_ok = False
                    res["ref_error"] = failure_text(r)
                    log(f"{name}: refrender failed ({res['ref_error']})")
                else:
                    ref_phases.append(parse_ref(r["stdout"]))
        k += 1
    heavy = bool(heavy)
    res["heavy"], res["runs"], res["cheap"] = heavy, runs, cheap
    if cheap and ours_ok:
        for _ in range(runs):
            r = run_once(ours_loud_cmd, a.timeout, REPO)
            if ok(r):
                res["phase_runs"].append(parse_ours(r["stderr"]))
    if not res["phase_runs"] and warm_ours is not None and ok(warm_ours):
        res["phase_runs"].append(parse_ours(warm_ours["stderr"]))

    good = lambda rs: [x["wall"] for x in rs if x["rc"] == 0 and not x["timed_out"]]
    res["ours_ok"], res["ref_ok"] = ours_ok, ref_ok
    res["ours_median"] = median(good(res["ours_runs"])) if ours_ok else None
    res["ref_median"] = median(good(res["ref_runs"])) if ref_ok else None
    res["ratio"] = (res["ours_median"] / res["ref_median"]
                    if res["ours_median"] and res["ref_median"] else None)
    all_ours = res["ours_runs"] + ([res["ours_warmup"]] if "ours_warmup" in res else [])
    all_ref = res["ref_runs"] + ([res["ref_warmup"]] if "ref_warmup" in res else [])
    res["ours_maxrss"] = max((x["maxrss"] for x in all_ours), default=None)
    res["ref_maxrss"] = max((x["maxrss"] for x in all_ref), default=None)
    res["phases"] = median_phases(res["phase_runs"])
    res["ref_phases"] = median_phases(ref_phases)
    if res["phase_runs"] and res["phases"] is None:
        res["notes"].append("our stderr line did not parse")
    return res, cheap, meshes


# ---------------------------------------------------------------- report

def fmt_s(x, digits=3):
    return "n/a" if x is None else f"{x:.{digits}f}"


def fmt_mb(b):
    if b is None:
        return "n/a"
    return f"{b / 2**20:.1f}" if b < 100 * 2**20 else f"{b / 2**20:.0f}"


def table(header, rows, align):
    widths = [max(len(str(r[i])) for r in [header] + rows) for i in range(len(header))]

    def line(cells):
        out = []
        for c, w, al in zip(cells, widths, align):
            out.append(str(c).rjust(w) if al == "r" else str(c).ljust(w))
        return "| " + " | ".join(out) + " |"

    sep = "| " + " | ".join(("-" * (w - 1) + ":") if al == "r" else "-" * w for w, al in zip(widths, align)) + " |"
    return "\n".join([line(header), sep] + [line(r) for r in rows])


def label(r):
    """A result's scene name with its culling setting when that is not the default."""
    return r["name"] + ("" if r["cull"] == "cull" else " no-cull")


def render_ratio(r):
    """Our render phase over refrender's (medians), or None."""
    p, rp = r["phases"] or {}, r["ref_phases"] or {}
    ren, rren = p.get("render"), rp.get("render")
    return ren / rren if ren is not None and rren else None


def fmt_ratio(x):
    return "n/a" if x is None else f"{x:.2f}"


def report(results, meta):
    out = []
    m = meta["machine"]
    modes = [c for c in CULL_MODES if any(r["cull"] == c for r in results)]
    out.append("# raytracer benchmark")
    out.append("")
    out.append(f"- date: {meta['date']} (took {meta['elapsed'] / 60:.1f} min)")
    out.append(f"- machine: {m['cpu']}, {m['cores']} cores ({m['usable_cores']} usable), "
               f"{(m['memory_bytes'] or 0) / 2**30:.1f} GiB; load average {meta['loadavg_start']} at start, "
               f"{meta['loadavg_end']} at end")
    out.append(f"- threads: {m['threads']} for both; runs: {meta['runs']} timed runs each after one warm-up, "
               f"alternating (heavy scenes, marked *: at most {meta['heavy_runs']})")
    out.append("- culling: every scene with " + " and with ".join(f"`--{c}`" for c in modes)
               + " on both sides (rows marked no-cull are the latter)")
    out.append(f"- ours: {meta['raytracer']} --precision {meta['precision']} (git {meta['git']}, "
               f"sha256 {meta['raytracer_sha256'][:12]})")
    if meta["refrender_problem"]:
        out.append(f"- **refrender could not run: {meta['refrender_problem']}; our times only**")
    else:
        out.append(f"- yardstick: {meta['refrender']}")
    out.append("")
    header = ["scene", "triangles", "ours s", "ref s", "ours/ref", "load", "bvh", "render", "write",
              "ours MiB", "ref MiB"]
    align = ["l", "r", "r", "r", "r", "r", "r", "r", "r", "r", "r"]
    rows = []
    for r in results:
        p = r["phases"] or {}
        name = label(r) + (" *" if r.get("heavy") else "")
        ours = fmt_s(r["ours_median"]) if r["ours_ok"] else "FAILED"
        ref = fmt_s(r["ref_median"]) if r["ref_ok"] else ("FAILED" if r["ref_cmd"] else "n/a")
        ratio = "n/a" if r["ratio"] is None else f"{r['ratio']:.2f}" + (" !" if r["ratio"] > 1.5 else "")
        rows.append([name, p.get("triangles", "?"), ours, ref, ratio, fmt_s(p.get("load")), fmt_s(p.get("bvh")),
                     fmt_s(p.get("render")), fmt_s(p.get("write")), fmt_mb(r["ours_maxrss"]),
                     fmt_mb(r["ref_maxrss"])])
    out.append(table(header, rows, align))
    out.append("")
    out.append("Times are medians of whole-process wall time (seconds); load/bvh/render/write is our "
               "own phase split (median of non-quiet runs); MiB is peak RSS (max over runs; readings "
               f"include a floor of {meta['rss_floor'] / 2**20:.1f} MiB, the process launcher's). "
               "`!` marks ours slower than 1.5x refrender; `*` a heavy scene.")

    for mode in modes:
        both = [r for r in results if r["cull"] == mode and r["ours_median"] is not None
                and r["ref_median"] is not None]
        mine = [r for r in results if r["cull"] == mode]
        out.append("")
        out.append(f"### `--{mode}`")
        out.append("")
        s_ours = sum(r["ours_median"] for r in both)
        s_ref = sum(r["ref_median"] for r in both)
        if both:
            out.append(f"**Total** over the {len(both)} scenes both finished: ours {s_ours:.2f} s, "
                       f"refrender {s_ref:.2f} s, ratio {s_ours / s_ref:.2f}.")
        else:
            s_all = sum(r["ours_median"] for r in mine if r["ours_median"] is not None)
            out.append(f"**Total** (ours only): {s_all:.2f} s.")
        official = [r for r in both if r["kind"] != "large"]
        if official and len(official) < len(both):
            o_ours = sum(r["ours_median"] for r in official)
            o_ref = sum(r["ref_median"] for r in official)
            out.append("")
            out.append(f"**Official scenes** ({len(official)} files): ours {o_ours:.3f} s, refrender {o_ref:.3f} s, "
                       f"ratio {o_ours / o_ref:.2f}.")
        slow = [r["name"] for r in both if r["ratio"] > 1.5]
        out.append("")
        out.append(f"**Ours slower than 1.5x refrender on {len(slow)} of {len(both)} scenes**"
                   + (": " + ", ".join(slow) if slow else "."))
        rr = [(r["name"], render_ratio(r)) for r in mine if render_ratio(r) is not None]
        if rr:
            over = [f"{n} {x:.2f}" for n, x in rr if x > 1.0]
            out.append("")
            out.append(f"**Render phase at most refrender's on {len(rr) - len(over)} of {len(rr)} scenes**"
                       + (" (over: " + ", ".join(over) + ")" if over else "."))

    failed = [r for r in results if not r["ours_ok"]]
    if failed:
        out.append("")
        out.append(f"**raytracer failed on {len(failed)} run(s):**")
        for r in failed:
            out.append(f"- {label(r)}: {r.get('ours_error', '?')} (`{r['ours_cmd']}`)")
    ref_failed = [r for r in results if r["ref_cmd"] and not r["ref_ok"]]
    if ref_failed:
        out.append("")
        out.append("refrender failed on: " + ", ".join(f"{label(r)} ({r.get('ref_error', '?')})" for r in ref_failed))

    # Render phase side by side, both culling settings, one row per scene.
    names = list(dict.fromkeys(r["name"] for r in results))
    by = {(r["name"], r["cull"]): r for r in results}
    if names:
        out.append("")
        out.append("## Render phase: ours / refrender, both culling settings")
        out.append("")
        header = ["scene", "triangles"]
        for mode in modes:
            header += [f"ours {mode} s", f"ref {mode} s", f"{mode} ratio"]
        rows = []
        for n in names:
            rs = [by.get((n, mode)) for mode in modes]
            tris = next(((x["phases"] or {}).get("triangles") for x in rs if x and x["phases"]), None)
            row = [n, tris or "?"]
            for x in rs:
                p, rp = ((x or {}).get("phases") or {}), ((x or {}).get("ref_phases") or {})
                rat = render_ratio(x) if x else None
                row += [fmt_s(p.get("render")), fmt_s(rp.get("render")),
                        fmt_ratio(rat) + (" >" if rat is not None and rat > 1.0 else "")]
            rows.append(row)
        out.append(table(header, rows, ["l"] + ["r"] * (len(header) - 1)))
        out.append("")
        out.append("Render: the render phase alone, summed over a scene's images (ours: median of our phase "
                   "split; refrender: median of its own render= figures). `>` marks ours slower than refrender.")

    large = [r for r in results if r["kind"] == "large"]
    if large:
        out.append("")
        out.append("## Large scenes: build cost and memory")
        out.append("")
        header = ["scene", "triangles", "ours load+bvh s", "ref parse+bvh s", "ours render s", "ref render s",
                  "render ratio", "ours B/tri", "ref B/tri"]
        rows = []
        for r in large:
            p = r["phases"] or {}
            rp = r["ref_phases"] or {}
            tris = p.get("triangles")
            lb = p["load"] + p["bvh"] if p else None
            rlb = rp["parse"] + rp["bvh"] if rp else None
            bpt = lambda rss: "n/a" if rss is None or not tris else f"{rss / tris:.0f}"
            rows.append([label(r), tris or "?", fmt_s(lb, 2), fmt_s(rlb, 2), fmt_s(p.get("render")),
                         fmt_s(rp.get("render")), fmt_ratio(render_ratio(r)), bpt(r["ours_maxrss"]),
                         bpt(r["ref_maxrss"])])
        out.append(table(header, rows, ["l", "r", "r", "r", "r", "r", "r", "r", "r"]))
        out.append("")
        out.append("Render: the render phase alone (ours: median of our phase split; refrender: median of "
                   "its own render= figures). B/tri: peak RSS of the whole process over the scene's "
                   "triangle count (ours' count, which includes the 2 ground triangles).")
    notes = {}
    for r in results:
        for n in r["notes"]:
            notes.setdefault(n, []).append(label(r))
    if notes:
        out.append("")
        for n, names_ in notes.items():
            out.append(f"- {n}: {', '.join(names_)}")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- main

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

    global SPAWNER_PROC
    SPAWNER_PROC = Spawner()
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
        SPAWNER_PROC.close()
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
