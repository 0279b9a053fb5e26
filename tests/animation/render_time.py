#!/usr/bin/env python3
"""The render time of an animation's frames, and the wall time of the whole animation
projected onto machines like this one (make tap-water, docs/animations.md).

Reads the --stats files of the shards (one single-threaded frame at a time per shard: each
image's seconds are its wall time on one core) and the shards' `time` (--time: a line
`wall R user U sys S`, bash's TIMEFORMAT='wall %R user %U sys %S' around the parallel run).

- CPU seconds per frame: the shards' user + sys over the frames rendered. Each frame's share
  of them is its share of the rays traced (--stats): other load on the machine stretches a
  frame's wall time by what else ran meanwhile, never its rays.
- Frames per hour: one single-threaded frame per core, the cores busy with nothing else.
- The projection: the animation's frames that were not rendered cost what the rendered
  frames around them cost (linear in the frame number, from the images' names ..._NNNN.png);
  TOTAL frames split by --shard K/N over N = machines x cores single-threaded jobs, each
  shard's frames one after the other: the wall time is the slowest shard's."""
import argparse
import json
import math
import re
import sys


def fail(msg):
    print("render_time.py: error: " + msg, file=sys.stderr)
    sys.exit(2)


def hms(s):
    s = int(round(s))
    return "%d:%02d:%02d" % (s // 3600, s // 60 % 60, s % 60)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("stats", nargs="+", help="the shards' --stats files")
    ap.add_argument("--time", required=True, help="the shards' wall and CPU seconds: `wall R user U sys S`")
    ap.add_argument("--total-frames", type=int, required=True, help="the whole animation's frames")
    ap.add_argument("--machines", default="1,8,64", help="machine counts to project for (default 1,8,64)")
    ap.add_argument("--report", help="also write the report to this file")
    ap.add_argument("--cores", type=int, help="cores per machine (default: this one's, from the stats)")
    args = ap.parse_args()

    try:
        with open(args.time, encoding="utf-8") as f:
            m = re.search(r"wall ([\d.]+) user ([\d.]+) sys ([\d.]+)", f.read())
    except OSError as e:
        fail("%s: %s" % (args.time, e))
    if not m:
        fail("%s: no line `wall R user U sys S`" % args.time)
    wall, cpu = float(m.group(1)), float(m.group(2)) + float(m.group(3))

    frames, cores = {}, args.cores
    for path in args.stats:
        try:
            with open(path, encoding="utf-8") as f:
                st = json.load(f)
        except (OSError, ValueError) as e:
            fail("%s: %s" % (path, e))
        cores = cores or st["machine"]["hardware_threads"]
        for im in st["images"]:
            if im["threads"] != 1:
                fail("%s: %s was rendered with %d threads; the figures assume one per frame" % (path, im["image"], im["threads"]))
            n = re.search(r"_(\d+)\.\w+$", im["image"])
            if not n:
                fail("%s: %s: no frame number (NAME_NNNN.png)" % (path, im["image"]))
            frames[int(n.group(1))] = {"wall": sum(im["seconds"].values()),
                                       "rays": im["rays"]["total"],
                                       "size": "%dx%d" % (im["width"], im["height"])}
    if not frames:
        fail("no image in the stats files")
    nums = sorted(frames)
    walls = sum(fr["wall"] for fr in frames.values())
    rays = sum(fr["rays"] for fr in frames.values())
    cost = {k: cpu * fr["rays"] / rays for k, fr in frames.items()}

    def cost_of(i):
        if i <= nums[0]:
            return cost[nums[0]]
        if i >= nums[-1]:
            return cost[nums[-1]]
        hi = next(k for k in nums if k >= i)
        lo = max(k for k in nums if k <= i)
        return cost[lo] if hi == lo else cost[lo] + (cost[hi] - cost[lo]) * (i - lo) / (hi - lo)

    per_frame = cpu / len(frames)
    lo_k, hi_k = min(cost, key=cost.get), max(cost, key=cost.get)
    out = ["Render time: %d frames (%s), %d shards' CPU %.1f s in %.1f s wall on %d cores"
           % (len(frames), frames[nums[0]]["size"], len(args.stats), cpu, wall, cores),
           "",
           "| figure | value |", "|---|---:|",
           "| CPU seconds per frame, mean | %.1f |" % per_frame,
           "| CPU seconds per frame by its rays, least (frame %d) and most (frame %d) | %.1f, %.1f |" % (lo_k, hi_k, cost[lo_k], cost[hi_k]),
           "| rays per frame, mean | %.1fM |" % (rays / len(frames) / 1e6),
           "| frames per hour on this machine (%d cores, nothing else running) | %.0f |" % (cores, 3600 * cores / per_frame),
           "| frames per hour as measured (the run's wall time, other load included) | %.0f |" % (3600 * len(frames) / wall),
           "| the frames' wall seconds per CPU second (1 on an idle machine) | %.2f |" % (walls / cpu),
           ""]
    all_cost = [cost_of(i) for i in range(args.total_frames)]
    total = sum(all_cost)
    out += ["The whole animation, %d frames: %.2f CPU hours (the %d frames not rendered costed from their neighbours)"
            % (args.total_frames, total / 3600, args.total_frames - len([k for k in nums if k < args.total_frames])),
            "",
            "| machines (%d cores each) | shards (--shard K/N) | wall time, --shard split | wall time, perfect split | frames per shard |"
            % cores, "|---:|---:|---:|---:|---:|"]
    for mach in (int(m) for m in args.machines.split(",")):
        n = mach * cores
        shards = [sum(all_cost[k::n]) for k in range(n)]
        per = math.ceil(args.total_frames / n)
        out.append("| %d | %d | %s | %s | %d |" % (mach, n, hms(max(shards)), hms(max(total / n, max(all_cost))), per))
    text = "\n".join(out)
    print(text)
    if args.report:
        with open(args.report, "w", encoding="utf-8") as f:
            f.write(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
