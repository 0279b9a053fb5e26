#!/usr/bin/python3
"""make check-web (docs/web.md): the WebAssembly module under Node and the page in headless
Chromium (Debian's chromium, chromium-driver and python3-selenium), against the native
double build:
  1. Node: every complete scene of ../shared (hw1, hw2; hw3 at a few samples per pixel and
     a seed of its own, on both sides) rendered by the module alone, pixel-identical to
     ./raytracer's images; a small scene of 40 samples per pixel rendered pass after pass,
     its passes 1, 16, 32 and 40, the last ./raytracer's image, the one of 32 its --samples 32.
  2. The page from a local server: it loads; the same scenes through raytracer.render(),
     pixel-identical, shown pass after pass; the small scene's passes through the API and
     through the page's button (its captions give the samples done and the time left); a
     scene given through the file input renders; traces equal
     ./raytracer --trace-json's, hw3's of a sample; a bad scene and a bad seed show the
     command line's one-line error and the page keeps working; the page's samples, seed and
     trace sample fields reach the image and the tree; a screenshot with an image, a ray
     tree and a heatmap is written to build/web/screenshot.png.
Exit status 0 when every check passed, 1 otherwise; without ../shared (RT_SHARED_DIR) or
the browser it fails loudly, never skips."""
import base64
import json
import os
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import REPO, RAYTRACER, RTDIFF, check, complete_scenes, failures, identical, shared_dir  # noqa: E402
from web_support import (CANVAS_JS, FETCH_JS, WEB, Clock, browser, canvas_equals, native_images,  # noqa: E402
                         render_in_page, start_server, wait_for, write_ppm)
from check_progressive import node_passes, page_passes  # noqa: E402

# Assignment 3's Monte Carlo scenes render at a few samples per pixel (their NumSamples
# would take minutes), with a seed other than the default: the page's samples and seed
# options against --samples and --seed, the same bytes.
HW3_SAMPLES, HW3_SEED = 4, 7
HW3_OPTIONS = {"samples": HW3_SAMPLES, "seed": HW3_SEED}
HW3_FLAGS = ["--samples", str(HW3_SAMPLES), "--seed", str(HW3_SEED)]


def settings(hw):
    """./raytracer's flags and the page's options for a scene of assignment `hw`, and how
    the checks' lines say so."""
    return (HW3_FLAGS, HW3_OPTIONS, f" at {HW3_SAMPLES} samples, seed {HW3_SEED}") if hw == "hw3" else ([], {}, "")


def node_checks(shared, scenes, tmp):
    print("== the module under Node", flush=True)
    for hw, rel in scenes:
        t0 = time.time()
        flags, options, what = settings(hw)
        scene = os.path.join(shared, "scenes", hw, rel)
        native = native_images(scene, os.path.join(tmp, "native", hw, os.path.dirname(rel)), flags)
        out = os.path.join(tmp, "node", hw, os.path.dirname(rel))
        r = subprocess.run(["node", "--no-experimental-fetch", os.path.join(REPO, "tests", "web", "node_render.js"),
                            out, "--options", json.dumps(options), scene], capture_output=True, text=True)
        if check(r.returncode == 0, f"node renders {hw}/{rel}" + (": " + r.stderr.strip() if r.returncode else "")):
            for line in r.stdout.splitlines():
                ppm, seconds = line.split("\t")
                name = os.path.splitext(os.path.basename(ppm))[0]
                same, text = identical(ppm, native.get(name, "missing"))
                check(same, f"node {hw}/{rel} {name}{what}: equal to native ({seconds} s; {text[0]})")
        if hw == "hw3":
            Clock.hw3 += time.time() - t0
    node_passes(shared, tmp)


# Traces a pixel of a scene of ../shared through the API: the --trace-json object or {error}.
TRACE_JS = FETCH_JS + """
const [url, options, x, y, sample, done] = arguments;
(async () => {
  const {name, files} = await fetchScene(url);
  return await raytracer.trace({files, scene: name, options, camera: 0, x, y, sample});
})().then(done, e => done({error: String(e && e.message || e)}));
"""


def has_field(tree, key):
    """Whether some object in the JSON `tree` has `key` with a value other than null."""
    if isinstance(tree, dict):
        return any((k == key and v is not None) or has_field(v, key) for k, v in tree.items())
    return isinstance(tree, list) and any(has_field(v, key) for v in tree)


def trace_check(d, base, shared, tmp, hw, rel, x, y, sample=0, shows=None):
    """A trace through the API equals ./raytracer --trace-json's (sample `sample`, with the
    scene's settings); `shows(trace)` names what the trace must hold, or None."""
    flags, options, what = settings(hw)
    native_json = os.path.join(tmp, "trace.json")
    subprocess.run([RAYTRACER, "--trace", f"{x},{y}", "--sample", str(sample), *flags, "--trace-json", native_json,
                    os.path.join(shared, "scenes", hw, rel)], check=True, capture_output=True)
    got = d.execute_async_script(TRACE_JS, base + f"shared/scenes/{hw}/{rel}", options, x, y, sample)
    with open(native_json, encoding="utf-8") as f:
        want = json.load(f)
    for t in (got, want):
        t.pop("scene", None)
    missing = shows(want) if shows else None
    check(got == want and not missing, f"a trace through the API equals ./raytracer --trace-json ({hw}/{rel} {x},{y}"
          + (f", sample {sample}{what}" if what else "") + (f"; the trace lacks {missing}" if missing else "")
          + (f"; {got['error']}" if "error" in got else "") + ")")


def page_checks(shared, scenes, tmp):
    print("== the page in headless Chromium", flush=True)
    fixtures = os.path.join(tmp, "fixtures")
    os.makedirs(fixtures, exist_ok=True)
    server = start_server(shared, fixtures)
    base = f"http://127.0.0.1:{server.server_address[1]}/"
    d = browser()
    try:
        d.get(base + "index.html")
        check(wait_for(d, "return window.raytracer && document.querySelectorAll('#bundled option').length > 1") is not None,
              "the page loads, with its bundled scenes listed")

        for hw, rel in scenes:
            t0 = time.time()
            flags, options, what = settings(hw)
            r = render_in_page(d, base + f"shared/scenes/{hw}/{rel}", {"workers": 2, **options})
            if check("error" not in r, f"page renders {hw}/{rel}" + (": " + r.get("error", "") if "error" in r else "")):
                native = native_images(os.path.join(shared, "scenes", hw, rel),
                                       os.path.join(tmp, "native-page", hw, os.path.dirname(rel)), flags)
                for im in r["images"]:
                    name = os.path.splitext(im["name"])[0]
                    ppm = os.path.join(tmp, f"page-{hw}-{name}.ppm")
                    write_ppm(ppm, im["width"], im["height"], base64.b64decode(im["rgba"]))
                    same, text = identical(ppm, native.get(name, "missing"))
                    passes = ", ".join(map(str, im["passes"]))
                    check(same and im["shown"] == im["passes"],
                          f"page {hw}/{rel} {name}{what}: equal to native ({im['seconds']:.3f} s, "
                          f"{r['workers']} workers, passes shown {passes}; {text[0]})")
            if hw == "hw3":
                Clock.hw3 += time.time() - t0

        # The float copy too, on two scenes: the same bytes as ./raytracer --precision float.
        for hw, rel in (("hw1", "scienceTree_glass.json"), ("hw2", "ellipsoids.json")):
            r = render_in_page(d, base + f"shared/scenes/{hw}/{rel}", {"workers": 2, "precision": "float"})
            out = os.path.join(tmp, "native-float", hw)
            os.makedirs(out, exist_ok=True)
            subprocess.run([RAYTRACER, "-q", "--precision", "float", "-o", out, os.path.join(shared, "scenes", hw, rel)],
                           check=True)
            for im in r.get("images", []):
                ppm = os.path.join(tmp, f"page-float-{im['name']}.ppm")
                write_ppm(ppm, im["width"], im["height"], base64.b64decode(im["rgba"]))
                same, text = identical(ppm, os.path.join(out, im["name"]))
                check(same, f"page {hw}/{rel} in float: equal to native float ({text[0]})")
            check("images" in r, f"page renders {hw}/{rel} in float {r.get('error', '')}")

        # Traces through the API equal the command line's --trace-json; assignment 3's of a
        # sample, each holding the figures of what it samples (the lens and an area light,
        # the shutter's time, a rough surface's turned ray).
        trace_check(d, base, shared, tmp, "hw1", "spheres_mirror.json", 400, 300)
        t0 = time.time()
        trace_check(d, base, shared, tmp, "hw3", "ramazan_tokay/chessboard_arealight_dof.json", 400, 400, 2,
                    lambda t: "lens" if t["sample"]["lens"] is None else None if has_field(t, "area_point")
                    else "area_point")
        trace_check(d, base, shared, tmp, "hw3", "cornellbox_boxes_dynamic.json", 140, 380, 3,
                    lambda t: None if t["sample"]["time"] and t["ray"]["time"] == t["sample"]["time"] else "time")
        trace_check(d, base, shared, tmp, "hw3", "cornellbox_brushed_metal.json", 500, 530, 1,
                    lambda t: None if has_field(t, "ideal_direction") else "ideal_direction")
        Clock.hw3 += time.time() - t0
        page_passes(d, base, shared, tmp)

        # A scene given through the file input, rendered by the page's button.
        knot = os.path.join(REPO, "scenes", "knot")
        inputs = [os.path.join(knot, n) for n in sorted(os.listdir(knot))]
        d.get(base + "index.html")
        wait_for(d, "return window.raytracer")
        d.find_element("id", "files").send_keys("\n".join(inputs))
        wait_for(d, "return window.app.scene === 'knot.json' && !document.getElementById('render').disabled")
        d.find_element("id", "render").click()
        ok = wait_for(d, "return document.querySelectorAll('#images canvas.render').length > 0 || "
                         "document.getElementById('error').textContent", 300)
        rgba = d.execute_script(CANVAS_JS)
        knot_png = list(native_images(os.path.join(knot, "knot.json"), os.path.join(tmp, "native-knot")).values())[0]
        if check(ok and rgba is not None, "a scene given through the file input renders (scenes/knot: "
                 + d.find_element("id", "error").text + ")"):
            canvas_equals(rgba, knot_png, os.path.join(tmp, "page-knot.ppm"), "its canvas")

        # The same scene dropped onto the page (a drop event carrying the files).
        d.get(base + "index.html")
        wait_for(d, "return window.raytracer")
        d.execute_async_script("""
            const done = arguments[0];
            (async () => {
              const dt = new DataTransfer();
              for (const n of ['knot.json', 'knot_1.ply', 'knot_2.ply', 'knot_3.ply'])
                dt.items.add(new File([await (await fetch('scenes/knot/' + n)).arrayBuffer()], n));
              document.getElementById('drop').dispatchEvent(new DragEvent('drop', {dataTransfer: dt, bubbles: true}));
            })().then(done, done);""")
        wait_for(d, "return window.app.scene === 'knot.json' && !document.getElementById('render').disabled")
        d.find_element("id", "render").click()
        dropped = wait_for(d, CANVAS_JS, 300)
        if check(dropped is not None, "a scene dropped onto the page renders (scenes/knot)"):
            canvas_equals(dropped, knot_png, os.path.join(tmp, "page-knot-dropped.ppm"), "its canvas")

        # A bad scene: the command line's line, next to the file's name; the page keeps working.
        bad = json.load(open(os.path.join(shared, "scenes", "hw1", "simple.json"), encoding="utf-8"))
        spheres = bad["Scene"]["Objects"]["Sphere"]
        (spheres[0] if isinstance(spheres, list) else spheres)["Radius"] = "-1"
        bad_path = os.path.join(fixtures, "bad.json")
        with open(bad_path, "w", encoding="utf-8") as f:
            json.dump(bad, f)
        line = subprocess.run([RAYTRACER, "-q", "-o", tmp, "bad.json"], cwd=fixtures, capture_output=True,
                              text=True).stderr.strip()
        d.execute_script("document.getElementById('files').value = ''")  # send_keys adds to a selection
        d.find_element("id", "files").send_keys(bad_path)
        wait_for(d, "return window.app.scene === 'bad.json' && !document.getElementById('render').disabled")
        d.find_element("id", "render").click()
        shown = wait_for(d, "return document.getElementById('error').textContent", 60) or ""
        check(line.startswith("error: bad.json: ") and shown.startswith(line) and "bad.json" in shown[len(line):],
              f"a bad scene shows the command line's line and the file's name ({shown!r})")

        # The page keeps working: a bundled scene; a bad seed in its field shows the renderer's
        # line; the samples, seed and trace sample fields reach the image and a clicked
        # pixel's tree; a comparison.
        set_field = "document.getElementById(arguments[0]).value = arguments[1]"
        d.execute_script("""const s = document.getElementById('bundled'); s.value = 'showcase';
                            s.dispatchEvent(new Event('change'));""")
        wait_for(d, "return window.app.scene === 'showcase.json' && !document.getElementById('render').disabled")
        d.execute_script(set_field, "seed", "abc")
        d.find_element("id", "render").click()
        shown = wait_for(d, "return document.getElementById('error').textContent", 60) or ""
        check(shown.startswith('error: options: seed: unknown option or bad value "abc"'),
              f"a bad seed in its field shows the renderer's line ({shown!r})")
        for field, value in (("seed", "3"), ("samples", "4"), ("sample", "2")):
            d.execute_script(set_field, field, value)
        d.find_element("id", "render").click()
        rendered = wait_for(d, "return window.app.rendering === false && "
                               "document.querySelectorAll('#images canvas.render').length > 0 && "
                               "!document.getElementById('error').textContent", 120) is not None
        showcase = os.path.join(REPO, "scenes", "showcase.json")
        if check(rendered, "after the errors, a bundled scene renders (4 samples, seed 3 in the page's fields)"):
            native = native_images(showcase, os.path.join(tmp, "native-showcase"), ["--samples", "4", "--seed", "3"])
            canvas_equals(d.execute_script(CANVAS_JS), native["showcase"], os.path.join(tmp, "page-showcase.ppm"),
                          "its canvas (./raytracer --samples 4 --seed 3)")
        canvas = d.find_element("css selector", "#images canvas.render")
        d.execute_script("""const c = arguments[0], r = c.getBoundingClientRect();
            c.dispatchEvent(new MouseEvent('click', {clientX: r.left + r.width * 0.5, clientY: r.top + r.height * 0.62, bubbles: true}));""",
                         canvas)
        check(wait_for(d, "return !document.getElementById('trace').hidden && "
                          "document.querySelectorAll('#trace-tree details').length > 0", 60) is not None,
              "clicking a pixel shows its ray tree")
        at = d.execute_script("return window.app.traced")
        native_json = os.path.join(tmp, "trace-showcase.json")
        subprocess.run([RAYTRACER, "--trace", f"{at['x']},{at['y']}", "--sample", "2", "--samples", "4", "--seed", "3",
                        "--trace-json", native_json, showcase], check=True, capture_output=True)
        with open(native_json, encoding="utf-8") as f:
            want = json.load(f)
        got = d.execute_script("return window.app.lastTrace") or {}
        for t in (got, want):
            t.pop("scene", None)
        where = d.find_element("id", "trace-where").text
        figures = d.find_element("id", "trace-sample").text
        check(got == want and "sample 2 of 4 (seed 3)" in where and "pixel_offset" in figures,
              f"its tree is sample 2's, ./raytracer --trace --sample 2's, with the sample's figures ({where})")
        theirs_dir = os.path.join(tmp, "theirs")
        subprocess.run([RAYTRACER, "-q", "--max-depth", "1", "-o", theirs_dir,
                        os.path.join(REPO, "scenes", "showcase.json")], check=True)
        d.find_element("css selector", "#images input[type=file]").send_keys(os.path.join(theirs_dir, "showcase.png"))
        figures = wait_for(d, "return document.querySelector('#images canvas.heat') && "
                              "document.querySelector('.figures').textContent", 60) or ""
        check("off by more than 1" in figures and "PSNR" in figures,
              f"a dropped PNG gives rtdiff's figures and a heatmap ({figures[:90]}...)")
        d.save_screenshot(os.path.join(WEB, "screenshot.png"))
        print(f"      screenshot: {os.path.relpath(os.path.join(WEB, 'screenshot.png'), REPO)}")
    finally:
        d.quit()
        server.shutdown()


def main():
    shared = shared_dir()
    if not shared:
        print("FAIL  check-web: no ../shared (set RT_SHARED_DIR): nothing to compare", file=sys.stderr)
        return 1
    for f in (os.path.join(WEB, "rt.js"), RAYTRACER, RTDIFF):
        if not os.path.exists(f):
            print(f"FAIL  check-web: {f} is missing (make web raytracer rtdiff)", file=sys.stderr)
            return 1
    scenes = complete_scenes(shared) + complete_scenes(shared, ("hw3",))
    t0 = time.time()
    with tempfile.TemporaryDirectory() as tmp:
        node_checks(shared, scenes, tmp)
        page_checks(shared, scenes, tmp)
    print(f"check-web: {time.time() - t0:.0f} s, of which {Clock.hw3:.0f} s on assignment 3's scenes")
    print(f"check-web: {len(failures)} failure(s)" if failures else "check-web: every check passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
