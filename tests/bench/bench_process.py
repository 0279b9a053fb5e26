"""bench.py's process runner: every timed program runs as a whole process started by a lean
helper interpreter, which reports its wall time, peak RSS and CPU time."""
import os
import shutil
import subprocess
import sys
import tempfile


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


# The running Spawner; bench.py's main starts it and closes it.
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
