"""What the page's checks (check_web.py, check_progressive.py, bench_web.py) share: the
native images, a local server for build/web and ../shared, headless Chromium, and the
scripts that render through the page's API and read its canvas."""
import base64
import functools
import http.server
import os
import shutil
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import REPO, RAYTRACER, check, identical  # noqa: E402

WEB = os.environ.get("RT_WEB_DIR") or os.path.join(REPO, "build", "web")  # another build: RT_WEB_DIR


def write_ppm(path, width, height, rgba):
    rgb = bytearray(width * height * 3)
    rgb[0::3], rgb[1::3], rgb[2::3] = rgba[0::4], rgba[1::4], rgba[2::4]
    with open(path, "wb") as f:
        f.write(b"P6\n%d %d\n255\n" % (width, height) + bytes(rgb))


_native = {}  # (scene, flags) -> its images, rendered once for the Node and the page checks


def native_images(scene, out, flags=()):
    """./raytracer's images of `scene` with `flags` (into `out` the first time): {image name: path}."""
    key = (scene, tuple(flags))
    if key not in _native:
        os.makedirs(out, exist_ok=True)
        before = set(os.listdir(out))
        subprocess.run([RAYTRACER, "-q", *flags, "-o", out, scene], check=True)
        _native[key] = {os.path.splitext(n)[0]: os.path.join(out, n) for n in set(os.listdir(out)) - before}
    return _native[key]


class Clock:
    """Seconds spent on assignment 3's scenes, for the summary (docs/web.md, "Tests")."""
    hw3 = 0.0


class Handler(http.server.SimpleHTTPRequestHandler):
    """build/web at /, ../shared at /shared/, the test's own files at /fixtures/."""
    roots = {}

    def translate_path(self, path):
        path = path.split("?", 1)[0]
        for prefix, root in self.roots.items():
            if path.startswith(prefix):
                return os.path.join(root, path[len(prefix):].lstrip("/"))
        return super().translate_path(path)

    def log_message(self, *args):
        pass


def start_server(shared, fixtures):
    Handler.roots = {"/shared/": shared, "/fixtures/": fixtures}
    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), functools.partial(Handler, directory=WEB))
    threading.Thread(target=server.serve_forever, daemon=True).start()
    return server


def browser():
    from selenium import webdriver
    from selenium.webdriver.chrome.service import Service
    o = webdriver.ChromeOptions()
    o.binary_location = shutil.which("chromium") or "/usr/bin/chromium"
    for a in ("--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,1800"):
        o.add_argument(a)
    d = webdriver.Chrome(service=Service(shutil.which("chromedriver") or "/usr/bin/chromedriver"), options=o)
    d.set_script_timeout(600)
    return d


# fetchScene(url): a scene of ../shared and its PLY files, as the API takes them: {name, files}.
FETCH_JS = """
async function fetchScene(url) {
  const dir = url.slice(0, url.lastIndexOf('/') + 1), name = url.slice(url.lastIndexOf('/') + 1);
  const text = new Uint8Array(await (await fetch(url)).arrayBuffer());
  const files = {[name]: text};
  for (const p of sceneFiles.plyPaths(JSON.parse(new TextDecoder().decode(text))))
    files[p] = new Uint8Array(await (await fetch(dir + p)).arrayBuffer());
  return {name, files};
}
"""

# Renders a scene of ../shared through the API: returns {images: [{name, width, height,
# passes, shown, rgba (base64)}], seconds} or {error}; `shown`: the samples per pixel of
# each pass the API showed (onPass), with its image when `keep`.
RENDER_JS = FETCH_JS + """
const [url, options, keep, done] = arguments;
(async () => {
  const {name, files} = await fetchScene(url);
  const b64 = (u8) => { let s = ''; for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode.apply(null, u8.subarray(i, i + 0x8000)); return btoa(s); };
  const shown = [];
  const onPass = (i) => { (shown[i.camera] = shown[i.camera] || []).push(keep ? [i.samplesDone, b64(i.rgba)] : i.samplesDone); };
  const r = await raytracer.render({files, scene: name, options: {...options, onPass}});
  return {seconds: r.seconds, workers: r.workers, images: r.images.map((i, c) => ({name: i.name, width: i.width, height: i.height,
          seconds: i.seconds, passes: i.passes, shown: shown[c], rgba: b64(i.rgba)}))};
})().then(done, e => done({error: String(e && e.message || e)}));
"""


def render_in_page(d, url, options, keep=False):
    return d.execute_async_script(RENDER_JS, url, options, keep)


# The first rendered canvas as [width, height, RGBA in base64], or null while there is none.
CANVAS_JS = """
const c = document.querySelector('#images canvas.render');
if (!c) return null;
const u8 = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
let s = ''; for (let i = 0; i < u8.length; i += 0x8000) s += String.fromCharCode.apply(null, u8.subarray(i, i + 0x8000));
return [c.width, c.height, btoa(s)];
"""


def canvas_equals(canvas, native_png, ppm, what):
    """Checks a CANVAS_JS result against a native image."""
    write_ppm(ppm, canvas[0], canvas[1], base64.b64decode(canvas[2]))
    same, text = identical(ppm, native_png)
    check(same, f"  and {what} equals native ({text[0]})")


def wait_for(d, js, timeout=120):
    t0 = time.time()
    while time.time() - t0 < timeout:
        v = d.execute_script(js)
        if v:
            return v
        time.sleep(0.1)
    return None
