"""make check-march, its renders: every instruction-set level ./raytracer holds that this
CPU executes (--isa), in both precisions, renders every complete official scene of
assignments 1, 2 and 3 (at HW3_CHECK_SAMPLES samples) and the repository's scenes to the same bytes; and the binary runs on
a CPU without AVX (qemu-x86_64 -cpu Nehalem), where it picks the baseline copy by itself and
refuses a level the CPU lacks. Prints a line per check; exit status 1 on any failure.
Without ../shared (RT_SHARED_DIR) the official scenes are skipped loudly (a failure when
CI=true); without qemu-x86_64 likewise the emulated run."""
import glob
import hashlib
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import (HW3_CHECK_SAMPLES, REPO, RAYTRACER, check, complete_scenes, failures,  # noqa: E402
                           isa_levels, shared_dir)

OUT = os.path.join(REPO, "build", "march-check")
CI = os.environ.get("CI") == "true"


def loud_skip(what):
    print("*" * 72 + f"\n*** check-march: SKIPPED: {what}\n" + "*" * 72, flush=True)
    check(not CI, f"CI=true and {what} was skipped")


def md5s(folder):
    out = {}
    for f in sorted(glob.glob(os.path.join(folder, "**", "*.png"), recursive=True)):
        with open(f, "rb") as fh:
            out[os.path.relpath(f, folder)] = hashlib.md5(fh.read()).hexdigest()
    return out


def main():
    shutil.rmtree(OUT, ignore_errors=True)
    held, runs = isa_levels()
    print(f"check-march: ./raytracer holds {' '.join(held)}; this CPU runs {' '.join(runs)}", flush=True)
    check(len(held) >= 1 and held[0] == runs[0], "the first level is one every CPU runs")
    # Each group into its own folder: scenes of two assignments may write the same image name.
    groups = {"ours": sorted(glob.glob(os.path.join(REPO, "scenes", "*.json")) +
                             [os.path.join(REPO, "scenes/knot/knot.json")])}
    shared = shared_dir()
    if shared:
        for hw, s in complete_scenes(shared, ("hw1", "hw2", "hw3")):
            groups.setdefault(hw, []).append(os.path.join(shared, "scenes", hw, s))
    else:
        loud_skip("the course's scenes (../shared or $RT_SHARED_DIR not found)")
    for precision in ("double", "float"):
        base = None
        for lv in runs:
            d = os.path.join(OUT, precision, lv)
            for group, scenes in groups.items():
                samples = ["--samples", HW3_CHECK_SAMPLES] if group == "hw3" else []
                r = subprocess.run([RAYTRACER, "-q", "--isa", lv, "--precision", precision, "-o",
                                    os.path.join(d, group)] + samples + scenes, capture_output=True, text=True)
                check(r.returncode == 0,
                      f"{precision} {lv}: rendered the {len(scenes)} scene files of {group} {r.stderr.strip()[:200]}")
            sums = md5s(d)
            if base is None:
                base = (lv, sums)
                continue
            same = [k for k in sums if base[1].get(k) == sums[k]]
            check(len(sums) == len(base[1]) and len(same) == len(sums),
                  f"{precision}: {len(same)} of {len(base[1])} images of {lv} byte-identical to {base[0]}'s")
    qemu = shutil.which("qemu-x86_64")
    if not qemu:
        loud_skip("the run on a CPU without AVX (qemu-x86_64 not installed: apt-get install qemu-user)")
    else:
        emu = [qemu, "-cpu", "Nehalem", RAYTRACER]
        r = subprocess.run(emu + ["--version"], capture_output=True, text=True)
        check(r.returncode == 0 and "(x86-64 kernels)" in r.stdout,
              f"under Nehalem, auto picks the baseline copy: {r.stdout.strip()}")
        for lv in held[1:]:
            r = subprocess.run(emu + ["--isa", lv, "--version"], capture_output=True, text=True)
            check(r.returncode == 2 and "does not execute" in r.stderr,
                  f"under Nehalem, --isa {lv} is refused: {r.stderr.strip()}")
        d = os.path.join(OUT, "nehalem")
        scene = os.path.join(REPO, "scenes", "mirror_box.json")
        for precision in ("double", "float"):
            r = subprocess.run(emu + ["-q", "-j", "2", "--precision", precision, "-o", os.path.join(d, precision), scene],
                               capture_output=True, text=True)
            ref = md5s(os.path.join(OUT, precision, held[0], "ours"))
            got = md5s(os.path.join(d, precision))
            check(r.returncode == 0 and got and all(ref.get(k) == v for k, v in got.items()),
                  f"under Nehalem, {precision}: mirror_box renders the baseline copy's bytes {r.stderr.strip()[:200]}")
    print(f"check-march: {'FAIL' if failures else 'passed'}", flush=True)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
