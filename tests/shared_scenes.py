"""What the Python checks (tests/web/check_web.py, tests/gltf/check_gltf.py) share: the
course's scenes in ../shared (RT_SHARED_DIR), and a check that prints and counts."""
import os
import subprocess

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RAYTRACER = os.path.join(REPO, "raytracer")
RTDIFF = os.path.join(REPO, "rtdiff")
failures = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what, flush=True)
    if not ok:
        failures.append(what)
    return ok


def shared_dir():
    d = os.environ.get("RT_SHARED_DIR") or os.path.join(os.path.dirname(REPO), "shared")
    return d if os.path.isdir(os.path.join(d, "scenes")) else ""


# Assignment 3's scenes take many samples per pixel: the checks that compare bytes render
# them at this many (--samples), which every promise of sameness covers as well.
HW3_CHECK_SAMPLES = "4"


def complete_rows(shared, hw):
    """(scene relative to its folder, image, reference relative to shared) of every row of
    assignment `hw`'s MANIFEST.tsv whose inputs are complete: a row per image."""
    out = []
    with open(os.path.join(shared, "scenes", hw, "MANIFEST.tsv"), encoding="utf-8") as f:
        for line in f:
            cols = line.rstrip("\n").split("\t")
            if not line.startswith("#") and len(cols) >= 4 and cols[3].startswith("complete"):
                out.append((cols[0], cols[1], cols[2]))
    return out


def complete_scenes(shared, assignments=("hw1", "hw2")):
    """(assignment, path relative to its scene folder) of every complete scene of `assignments`."""
    out = []
    for hw in assignments:
        for rel, _, _ in complete_rows(shared, hw):
            if (hw, rel) not in out:  # a scene of several cameras has a row per image: once
                out.append((hw, rel))
    return out


def identical(a, b):
    """rtdiff at tolerance 0: no channel of any pixel differs."""
    r = subprocess.run([RTDIFF, "--tolerance", "0", "--fail-above", "0", a, b], capture_output=True, text=True)
    return r.returncode == 0, (r.stdout + r.stderr).strip().splitlines()[-1:] or [""]


def isa_levels():
    """The instruction-set levels ./raytracer holds (as its refusal of an unknown --isa lists
    them), and those of them this CPU runs."""
    r = subprocess.run([RAYTRACER, "--isa", "?"], capture_output=True, text=True)
    held = r.stderr.strip().rsplit(": ", 1)[-1].split(", ")
    runs = [lv for lv in held
            if subprocess.run([RAYTRACER, "--isa", lv, "--version"], capture_output=True).returncode == 0]
    return held, runs
