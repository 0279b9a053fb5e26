"""bench.py's measurement of one scene under one culling setting: warm-up, alternating timed
runs of both programs within the budget rules, and the phase split read from their output."""
import re
import statistics

from bench_common import REPO, log, loud
from bench_process import failure_text, ok, run_once
from bench_scenes import mesh_files


OURS_LINE = re.compile(
    r"^(?P<image>.*): (?P<w>\d+)x(?P<h>\d+), (?P<precision>double|float), (?P<tris>\d+) triangles?, "
    r"(?P<spheres>\d+) spheres?, (?:\d+ instances?, )?"
    r"load (?P<load>[\d.eE+-]+)s, bvh (?P<bvh>[\d.eE+-]+)s, render (?P<render>[\d.eE+-]+)s(?: \([^)]*\))?, "
    r"write (?P<write>[\d.eE+-]+)s(, \d+ warnings?)?\s*$")


REF_LINE = re.compile(
    r"^(?P<image>\S+) parse=(?P<parse>[\d.eE+-]+)s bvh=(?P<bvh>[\d.eE+-]+)s render=(?P<render>[\d.eE+-]+)s "
    r"rays=(?P<rays>\d+) rays/s=(?P<rps>[\d.eE+-]+)")


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
