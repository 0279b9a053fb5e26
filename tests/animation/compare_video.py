#!/usr/bin/env python3
"""Our frames of an animation against the course's video of it (make tap-water,
docs/animations.md). Frame NNNN of the video (counted from 0) is the scene tap_NNNN.json, so
our image NAME_NNNN.png is compared with the video's frame NNNN.

The video is H.264 at a high compression and the renders on both sides are Monte Carlo
images, so frames are compared by block means (rtdiff --mc, docs/rtdiff.md), never pixel by
pixel, and the compression is measured, then put on our side too. Per frame N:

  ours        our PNG frame against the video's frame N.
  ours.h264   our frame after our frames, in name order, are encoded as the course's video
              was (ENCODE at --fps) and decoded: both sides have been through the codec.
  codec       ours.h264 against ours: what the compression alone does to a frame, the
              allowance the comparison makes.
  video next  the video's frame N+1 against N (N-1 for its last): the reference's own
              compression noise between two frames, plus the water's motion.
  nearest     which of the video's frames N-S..N+S ours.h264 is nearest to (pixel RMSE):
              the frame mapping checked. Where it is another frame than N, but that frame is
              nearer to frame N than ours is, the two cannot be told apart: `alike`.

Stdlib only; needs ffmpeg and rtdiff. Exit status 0 when every frame is nearest to its own
video frame (or alike) and passes rtdiff --mc's verdict through the codec, 1 otherwise, 2 on
bad input."""
import argparse
import glob
import os
import re
import shutil
import subprocess
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The course's video, as its x264 settings string records it: libx264 at CRF 23 with the
# medium preset's settings, yuv420p, 30 frames a second.
ENCODE = ["-c:v", "libx264", "-preset", "medium", "-crf", "23", "-pix_fmt", "yuv420p"]


def fail(msg):
    print("compare_video.py: error: " + msg, file=sys.stderr)
    sys.exit(2)


def run(cmd):
    r = subprocess.run(cmd, capture_output=True, text=True)
    if r.returncode != 0:
        fail("%s failed (exit %d): %s" % (" ".join(cmd), r.returncode, r.stderr.strip()[-2000:]))


def decode(video, out_dir, keep=None):
    """Every frame of `video` (presentation order, from 0) as out_dir/NNNN.png, or of them only
    the indices in `keep`; returns the indices written, in order."""
    shutil.rmtree(out_dir, ignore_errors=True)
    os.makedirs(out_dir)
    run(["ffmpeg", "-v", "error", "-i", video, "-vsync", "0", "-start_number", "0", os.path.join(out_dir, "%04d.png")])
    have = []
    for name in sorted(os.listdir(out_dir)):
        i = int(name[:-4])
        if keep is None or i in keep:
            have.append(i)
        else:
            os.remove(os.path.join(out_dir, name))
    return have


ROW = re.compile(r"^vs reference\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)\s+(\S+)")


def mc(rtdiff, a, b, block, threshold):
    """rtdiff --mc's figures of A against B: % blocks off, mean diff R G B and all, RMSE, pass."""
    r = subprocess.run([rtdiff, "--mc", "--block", str(block), "--block-threshold", str(threshold), a, b],
                       capture_output=True, text=True)
    for line in r.stdout.splitlines():
        m = ROW.match(line)
        if m and r.returncode in (0, 1):
            v = [float(x) for x in m.groups()]
            return {"off": v[0], "diff": v[1:4], "all": v[4], "rmse": v[5], "pass": r.returncode == 0}
    fail("rtdiff --mc %s %s: no figures (exit %d): %s" % (a, b, r.returncode, (r.stdout + r.stderr).strip()))


def cell(f, rgb=False):
    return "%.2f%%, %s" % (f["off"], " ".join("%+.2f" % x for x in f["diff"]) if rgb else "%+.2f" % f["all"])


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--frames", required=True, help="folder of our frames, NAME_NNNN.png")
    ap.add_argument("--video", required=True, help="the course's video, frame NNNN = scene NNNN")
    ap.add_argument("--work", required=True, help="folder for the decoded frames and our encoding")
    ap.add_argument("--fps", default="30", help="our frames' encoding: frames a second (default 30, the video's)")
    ap.add_argument("--rtdiff", default=os.path.join(REPO, "rtdiff"))
    ap.add_argument("--block", type=int, default=16, help="block side in pixels (default 16)")
    ap.add_argument("--threshold", type=int, default=3, help="a block is off when a channel is off by more than this many levels (default 3)")
    ap.add_argument("--search", type=int, default=2, help="the frame mapping: look at N-S..N+S (default 2)")
    ap.add_argument("--report", help="also write the report to this file")
    args = ap.parse_args()

    for f, what in ((args.video, "the course's video"), (args.rtdiff, "rtdiff")):
        if not os.path.isfile(f):
            fail("%s not found: %s" % (what, f))
    frames = []
    for p in sorted(glob.glob(os.path.join(args.frames, "*.png"))):
        m = re.search(r"_(\d+)\.png$", p)
        if not m:
            fail("%s: no frame number (NAME_NNNN.png)" % p)
        frames.append((int(m.group(1)), p))
    if not frames:
        fail("no frame in %s" % args.frames)

    ref_dir = os.path.join(args.work, "video")
    need = {n + d for n, _ in frames for d in range(-args.search, args.search + 1)} | {n + 1 for n, _ in frames}
    have = set(decode(args.video, ref_dir, keep=need))
    ref = lambda i: os.path.join(ref_dir, "%04d.png" % i)  # noqa: E731
    for n, p in frames:
        if n not in have:
            fail("%s: the video has no frame %d" % (p, n))
    # Our frames through the codec: a folder of links in name order, encoded, decoded.
    seq = os.path.join(args.work, "ours.seq")
    shutil.rmtree(seq, ignore_errors=True)
    os.makedirs(seq)
    for i, (_, p) in enumerate(frames):
        os.symlink(os.path.abspath(p), os.path.join(seq, "%04d.png" % i))
    ours_mp4 = os.path.join(args.work, "ours.mp4")
    run(["ffmpeg", "-v", "error", "-y", "-framerate", args.fps, "-i", os.path.join(seq, "%04d.png")] + ENCODE + [ours_mp4])
    h264_dir = os.path.join(args.work, "ours.h264")
    decoded = decode(ours_mp4, h264_dir)
    if len(decoded) != len(frames):
        fail("%s has %d frames, %s %d" % (ours_mp4, len(decoded), args.frames, len(frames)))
    h264 = {n: os.path.join(h264_dir, "%04d.png" % i) for (n, _), i in zip(frames, decoded)}

    B, T = args.block, args.threshold
    rows, bad = [], []
    for n, p in frames:
        cand = {d: mc(args.rtdiff, h264[n], ref(n + d), B, T) for d in range(-args.search, args.search + 1) if n + d in have}
        best = min(cand, key=lambda d: cand[d]["rmse"])
        runner = min(cand[d]["rmse"] for d in cand if d != best)
        alike = best != 0 and mc(args.rtdiff, ref(n + best), ref(n), B, T)["rmse"] < cand[0]["rmse"]
        r = {"n": n, "best": best, "alike": alike, "rmse": cand[best]["rmse"], "runner": runner,
             "ours": mc(args.rtdiff, p, ref(n), B, T), "h264": cand[0], "codec": mc(args.rtdiff, h264[n], p, B, T),
             "next": mc(args.rtdiff, ref(n + 1 if n + 1 in have else n - 1), ref(n), B, T)}
        rows.append(r)
        if (best != 0 and not alike) or not r["h264"]["pass"]:
            bad.append(n)

    out = ["Our frames (%s) against the video (%s): the means of %dx%d blocks; a block is off when some channel's"
           % (args.frames, args.video, B, B),
           "mean differs by more than %d levels. Each cell: %% blocks off, mean signed difference A - B in levels"
           % T,
           "(all channels; R G B for ours.h264). ours.h264: our frames encoded as the video was (%s, %s fps) and decoded."
           % (" ".join(ENCODE), args.fps),
           "",
           "| frame | nearest video frame (its RMSE; the next nearest's) | ours vs video | ours.h264 vs video "
           "| codec: ours.h264 vs ours | video: next frame vs this | verdict |",
           "|---:|---|---|---|---|---|---|"]
    for r in rows:
        near = "%+d%s (%.2f; %.2f)" % (r["best"], ", alike" if r["alike"] else "", r["rmse"], r["runner"])
        out.append("| %d | %s | %s | %s | %s | %s | %s |" % (
            r["n"], near, cell(r["ours"]), cell(r["h264"], rgb=True), cell(r["codec"]), cell(r["next"]),
            "FAIL" if r["n"] in bad else "ok"))
    out.append("")
    for key, what in (("ours", "ours vs video"), ("h264", "ours.h264 vs video"),
                      ("codec", "codec (ours.h264 vs ours)"), ("next", "video, next frame vs this")):
        f = [r[key] for r in rows]
        out.append("%s: %.2f%% blocks off on average (most %.2f%%), mean difference %s, RMSE %.2f" % (
            what, sum(x["off"] for x in f) / len(f), max(x["off"] for x in f),
            " ".join("%+.2f" % (sum(x["diff"][c] for x in f) / len(f)) for c in range(3)),
            sum(x["rmse"] for x in f) / len(f)))
    out.append("frame mapping: %d of %d frames nearest to the video's frame of their number, %d alike another "
               "(searched N-%d..N+%d)" % (sum(1 for r in rows if r["best"] == 0), len(rows),
                                          sum(1 for r in rows if r["alike"]), args.search, args.search))
    out.append("%d of %d frames ok%s" % (len(rows) - len(bad), len(rows),
                                          " (FAIL: %s)" % ", ".join(str(n) for n in bad) if bad else ""))
    text = "\n".join(out)
    print(text)
    if args.report:
        with open(args.report, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
