#!/usr/bin/python3
"""make bench-web (docs/web.md): the render phase of every complete scene of ../shared in the
page (headless Chromium, raytracer.render with one worker) against ./raytracer with one
thread (-j 1), alternating, medians of --runs; and the page's time to its first image of
hw1/simple.json (default workers): from navigation start, and from the call once the page
has loaded. Writes build/bench/web.md."""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import check_web as cw  # noqa: E402  (the server, the browser, the scene list)

FIRST_IMAGE_JS = """
const [url, done] = arguments;
(async () => {
  const t0 = performance.now();
  const name = url.slice(url.lastIndexOf('/') + 1);
  const files = {[name]: new Uint8Array(await (await fetch(url)).arrayBuffer())};
  const r = await raytracer.render({files, scene: name});
  return {since_navigation: performance.now() / 1000, since_call: (performance.now() - t0) / 1000, workers: r.workers};
})().then(done, e => done({error: String(e.message || e)}));
"""


def native_render_seconds(scene, out):
    """{image: render seconds} of one ./raytracer -j 1 run."""
    stats = os.path.join(out, "stats.json")
    subprocess.run([cw.RAYTRACER, "-q", "-j", "1", "--stats", stats, "-o", out, scene], check=True)
    with open(stats, encoding="utf-8") as f:
        return {os.path.basename(i["image"]): i["seconds"]["render"] for i in json.load(f)["images"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=3)
    ap.add_argument("--out", default=os.path.join(cw.REPO, "build", "bench", "web.md"))
    a = ap.parse_args()
    shared = cw.shared_dir()
    if not shared:
        print("bench-web: no ../shared (set RT_SHARED_DIR)", file=sys.stderr)
        return 1
    scenes = cw.complete_scenes(shared)
    with tempfile.TemporaryDirectory() as tmp:
        server = cw.start_server(shared, tmp)
        base = f"http://127.0.0.1:{server.server_address[1]}/"
        d = cw.browser()
        try:
            first = []
            for _ in range(a.runs):
                d.get(base + "index.html")
                cw.wait_for(d, "return window.raytracer")
                first.append(d.execute_async_script(FIRST_IMAGE_JS, base + "shared/scenes/hw1/simple.json"))
            rows = []
            for hw, rel in scenes:
                page, native = {}, {}
                for _ in range(a.runs):
                    for name, s in native_render_seconds(os.path.join(shared, "scenes", hw, rel), tmp).items():
                        native.setdefault(name, []).append(s)
                    r = cw.render_in_page(d, base + f"shared/scenes/{hw}/{rel}", {"workers": 1})
                    if "error" in r:
                        print(f"bench-web: {hw}/{rel}: {r['error']}", file=sys.stderr)
                        return 1
                    for im in r["images"]:
                        page.setdefault(im["name"], []).append(im["seconds"])
                for name in page:
                    p, n = statistics.median(page[name]), statistics.median(native[name])
                    rows.append((hw, name, p, n))
                    print(f"{hw} {name}: page {p:.3f} s, native {n:.3f} s, {p / n:.2f}x", flush=True)
        finally:
            d.quit()
            server.shutdown()
    md = ["# The page against the native build", "",
          f"Render phase, one worker against one thread (`-j 1`), medians of {a.runs} alternating runs; "
          f"{os.cpu_count()} hardware threads.", "",
          "| set | image | page s | native s | page / native |", "| --- | --- | ---: | ---: | ---: |"]
    md += [f"| {hw} | {name} | {p:.3f} | {n:.3f} | {p / n:.2f} |" for hw, name, p, n in rows]
    for hw in ("hw1", "hw2"):
        sel = [(p, n) for h, _, p, n in rows if h == hw]
        if sel:
            tp, tn = sum(p for p, _ in sel), sum(n for _, n in sel)
            md.append(f"| {hw} | all {len(sel)} (sum) | {tp:.3f} | {tn:.3f} | {tp / tn:.2f} |")
            md.append(f"| {hw} | median of the ratios | | | {statistics.median(p / n for p, n in sel):.2f} |")
    nav = statistics.median(f["since_navigation"] for f in first)
    call = statistics.median(f["since_call"] for f in first)
    md += ["", f"Time to the first image of hw1/simple.json ({first[0]['workers']} workers, a fresh page each run, "
               f"median of {a.runs}): {nav:.3f} s from navigation start, {call:.3f} s from the call "
               f"(fetch, workers and modules started, scene loaded, rendered)."]
    os.makedirs(os.path.dirname(a.out), exist_ok=True)
    with open(a.out, "w", encoding="utf-8") as f:
        f.write("\n".join(md) + "\n")
    print("\n".join(md[-12:]))
    print(f"bench-web: {os.path.relpath(a.out, cw.REPO)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
