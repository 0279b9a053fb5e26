"""report.py's record of the machine and build: CPU, threads, kernel, compiler, commit, date."""
import datetime
import os
import platform
import subprocess
import sys

from report_common import REPO

sys.path.insert(0, os.path.join(REPO, "tests", "bench"))
from bench_machine import cpu_model  # noqa: E402  (one reader of /proc/cpuinfo for both scripts)


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
