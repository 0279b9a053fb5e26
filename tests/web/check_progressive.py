"""make check-web's checks of progressive rendering (docs/web.md, "Tests"): a small scene of
assignment 3 rendered pass after pass by the module under Node, through the page's API and
by the page's button, each pass against ./raytracer."""
import base64
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import REPO, check, identical  # noqa: E402
from web_support import CANVAS_JS, Clock, canvas_equals, native_images, render_in_page, wait_for, write_ppm  # noqa: E402

# Progressive rendering, checked on a small scene of assignment 3 (chessboard_arealight_dof,
# a lens and an area light, at 160x160) of 40 samples per pixel under a seed: its passes end
# at these samples per pixel (raytracer.passes), and under the default (random) sampler the
# image after 32 of 40 samples is the render at 32 (neither count a square: the same
# samples, rt/shading/pixel_samples.h).
SMALL, SMALL_SEED, SMALL_PASSES = "small_dof", 7, [1, 16, 32, 40]


def small_scene(shared, fixtures):
    """The small scene, written into `fixtures`: its path."""
    with open(os.path.join(shared, "scenes", "hw3", "ramazan_tokay", "chessboard_arealight_dof.json"),
              encoding="utf-8") as f:
        tree = json.load(f)
    cams = tree["Scene"]["Cameras"]["Camera"]
    (cams[0] if isinstance(cams, list) else cams).update(
        {"ImageResolution": "160 160", "NumSamples": str(SMALL_PASSES[-1]), "ImageName": SMALL + ".png"})
    os.makedirs(fixtures, exist_ok=True)
    path = os.path.join(fixtures, SMALL + ".json")
    with open(path, "w", encoding="utf-8") as f:
        json.dump(tree, f)
    return path


def node_passes(shared, tmp):
    """The small scene by the module alone under Node (node_render.js --passes)."""
    t0 = time.time()
    scene = small_scene(shared, os.path.join(tmp, "fixtures"))
    out = os.path.join(tmp, "node-passes")
    r = subprocess.run(["node", "--no-experimental-fetch", os.path.join(REPO, "tests", "web", "node_render.js"), out,
                        "--passes", "--options", json.dumps({"seed": SMALL_SEED}), scene], capture_output=True, text=True)
    lines = [line.split("\t") for line in r.stdout.splitlines()]
    check(r.returncode == 0, "node renders the small scene with --passes " + r.stderr.strip())
    check_passes("node", {int(c[2]): c[0] for c in lines if len(c) == 3}, scene, tmp, time.time() - t0)
    Clock.hw3 += time.time() - t0


def check_passes(who, passes, scene, tmp, seconds):
    """{samples per pixel: ppm} of the small scene's passes against ./raytracer: all of them
    shown, the last the image of 40 samples, the one of 32 --samples 32's, the first not the last."""
    flags = ["--seed", str(SMALL_SEED)]
    final = native_images(scene, os.path.join(tmp, "native-small"), flags)[SMALL]
    at32 = native_images(scene, os.path.join(tmp, "native-small-32"), flags + ["--samples", "32"])[SMALL]
    if not check(sorted(passes) == SMALL_PASSES, f"{who} renders {SMALL} (40 samples, seed {SMALL_SEED}) pass after "
                 f"pass ({seconds:.2f} s): samples per pixel {', '.join(map(str, sorted(passes)))}"):
        return
    same, text = identical(passes[40], final)
    check(same, f"  its last pass equals ./raytracer --seed {SMALL_SEED} ({text[0]})")
    same, text = identical(passes[32], at32)
    check(same, f"  its pass of 32 samples equals ./raytracer --seed {SMALL_SEED} --samples 32 ({text[0]})")
    check(not identical(passes[1], final)[0], "  its first pass (1 sample per pixel) is another image")


# Records each text the images' captions and the status line show, in window.seen.
WATCH_JS = """
window.seen = [];
const note = () => { for (const e of document.querySelectorAll('#images .caption, #status')) if (!window.seen.includes(e.textContent)) window.seen.push(e.textContent); };
new MutationObserver(note).observe(document.body, {subtree: true, childList: true, characterData: true});
"""


def page_passes(d, base, shared, tmp):
    """The small scene through the API, its passes' images kept, and through the page's
    button: a caption for each pass with the samples done and the time left."""
    t0 = time.time()
    scene = small_scene(shared, os.path.join(tmp, "fixtures"))
    r = render_in_page(d, base + f"fixtures/{SMALL}.json", {"workers": 2, "seed": SMALL_SEED}, keep=True)
    passes = {}
    for k, rgba in (r["images"][0]["shown"] if "images" in r else []):
        passes[k] = os.path.join(tmp, f"page-{SMALL}-{k}.ppm")
        write_ppm(passes[k], 160, 160, base64.b64decode(rgba))
    check_passes("the page's API" + (": " + r["error"] if "error" in r else ""), passes, scene, tmp, time.time() - t0)

    d.get(base + "index.html")
    wait_for(d, "return window.raytracer")
    d.find_element("id", "files").send_keys(scene)
    wait_for(d, f"return window.app.scene === '{SMALL}.json' && !document.getElementById('render').disabled")
    d.execute_script("document.getElementById('seed').value = arguments[0]", str(SMALL_SEED))
    d.execute_script(WATCH_JS)
    d.find_element("id", "render").click()
    ok = wait_for(d, "return window.app.rendering === false && document.querySelector('#images canvas.render')", 120)
    seen = d.execute_script("return window.seen") or []
    shown = [k for c, k in d.execute_script("return window.app.passes") or []]
    captions = [t for t in seen if "samples/pixel (pass" in t and "left" in t]
    check(ok and shown == SMALL_PASSES and len(captions) == 3 and any("% (32 of 40 samples" in t and " left" in t
                                                                       for t in seen),
          f"the page's button shows its passes {shown}, the samples done and the time left in its caption "
          f"({captions[0] if captions else 'none'}) and status line")
    canvas_equals(d.execute_script(CANVAS_JS), native_images(scene, os.path.join(tmp, "native-small"),
                                                             ["--seed", str(SMALL_SEED)])[SMALL],
                  os.path.join(tmp, "page-small.ppm"), "its canvas")
    Clock.hw3 += time.time() - t0
