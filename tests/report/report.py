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
"""
import argparse
import datetime
import html
import json
import math
import os
import platform
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

MAX_REPEATS = 150  # runs repeated because the machine was busy, in all
REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
sys.path.insert(0, os.path.join(REPO, "tests", "bench"))
from bench import cpu_model  # noqa: E402  (one reader of /proc/cpuinfo for both scripts)


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def loud(msg):
    log("!" * 78 + "\n!! " + msg + "\n" + "!" * 78)


# ---------------------------------------------------------------------------------------
# Scenes

class Scene:
    def __init__(self, key, path, kind, refs=None, label=None):
        self.key = key            # unique, file-name safe
        self.path = path          # the scene file
        self.kind = kind          # official | ours | far | big
        self.refs = refs or {}    # image name -> reference PNG
        self.label = label or os.path.basename(path)
        self.reflective = has_reflective_material(path)


def has_reflective_material(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        mats = doc["Scene"]["Materials"]["Material"]
    except (OSError, ValueError, KeyError, TypeError):
        return False
    if isinstance(mats, dict):
        mats = [mats]
    return any(isinstance(m, dict) and m.get("_type") in ("mirror", "conductor", "dielectric") for m in mats)


def official_scenes(shared):
    manifest = os.path.join(shared, "scenes", "hw1", "MANIFEST.tsv")
    scenes, order = {}, []
    with open(manifest, encoding="utf-8") as f:
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            cols = line.rstrip("\n").split("\t")
            if len(cols) < 4 or cols[3].strip() != "complete":
                continue
            rel, image, ref = cols[0], cols[1], cols[2]
            if rel not in scenes:
                key = rel[:-5].replace("/", "_") if rel.endswith(".json") else rel.replace("/", "_")
                scenes[rel] = Scene(key, os.path.join(shared, "scenes", "hw1", rel), "official", label=rel)
                order.append(rel)
            ref_path = os.path.join(shared, ref)
            if os.path.isfile(ref_path):
                scenes[rel].refs[image] = ref_path
    return [scenes[r] for r in order]


def our_scenes():
    out = []
    root = os.path.join(REPO, "scenes")
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in ("tools", "renders"))
        for name in sorted(filenames):
            if name.endswith(".json"):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, REPO)
                out.append(Scene("ours_" + name[:-5], path, "ours", label=rel))
    return out


def offset_scene(src, dst, offset):
    """Writes `src` moved by (offset, offset, offset): vertices, camera, gaze point, lights."""
    with open(src, encoding="utf-8") as f:
        doc = json.load(f)
    s = doc["Scene"]

    def shift(text):
        v = [float(x) for x in str(text).split()]
        return " ".join(repr(x + offset) for x in v)

    vd = s.get("VertexData")
    if isinstance(vd, dict):
        nums = [float(x) for x in str(vd["_data"]).split()]
        vd["_data"] = " ".join(repr(x + offset) for x in nums)
    elif isinstance(vd, str):
        nums = [float(x) for x in vd.split()]
        s["VertexData"] = " ".join(repr(x + offset) for x in nums)
    cams = s["Cameras"]["Camera"]
    for c in cams if isinstance(cams, list) else [cams]:
        c["Position"] = shift(c["Position"])
        if "GazePoint" in c:
            c["GazePoint"] = shift(c["GazePoint"])
    lights = s.get("Lights", {}).get("PointLight", [])
    for l in lights if isinstance(lights, list) else [lights]:
        l["Position"] = shift(l["Position"])
    with open(dst, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=2)


def far_scenes(shared, work):
    out = []
    folder = os.path.join(work, "scenes", "far")
    os.makedirs(folder, exist_ok=True)
    for name in ("simple", "spheres"):
        src = os.path.join(shared, "scenes", "hw1", name + ".json")
        ref = os.path.join(shared, "references", "hw1", name + ".png")
        if not os.path.isfile(src):
            continue
        for exp in (2, 3, 4):
            dst = os.path.join(folder, f"{name}_1e{exp}.json")
            offset_scene(src, dst, 10.0 ** exp)
            refs = {name + ".png": ref} if os.path.isfile(ref) else {}
            out.append(Scene(f"far_{name}_1e{exp}", dst, "far", refs, label=f"{name}.json + 1e{exp}"))
    return out


def big_scene(gen_mesh, work):
    folder = os.path.join(work, "scenes")
    os.makedirs(folder, exist_ok=True)
    scene = os.path.join(folder, "knot_1m_plain.json")
    if not os.path.isfile(scene) or os.path.getmtime(scene) < os.path.getmtime(gen_mesh):
        log("generating a 1M-triangle mesh (tests/bench/gen_mesh) ...")
        r = subprocess.run([gen_mesh, "--out-dir", folder, "--name", "knot_1m", "1M"], capture_output=True, text=True)
        if r.returncode != 0:
            loud("gen_mesh failed: " + r.stderr.strip())
            return None
    return Scene("knot_1m_plain", scene, "big", label="knot_1m_plain.json (generated, 1M triangles)")


# ---------------------------------------------------------------------------------------
# Running

class Runner:
    def __init__(self, configs, threads, repeat, work, timeout):
        self.configs = configs      # name -> (binary, [options])
        self.threads = threads
        self.repeat = repeat        # raytracer --repeat: renders per image in each process
        self.work = work
        self.timeout = timeout
        self.runs = {}              # (config, scene key) -> [ {"wall", "images": {name: record}} ]
        self.failed = {}            # (config, scene key) -> message
        self.kept = {}              # (config, scene key) -> folder of the first run's images
        self.repeated = 0           # runs repeated because other processes used the CPU

    def run_once(self, config, scene, keep):
        binary, options = self.configs[config]
        tmp = tempfile.mkdtemp(prefix="rt_report_")
        try:
            out = os.path.join(self.work, "img", config, scene.key) if keep else os.path.join(tmp, "out")
            if keep:
                shutil.rmtree(out, ignore_errors=True)
            os.makedirs(out, exist_ok=True)
            stats = os.path.join(tmp, "stats.json")
            cmd = [binary, "-q", "-j", str(self.threads), "--repeat", str(self.repeat), "--stats", stats, "-o", out] \
                + options + [scene.path]
            err_path = os.path.join(tmp, "stderr")
            # A run during which other processes used more than a quarter of a core is
            # repeated (twice at most, and at most MAX_REPEATS times in all: on a machine
            # that stays busy the report would take too long); the least disturbed attempt counts.
            best = None
            for attempt in range(3):
                busy0 = cpu_busy_seconds()
                t0 = time.perf_counter()
                with open(err_path, "wb") as err:
                    p = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL, stderr=err)
                    killer = threading.Timer(self.timeout, p.kill)
                    killer.start()
                    _, status, usage = os.wait4(p.pid, 0)
                    killer.cancel()
                    p.returncode = os.waitstatus_to_exitcode(status)
                wall = time.perf_counter() - t0
                others = cpu_busy_seconds() - busy0 - (usage.ru_utime + usage.ru_stime)
                if p.returncode != 0 or not os.path.isfile(stats):
                    with open(err_path, encoding="utf-8", errors="replace") as f:
                        raise RuntimeError(f"exit {p.returncode}: {f.read().strip()[-400:]}")
                disturbed = others > 0.25 * wall + 0.02
                with open(stats, encoding="utf-8") as f:
                    doc = json.load(f)
                images = {os.path.relpath(rec["image"], out): rec for rec in doc["images"]}
                run = {"wall": wall, "cpu": usage.ru_utime + usage.ru_stime, "others_cpu": others,
                       "disturbed": disturbed, "images": images}
                if best is None or others / wall < best["others_cpu"] / best["wall"]:
                    best = run
                if not disturbed or self.repeated >= MAX_REPEATS:
                    break
                self.repeated += 1
            return best, out
        finally:
            shutil.rmtree(tmp, ignore_errors=True)

    def measure(self, configs, scenes, runs, study):
        """Round-robin rounds until every (config, scene) has `runs` runs."""
        # Scene by scene, every configuration in turn: a burst of load from elsewhere
        # hits the configurations being compared alike.
        todo = [(c, s) for s in scenes for c in configs if (c, s.key) not in self.failed]
        rounds = max([0] + [runs - len(self.runs.get((c, s.key), [])) for c, s in todo])
        total = sum(max(0, runs - len(self.runs.get((c, s.key), []))) for c, s in todo)
        done = 0
        t0 = time.perf_counter()
        for _ in range(rounds):
            for c, s in todo:
                have = self.runs.setdefault((c, s.key), [])
                if len(have) >= runs or (c, s.key) in self.failed:
                    continue
                try:
                    rec, folder = self.run_once(c, s, keep=not have)
                except (RuntimeError, subprocess.TimeoutExpired, OSError, ValueError) as e:
                    loud(f"{study}: {c} {s.label}: {e}")
                    self.failed[(c, s.key)] = str(e)
                    continue
                if not have:
                    self.kept[(c, s.key)] = folder
                have.append(rec)
                done += 1
                if sys.stderr.isatty():
                    print(f"\r{study}: {done}/{total} runs, {time.perf_counter() - t0:.0f} s", end="",
                          file=sys.stderr, flush=True)
        if sys.stderr.isatty():
            print("\r" + " " * 60 + "\r", end="", file=sys.stderr, flush=True)
        log(f"{study}: {done} runs in {time.perf_counter() - t0:.1f} s")

    def ok(self, config, scene):
        return bool(self.runs.get((config, scene.key))) and (config, scene.key) not in self.failed

    def images(self, config, scene):
        """Image names of a configuration's runs of a scene, in the raytracer's order."""
        runs = self.runs.get((config, scene.key)) or []
        return list(runs[0]["images"].keys()) if runs else []

    def record(self, config, scene, image):
        return self.runs[(config, scene.key)][0]["images"][image]

    def median(self, config, scene, image, field):
        return self.timing(config, scene, image, field).median

    def timing(self, config, scene, image, field):
        """The median over the processes of each one's median, and the fastest and slowest
        render of all of them (--stats seconds_min / seconds_max), as a Timing."""
        recs = [r["images"][image] for r in self.runs[(config, scene.key)] if image in r["images"]]
        return Timing(statistics.median(rec["seconds"][field] for rec in recs),
                      min(rec["seconds_min"][field] for rec in recs),
                      max(rec["seconds_max"][field] for rec in recs),
                      sum(rec["repeat"] if field != "write" else 1 for rec in recs))

    def png(self, config, scene, image):
        return os.path.join(self.kept[(config, scene.key)], image)


def cpu_busy_seconds():
    """CPU seconds spent by the whole machine so far (/proc/stat, all but idle and iowait)."""
    try:
        with open("/proc/stat", encoding="ascii") as f:
            fields = [int(x) for x in f.readline().split()[1:]]
    except (OSError, ValueError):
        return 0.0
    busy = sum(fields[:8]) - fields[3] - fields[4]  # user nice system idle iowait irq softirq steal
    return busy / os.sysconf("SC_CLK_TCK")


class Differ:
    """build/report/imgdiff as a coprocess; results cached."""

    def __init__(self, binary):
        self.p = subprocess.Popen([binary], stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
        self.cache = {}

    def __call__(self, a, b, diff_png=None):
        key = (a, b, diff_png)
        if key not in self.cache:
            self.p.stdin.write("\t".join([a, b] + ([diff_png] if diff_png else [])) + "\n")
            self.p.stdin.flush()
            self.cache[key] = json.loads(self.p.stdout.readline())
        return self.cache[key]

    def close(self):
        self.p.stdin.close()
        self.p.wait()


# ---------------------------------------------------------------------------------------
# Timings and their ratios

class Timing:
    """Seconds: a median, the fastest and slowest run, and how many runs they are of.
    Timings add up (a total over images: medians, fastest and slowest summed)."""

    def __init__(self, median, lo, hi, n):
        self.median, self.lo, self.hi, self.n = median, lo, hi, n

    def __add__(self, other):
        return Timing(self.median + other.median, self.lo + other.lo, self.hi + other.hi, min(self.n, other.n))

    @staticmethod
    def total(timings):
        timings = list(timings)
        if not timings or any(t is None for t in timings):
            return None
        out = timings[0]
        for t in timings[1:]:
            out = out + t
        return out


def ratio_text(num, den):
    """num / den as "1.23x"; "within noise" when the runs' spreads overlap (the fastest of
    either is no faster than the slowest of the other), "one run" when there is no spread
    to judge by."""
    if num is None or den is None or den.median <= 0:
        return "—"
    text = f"{num.median / den.median:.2f}x"
    if min(num.n, den.n) < 2:
        return text + " (one run)"
    if num.lo <= den.hi and den.lo <= num.hi:
        return text + " (within noise)"
    return text


# ---------------------------------------------------------------------------------------
# Formatting

def fs(x, digits=3):
    return "—" if x is None else f"{x:.{digits}f}"


def pct(n, total, digits=2):
    return "—" if n is None or not total else f"{100.0 * n / total:.{digits}f}%"


def mean(xs):
    xs = [x for x in xs if x is not None]
    return sum(xs) / len(xs) if xs else None


def worst(xs):
    xs = [x for x in xs if x is not None]
    return max(xs) if xs else None


def pct_s(x, digits=3):
    return "—" if x is None else f"{x:.{digits}f}%"


class Doc:
    """Sections rendered both as Markdown and as HTML."""

    def __init__(self):
        self.parts = []

    def h(self, level, text):
        self.parts.append(("h", level, text))

    def p(self, text):
        self.parts.append(("p", text))

    def table(self, header, rows, align=None):
        self.parts.append(("table", header, rows, align or ["l"] + ["r"] * (len(header) - 1)))

    def image(self, src, alt):
        self.parts.append(("img", src, alt))

    def gallery(self, header, rows):
        """rows: [(label, [(src or None, caption)])]"""
        self.parts.append(("gallery", header, rows))

    def markdown(self):
        out = []
        for part in self.parts:
            if part[0] == "h":
                out.append("#" * part[1] + " " + part[2] + "\n")
            elif part[0] == "p":
                out.append(part[1] + "\n")
            elif part[0] == "table":
                _, header, rows, align = part
                out.append("| " + " | ".join(header) + " |")
                out.append("| " + " | ".join("---:" if a == "r" else "---" for a in align) + " |")
                for r in rows:
                    out.append("| " + " | ".join(str(c) for c in r) + " |")
                out.append("")
            elif part[0] == "img":
                out.append(f"![{part[2]}]({part[1]})\n")
            elif part[0] == "gallery":
                _, header, rows = part
                out.append("| " + " | ".join(header) + " |")
                out.append("| " + " | ".join("---" for _ in header) + " |")
                for label, cells in rows:
                    cs = []
                    for src, cap in cells:
                        cs.append(f'<img src="{src}" width="240" alt="{cap}"><br>{cap}' if src else "—")
                    out.append("| " + " | ".join([label] + cs) + " |")
                out.append("")
        return "\n".join(out) + "\n"

    def html(self, title):
        return html_page(title, self.parts)


def html_inline(t):
    """Markdown's `code` and **bold** spans as HTML; everything else escaped."""
    parts = t.split("`")
    return "".join(re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", html.escape(x)) if i % 2 == 0
                   else "<code>" + html.escape(x) + "</code>" for i, x in enumerate(parts))


def html_page(title, parts):
    """Doc's parts as one HTML page."""
    e = html.escape
    inline = html_inline
    out = [f"<!doctype html><html><head><meta charset='utf-8'><title>{e(title)}</title><style>"
           "body{font-family:sans-serif;margin:2em;max-width:1400px} table{border-collapse:collapse;margin:1em 0}"
           "td,th{border:1px solid #ccc;padding:3px 8px} td.r{text-align:right} img{max-width:100%}"
           "code{background:#f4f4f4}</style></head><body>"]
    for part in parts:
        if part[0] == "h":
            out.append(f"<h{part[1]}>{inline(part[2])}</h{part[1]}>")
        elif part[0] == "p":
            out.append("<p>" + inline(part[1]) + "</p>")
        elif part[0] == "table":
            _, header, rows, align = part
            out.append("<table><tr>" + "".join("<th>" + inline(h) + "</th>" for h in header) + "</tr>")
            for r in rows:
                out.append("<tr>" + "".join(
                    f"<td class='{'r' if a == 'r' else 'l'}'>" + inline(str(c)) + "</td>" for c, a in zip(r, align))
                    + "</tr>")
            out.append("</table>")
        elif part[0] == "img":
            out.append(f"<p><img src='{e(part[1])}' alt='{e(part[2])}'></p>")
        elif part[0] == "gallery":
            _, header, rows = part
            out.append("<table><tr>" + "".join("<th>" + e(h) + "</th>" for h in header) + "</tr>")
            for label, cells in rows:
                cs = "".join(
                    (f"<td><a href='{e(src)}'><img src='{e(src)}' width='320'></a><br>{e(cap)}</td>" if src
                     else "<td>—</td>") for src, cap in cells)
                out.append(f"<tr><td>{inline(label)}</td>{cs}</tr>")
            out.append("</table>")
    out.append("</body></html>")
    return "\n".join(out) + "\n"


def svg_chart(rows, title):
    """rows: [(label, t_nocull, t_cull)] -> a grouped horizontal bar chart."""
    e = html.escape
    label_w, bar_w, right = 260, 560, 90
    bar_h, gap, top = 11, 9, 58
    width = label_w + bar_w + right
    height = top + len(rows) * (2 * bar_h + gap) + 40
    tmax = max([0.001] + [max(a or 0, b or 0) for _, a, b in rows])
    # a round step giving 4 to 8 ticks
    raw = tmax / 6
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if raw <= m * mag)
    n = math.ceil(tmax / step - 1e-9)
    ticks = [round(i * step, 10) for i in range(n + 1)]
    axis_max = ticks[-1]
    sx = bar_w / axis_max
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="14">{e(title)}</text>',
           f'<rect x="{label_w}" y="30" width="12" height="10" fill="#8aa1c1"/>'
           f'<text x="{label_w + 16}" y="39">culling off</text>',
           f'<rect x="{label_w + 110}" y="30" width="12" height="10" fill="#e07b39"/>'
           f'<text x="{label_w + 126}" y="39">culling on</text>']
    for t in ticks:
        x = label_w + t * sx
        out.append(f'<line x1="{x:.1f}" y1="{top - 6}" x2="{x:.1f}" y2="{height - 30}" stroke="#e4e4e4"/>')
        out.append(f'<text x="{x:.1f}" y="{height - 16}" text-anchor="middle">{t:g} s</text>')
    y = top
    for label, a, b in rows:
        out.append(f'<text x="{label_w - 6}" y="{y + bar_h + 4}" text-anchor="end">{e(label)}</text>')
        for val, colour, dy in ((a, "#8aa1c1", 0), (b, "#e07b39", bar_h)):
            if val is None:
                continue
            w = max(1.0, val * sx)
            out.append(f'<rect x="{label_w}" y="{y + dy}" width="{w:.1f}" height="{bar_h - 1}" fill="{colour}"/>')
            out.append(f'<text x="{label_w + w + 4:.1f}" y="{y + dy + bar_h - 2}" font-size="9">{val:.3f}</text>')
        y += 2 * bar_h + gap
    out.append(f'<line x1="{label_w}" y1="{top - 6}" x2="{label_w}" y2="{height - 30}" stroke="#444"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------------------------------
# Machine

def machine(threads, bins):
    cpu = cpu_model()
    try:
        cxx = subprocess.run([os.environ.get("CXX", "g++"), "--version"], capture_output=True,
                             text=True).stdout.splitlines()[0]
    except (OSError, IndexError):
        cxx = "?"
    try:
        rev = subprocess.run(["git", "-C", REPO, "rev-parse", "--short", "HEAD"], capture_output=True,
                             text=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", REPO, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True).stdout.strip()
        rev = rev + ("+changes" if dirty else "") if rev else "?"
    except OSError:
        rev = "?"
    return {"cpu": cpu, "hardware_threads": os.cpu_count(), "usable_threads": len(os.sched_getaffinity(0)),
            "threads": threads, "kernel": platform.release(), "compiler": cxx, "commit": rev,
            "date": datetime.datetime.now().strftime("%Y-%m-%d %H:%M"),
            "binaries": bins}


# ---------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--bin", required=True, help="the raytracer")
    ap.add_argument("--imgdiff", required=True)
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

    # --- images and comparisons --------------------------------------------------------------
    shutil.rmtree(os.path.join(a.out, "img"), ignore_errors=True)
    img_dir = os.path.join(a.out, "img")
    os.makedirs(img_dir, exist_ok=True)

    def ref_of(scene, image):
        return scene.refs.get(image) or scene.refs.get(os.path.basename(image))

    def vs_ref(cfg, scene, image):
        ref = ref_of(scene, image)
        if not ref or not R.ok(cfg, scene):
            return None
        d = D(R.png(cfg, scene, image), ref)
        return None if "error" in d else d

    def vs_cfg(cfg, base, scene, image, diff_png=None):
        if not R.ok(cfg, scene) or not R.ok(base, scene):
            return None
        d = D(R.png(cfg, scene, image), R.png(base, scene, image), diff_png)
        return None if "error" in d else d

    n_runs = sum(len(v) for v in R.runs.values())
    still_disturbed = sum(1 for v in R.runs.values() for r in v if r.get("disturbed"))
    data = {"repeated_runs": R.repeated, "disturbed_runs": still_disturbed,
            "machine": machine(a.threads, {k: v[0] for k, v in configs.items()}), "runs": runs, "repeat": repeat,
            "quick": a.quick, "images": []}
    doc = Doc()
    m = data["machine"]
    doc.h(1, "Ray tracer report: culling, timings and the speed/accuracy trade")
    doc.p(f"Machine: {m['cpu']}, {m['hardware_threads']} hardware threads, rendering with {a.threads} threads "
          f"(`-j {a.threads}`); {m['compiler']}; commit {m['commit']}; {m['date']}. Times are medians of "
          f"{runs} process{'es' if runs > 1 else ''} of each configuration, each rendering every image "
          f"{repeat} time{'s' if repeat > 1 else ''} (`--repeat {repeat}`; the raytracer's `--stats` figures: "
          f"render = tracing only, BVH build separately), processes interleaved across configurations. "
          f"A ratio is marked *within noise* where the fastest and slowest renders of the two "
          f"configurations overlap, *one run* where there is one render of each. "
          f"Made by `make report{'-quick' if a.quick else ''}` (tests/report/report.py). "
          f"A run during which other processes used more than a quarter of a core was repeated "
          f"(twice at most, {MAX_REPEATS} times in all): {R.repeated} repeats; {still_disturbed} of "
          f"{n_runs} runs kept were still disturbed.")

    # ---- blog table ----
    doc.h(2, "Back-face culling off and on")
    doc.p("One row per image. Time: render seconds (tracing only; parsing, BVH build and PNG writing "
          "excluded). Pixels changed: pixels whose colour differs at all between the two renders. "
          "Off by >1 vs reference: pixels with a channel more than one level away from the course's "
          "reference image, with culling on (as the references were made).")
    rows, chart_rows = [], []
    all_off, all_on = [], []
    gallery = []
    for s in main_set:
        if not (R.ok("double", s) and R.ok("nocull", s)):
            continue
        for im in R.images("double", s):
            rec = R.record("double", s, im)
            tm_on = R.timing("double", s, im, "render")
            tm_off = R.timing("nocull", s, im, "render")
            t_on, t_off = tm_on.median, tm_off.median
            all_on.append(tm_on)
            all_off.append(tm_off)
            stem = f"{s.key}__{os.path.splitext(os.path.basename(im))[0]}"
            diff_png = os.path.join(img_dir, stem + "__culling_diff.png")
            ch = vs_cfg("nocull", "double", s, im, diff_png)
            rd = vs_ref("double", s, im)
            pixels = rec["width"] * rec["height"]
            prim = rec["primitives"]
            shutil.copy2(R.png("double", s, im), os.path.join(img_dir, stem + "__cull.png"))
            shutil.copy2(R.png("nocull", s, im), os.path.join(img_dir, stem + "__nocull.png"))
            ref = ref_of(s, im)
            if ref:
                shutil.copy2(ref, os.path.join(img_dir, stem + "__reference.png"))
            rows.append([f"`{s.label}`", os.path.basename(im), f"{rec['width']}x{rec['height']}",
                         str(prim["triangles"]) + (f" + {prim['spheres']} sph" if prim["spheres"] else ""),
                         fs(t_off), fs(t_on), ratio_text(tm_off, tm_on),
                         f"{ch['changed']} ({pct(ch['changed'], pixels)})" if ch else "—",
                         pct(rd["over1"], pixels, 3) if rd else "no reference"])
            chart_rows.append((os.path.basename(im), t_off, t_on))
            gallery.append((f"`{s.label}` {os.path.basename(im)}",
                            [(f"img/{stem}__cull.png", "ours, culling on"),
                             (f"img/{stem}__nocull.png", "ours, culling off"),
                             (f"img/{stem}__reference.png" if ref else None, "reference"),
                             (f"img/{stem}__culling_diff.png",
                              f"changed by culling: {ch['changed'] if ch else '?'} px")]))
            data["images"].append({"scene": s.label, "image": im, "kind": s.kind, "width": rec["width"],
                                   "height": rec["height"], "primitives": prim, "render_nocull": t_off,
                                   "render_cull": t_on, "culling_diff": ch, "vs_reference": rd,
                                   "rays_cull": rec["rays"],
                                   "rays_nocull": R.record("nocull", s, im)["rays"]})
    sum_off, sum_on = Timing.total(all_off), Timing.total(all_on)
    rows.append(["**all**", "", "", "", fs(sum_off.median if sum_off else None),
                 fs(sum_on.median if sum_on else None), ratio_text(sum_off, sum_on), "", ""])
    doc.table(["scene", "image", "resolution", "triangles", "no culling (s)", "culling (s)", "speed-up",
               "pixels changed by culling", "off by >1 vs reference"], rows,
              ["l", "l", "r", "r", "r", "r", "r", "r", "r"])
    with open(os.path.join(a.out, "chart.svg"), "w", encoding="utf-8") as f:
        f.write(svg_chart(chart_rows, f"Render time per image, median of {runs * repeat} "
                                      f"render{'s' if runs * repeat > 1 else ''}, {a.threads} threads"))
    doc.image("chart.svg", "render time per image, culling off and on")

    # ---- the trade, one row per option ----
    def errors(cfg, scenes, base="double"):
        """(mean %, worst %) off by >1 vs reference over official images; the same vs `base` for ours."""
        ref_p, own_p, n_ref, n_own = [], [], 0, 0
        for s in scenes:
            if not R.ok(cfg, s):
                continue
            for im in R.images(cfg, s):
                rec = R.record(cfg, s, im)
                px = rec["width"] * rec["height"]
                if s.kind == "official":
                    d = vs_ref(cfg, s, im)
                    if d:
                        ref_p.append(100.0 * d["over1"] / px)
                        n_ref += 1
                else:
                    d = vs_cfg(cfg, base, s, im)
                    if d:
                        own_p.append(100.0 * d["over1"] / px)
                        n_own += 1
        return mean(ref_p), worst(ref_p), mean(own_p), worst(own_p), n_ref, n_own

    def total_timing(cfg, scenes, fields=("render",)):
        parts = []
        for s in scenes:
            if not R.ok(cfg, s):
                return None
            for i, im in enumerate(R.images(cfg, s)):
                for fld in fields:
                    if fld == "bvh" and i > 0:
                        continue  # one build per scene file
                    parts.append(R.timing(cfg, s, im, fld))
        return Timing.total(parts)

    def total_time(cfg, scenes, fields=("render",)):
        t = total_timing(cfg, scenes, fields)
        return t.median if t else None

    summary = []

    def add_row(study, option, cfg, scenes, base_cfg="double", fields=("render",), err_base="double"):
        t = total_timing(cfg, scenes, fields)
        t0 = total_timing(base_cfg, scenes, fields)
        rm, rw, om, ow, nr, no = errors(cfg, scenes, err_base)
        summary.append([study, option, f"{sum(len(R.images(cfg, s)) for s in scenes)}", fs(t.median if t else None),
                        ratio_text(t, t0) if cfg != base_cfg else "1.00x",
                        f"{pct_s(rm)} / {pct_s(rw)}" if nr else "—",
                        f"{pct_s(om)} / {pct_s(ow)}" if no else "—"])

    add_row("precision", "double (default)", "double_prec", main_set, "double_prec")
    add_row("precision", "float (`--precision float`)", "float", main_set, "double_prec")
    add_row("precision", "float, culling off (`--precision float --no-cull`)", "float_nocull", main_set, "double_prec")
    add_row("culling", "on (default)", "double", main_set)
    add_row("culling", "off (`--no-cull`)", "nocull", main_set)
    add_row("ShadowRayEpsilon", "x0.1 (`--epsilon-scale 0.1`)", "eps0.1", main_set, "eps1")
    add_row("ShadowRayEpsilon", "x1 (default)", "eps1", main_set, "eps1")
    add_row("ShadowRayEpsilon", "x10 (`--epsilon-scale 10`)", "eps10", main_set, "eps1")
    add_row("weak rays", "not traced below weight 1e-4 (default)", "minw_default", main_set, "minw_default",
            err_base="minw_default")
    add_row("weak rays", "all traced to MaxRecursionDepth (`--min-weight 0`)", "minw0", main_set, "minw_default",
            err_base="minw_default")
    for d in depths:
        add_row("MaxRecursionDepth", f"{d} (`--max-depth {d}`)", f"depth{d}", depth_set, "depth_default")
    add_row("MaxRecursionDepth", "the scene's own (default)", "depth_default", depth_set, "depth_default")
    for name, cfg in bvh_configs:
        add_row("BVH", name, cfg, bvh_set, "bvh_default", fields=("bvh", "render"), err_base="bvh_default")
    doc.h(2, "The speed/accuracy trade, one row per option")
    doc.p("Time: the sum over the study's images of the median render time (for BVH rows: BVH build + "
          "render), and its ratio to the default. Error, official scenes: the percentage of pixels more than "
          "one level off the course's reference image, mean / worst over the images. Error, our scenes (no "
          "reference): the same against our default double-precision render. Studies: precision, culling, "
          f"epsilon and weak rays over all {sum(len(R.images('double', s)) for s in main_set)} images; depth over the "
          f"{len(depth_set)} scenes with mirrors, conductors or glass; BVH over the {len(bvh_set)} scenes of "
          "5000+ triangles" + (" (including a generated 1M-triangle mesh)" if big else "") + ".")
    doc.table(["study", "option", "images", "time (s)", "vs default", "official: % off vs reference (mean / worst)",
               "ours: % changed vs double (mean / worst)"], summary, ["l", "l", "r", "r", "r", "r", "r"])
    data["summary"] = summary

    # ---- far from the origin ----
    if far:
        doc.h(3, "Precision far from the origin")
        doc.p("The official simple.json and spheres.json with every position (vertices, camera, gaze point, "
              "lights) moved by (d, d, d); ShadowRayEpsilon stays 1e-3. Compared with the unmoved scene's "
              "reference image: pixels more than one level off, and the largest channel difference.")
        frows = []
        bases = [s for s in official if s.label in ("simple.json", "spheres.json")]
        for s in bases + far:
            cells = [s.label]
            for cfg in ("double", "float"):
                ims = R.images(cfg, s)
                if not ims:
                    cells += ["failed", ""]
                    continue
                im = ims[0]
                d = vs_ref(cfg, s, im)
                rec = R.record(cfg, s, im)
                px = rec["width"] * rec["height"]
                cells += [pct(d["over1"], px, 3) if d else "—", str(d["max"]) if d else "—"]
            frows.append(cells)
        doc.table(["scene", "double: off by >1", "double: max", "float: off by >1", "float: max"], frows)
        data["far"] = frows

    # ---- epsilon: acne and leaks ----
    doc.h(3, "ShadowRayEpsilon: acne against light leaking")
    doc.p("Pixels more than one level away from the default (x1) render, split by whether they got darker "
          "(surfaces shadowing themselves: acne) or brighter (shadow rays starting beyond a thin occluder: "
          "leaks), summed over all images.")
    erows = []
    for cfg, name in (("eps0.1", "x0.1"), ("eps10", "x10")):
        dark = bright = total_px = 0
        worst_im = ("", 0.0)
        for s in main_set:
            if not R.ok(cfg, s):
                continue
            for im in R.images(cfg, s):
                d = vs_cfg(cfg, "double", s, im)
                if not d:
                    continue
                dark += d["darker"]
                bright += d["brighter"]
                total_px += d["pixels"]
                share = 100.0 * d["over1"] / d["pixels"]
                if share > worst_im[1]:
                    worst_im = (os.path.basename(im), share)
        erows.append([name, f"{dark} ({pct(dark, total_px, 3)})", f"{bright} ({pct(bright, total_px, 3)})",
                      f"{worst_im[0]} ({worst_im[1]:.2f}%)" if worst_im[0] else "—"])
    doc.table(["ShadowRayEpsilon", "darker pixels (acne)", "brighter pixels (leaks)", "most changed image"], erows)
    data["epsilon"] = erows

    # ---- depth ----
    doc.h(3, "MaxRecursionDepth: time against pixels still changing")
    doc.p(f"Over the {len(depth_set)} scenes with mirrors, conductors or glass: "
          + ", ".join(f"`{s.label}`" for s in depth_set) + ". Pixels changed: pixels whose colour differs "
          "at all from the render one level shallower.")
    drows = []
    prev = None
    for d in depths:
        cfg = f"depth{d}"
        t = total_time(cfg, depth_set)
        rays = sum(R.record(cfg, s, im)["rays"]["total"] for s in depth_set if R.ok(cfg, s)
                   for im in R.images(cfg, s))
        changed = total_px = 0
        if prev:
            for s in depth_set:
                for im in R.images(cfg, s):
                    dd = vs_cfg(cfg, prev, s, im)
                    if dd:
                        changed += dd["changed"]
                        total_px += dd["pixels"]
        rm, rw, om, ow, nr, no = errors(cfg, depth_set)
        drows.append([str(d), fs(t), f"{rays / 1e6:.2f} M", f"{changed} ({pct(changed, total_px, 3)})" if prev else "—",
                      f"{pct_s(rm)} / {pct_s(rw)}" if nr else "—"])
        prev = cfg
    doc.table(["depth", "render (s)", "rays", "pixels changed from depth - 1", "official: % off vs reference"],
              drows)
    data["depth"] = drows

    # ---- BVH ----
    doc.h(3, "BVH leaf size and build quality: build time against render time")
    doc.p("Over " + ", ".join(f"`{s.label}`" for s in bvh_set) + ". Build and render: sums of medians. "
          "Nodes and depth: of the largest scene. Identical: every image equal, pixel for pixel, to the "
          "default build's (the traversal's answer never depends on the tree).")
    brows = []
    largest = max(bvh_set, key=lambda s: max((R.record("bvh_default", s, im)["primitives"]["triangles"]
                                              for im in R.images("bvh_default", s)), default=0)) if bvh_set else None
    for name, cfg in bvh_configs:
        tb = total_time(cfg, bvh_set, ("bvh",))
        tr = total_time(cfg, bvh_set, ("render",))
        same = all((vs_cfg(cfg, "bvh_default", s, im) or {"changed": 1})["changed"] == 0
                   for s in bvh_set for im in R.images(cfg, s))
        nodes = depth = "—"
        if largest and R.ok(cfg, largest):
            rec = R.record(cfg, largest, R.images(cfg, largest)[0])
            nodes, depth = str(rec["bvh"]["nodes"]), str(rec["bvh"]["depth"])
        brows.append([name, fs(tb), fs(tr), fs(tb + tr if tb is not None and tr is not None else None),
                      nodes, depth, "yes" if same else "NO"])
    doc.table(["BVH", "build (s)", "render (s)", "build + render (s)", "nodes", "depth", "identical"], brows)
    data["bvh"] = brows

    # ---- images ----
    doc.h(2, "Images")
    doc.p("Our render with culling on and off, the course's reference, and what culling changes (grey: "
          "unchanged; red: darker with culling off; green: brighter).")
    doc.gallery(["image", "culling on", "culling off", "reference", "culling changes"], gallery)

    failures = [f"{c} {k}: {msg}" for (c, k), msg in R.failed.items()]
    if failures:
        doc.h(2, "Failures")
        for f in failures:
            doc.p(f)
    data["failures"] = failures
    elapsed = time.perf_counter() - t_start
    doc.p(f"Report made in {elapsed:.0f} s.")
    D.close()

    with open(os.path.join(a.out, "index.md"), "w", encoding="utf-8") as f:
        f.write(doc.markdown())
    with open(os.path.join(a.out, "index.html"), "w", encoding="utf-8") as f:
        f.write(doc.html("Ray tracer report"))
    data["runs_raw"] = {f"{c}|{k}": v for (c, k), v in R.runs.items()}
    with open(os.path.join(a.out, "report.json"), "w", encoding="utf-8") as f:
        json.dump(data, f, indent=1)
    print(doc.markdown().split("## Images")[0])
    log(f"report: {os.path.relpath(os.path.join(a.out, 'index.md'))} (and index.html, chart.svg, report.json) "
        f"in {elapsed:.0f} s" + (f"; {len(failures)} failed runs" if failures else ""))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
