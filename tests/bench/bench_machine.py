"""bench.py's facts about the run: the machine, its load, the git state, the binary's hash,
and whether refrender can render at all."""
import hashlib
import json
import os
import platform
import shutil
import subprocess
import tempfile

from bench_common import REPO


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
