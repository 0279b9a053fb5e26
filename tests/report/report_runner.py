"""report.py's runs: every configuration of a study as whole ./raytracer processes with
--stats, interleaved and repeated when other processes took the CPU; and the image
comparer build/report/imgdiff as a coprocess."""
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import threading
import time

from report_common import log, loud
from report_timing import Timing


MAX_REPEATS = 150  # runs repeated because the machine was busy, in all


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
