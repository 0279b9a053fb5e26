// The page (index.html): picks the scene files, renders them with raytracer.js, shows the
// images, the ray tree of a clicked pixel, and a comparison with the user's own PNG.
/* global raytracer, sceneFiles */
"use strict";

const $ = (id) => document.getElementById(id);
const state = { files: null, scene: "", result: null, bundled: [] };
window.app = state;  // for tests and the curious

function setError(message) {
  $("error").textContent = message ? message + (state.scene ? "   (scene file: " + state.scene + ")" : "") : "";
}
function setStatus(text) {
  $("status").textContent = text;
}

const baseName = (p) => p.slice(p.lastIndexOf("/") + 1);

// Files the user gave (name -> bytes): the scene is the first JSON file with a "Scene";
// each PLY path it names is served by the given file of the same name.
function useFiles(given) {
  let scene = "", tree = null;
  for (const [name, bytes] of Object.entries(given)) {
    if (!name.toLowerCase().endsWith(".json")) continue;
    try {
      const t = JSON.parse(new TextDecoder().decode(bytes));
      if (t && typeof t === "object" && "Scene" in t) {
        scene = name;
        tree = t;
        break;
      }
    } catch (e) {
      if (!scene) scene = name;  // not JSON: the renderer says where
    }
  }
  const files = { ...given };
  if (tree)
    for (const p of sceneFiles.plyPaths(tree)) {
      const match = Object.keys(given).find((n) => baseName(n) === baseName(p));
      if (match && !(p in files)) files[p] = given[match];
    }
  state.files = files;
  state.scene = scene || Object.keys(given)[0] || "";
  $("filelist").textContent = Object.keys(given).join(", ");
  $("render").disabled = !state.scene;
  setError(scene || !state.scene ? "" : "error: no scene file (JSON with a \"Scene\") among the files");
}

async function readFiles(list) {
  const given = {};
  for (const f of list) given[f.name] = new Uint8Array(await f.arrayBuffer());
  useFiles(given);
}

// The fields as raytracer.js's options. Samples and seed go as typed, for the renderer to
// check (a bad one shows its line); a seed beyond 2^53 as its digits, which a number
// would round.
function options() {
  const o = { cull: $("cull").checked, precision: $("precision").value };
  const depth = parseInt($("max_depth").value, 10);
  if (!Number.isNaN(depth) && depth >= 0) o.max_depth = depth;
  const eps = parseFloat($("epsilon_scale").value);
  if (eps > 0 && eps !== 1) o.epsilon_scale = eps;
  const samples = $("samples").value;
  if (samples !== "") o.samples = Number(samples);
  const seed = $("seed").value.trim();
  if (seed !== "") o.seed = /^\d+$/.test(seed) && Number.isSafeInteger(Number(seed)) ? Number(seed) : seed;
  if ($("sampler").value !== "random") o.sampler = $("sampler").value;
  const w = parseInt($("workers").value, 10);
  if (w > 0) o.workers = w;
  return o;
}

function canvasOf(width, height, rgba) {
  const c = document.createElement("canvas");
  c.width = width;
  c.height = height;
  c.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(rgba.buffer, rgba.byteOffset, rgba.length), width, height), 0, 0);
  return c;
}

// The pixel under a mouse event, as --trace takes it (column, row from the top left).
function pixelOf(ev, canvas, width, height) {
  const r = canvas.getBoundingClientRect();
  return {
    x: Math.min(width - 1, Math.max(0, Math.floor((ev.clientX - r.left) * width / r.width))),
    y: Math.min(height - 1, Math.max(0, Math.floor((ev.clientY - r.top) * height / r.height))),
  };
}

const seconds = (s) => (s < 10 ? s.toFixed(1) : s.toFixed(0)) + " s";

// Renders the scene, showing each image as its passes come: a first image after one
// sample per pixel, then refined (raytracer.js, onPass), with the samples done and the
// time left in the status line and under the image.
async function render() {
  if (!state.files) return;
  setError("");
  $("render").disabled = true;
  $("images").textContent = "";
  $("trace").hidden = true;
  const progress = $("progress");
  progress.value = 0;
  const opts = options();
  state.options = opts;
  state.rendering = true;
  state.passes = [];  // [camera, samples per pixel] of each image shown
  const views = [];
  let shown = "";  // the latest pass, for the status line
  const t0 = performance.now();
  setStatus("rendering " + state.scene + " …");
  try {
    const result = await raytracer.render({
      files: state.files, scene: state.scene,
      options: {
        ...opts,
        onProgress: (camera, done, total) => {
          progress.value = done / total;
          const elapsed = (performance.now() - t0) / 1000, f = done / total;
          setStatus("rendering " + state.scene + ": image " + (camera + 1) + ", " + (100 * f).toFixed(0) + "%" +
                    shown + ", " + seconds(elapsed) + (f > 0 && f < 1 ? ", about " + seconds(elapsed * (1 - f) / f) + " left" : ""));
        },
        onPass: (img) => {
          state.passes.push([img.camera, img.samplesDone]);
          shown = img.samples > 1 ? " (" + img.samplesDone + " of " + img.samples + " samples per pixel shown)" : "";
          if (!views[img.camera]) views[img.camera] = showImage(img, img.camera);
          else views[img.camera].update(img);
        },
      },
    });
    state.result = { ...result, options: opts };
    progress.value = 1;
    result.images.forEach((img, camera) => views[camera].update(img));
    setStatus(result.images.length + " image(s), " + result.seconds.toFixed(3) + " s rendering on " + result.workers +
              " worker(s), load " + result.loadSeconds.toFixed(3) + " s" +
              (result.warnings.length ? "; warnings: " + result.warnings.join("; ") : ""));
  } catch (e) {
    setError(e.message);
    setStatus("");
  } finally {
    state.rendering = false;
    $("render").disabled = false;
  }
}

// An image's box: its canvas, caption, PNG download, comparison and tracing; update(img)
// draws a later pass (or the final image) in it.
function showImage(first, camera) {
  const view = { img: first };
  const box = document.createElement("div");
  box.className = "image";
  const stack = document.createElement("div");
  stack.className = "stack";
  const canvas = canvasOf(first.width, first.height, first.rgba);
  canvas.className = "render";
  stack.appendChild(canvas);
  const caption = document.createElement("div");
  caption.className = "caption";
  const text = document.createTextNode("");
  const link = document.createElement("a");
  link.textContent = "download " + first.name;
  link.download = first.name.replace(/\.[^.]*$/, "") + ".png";
  link.href = "#";
  link.onclick = (ev) => {
    ev.preventDefault();
    canvas.toBlob((blob) => {
      const a = document.createElement("a");
      a.href = URL.createObjectURL(blob);
      a.download = link.download;
      a.click();
      setTimeout(() => URL.revokeObjectURL(a.href), 1000);
    }, "image/png");
  };
  caption.append(text, link);
  // A pass (samplesDone of samples, secondsLeft) or the final image (its seconds).
  view.update = (img) => {
    view.img = img;
    const c = img.rgba;
    canvas.getContext("2d").putImageData(new ImageData(new Uint8ClampedArray(c.buffer, c.byteOffset, c.length), img.width, img.height), 0, 0);
    const size = img.name + ": " + img.width + "x" + img.height + ", ";
    text.textContent = img.secondsLeft > 0
      ? size + img.samplesDone + " of " + img.samples + " samples/pixel (pass " + img.pass + " of " + img.passes.length +
        "), " + seconds(img.seconds) + ", about " + seconds(img.secondsLeft) + " left  "
      : size + (img.samples ? img.samples + " samples/pixel, " : "") + img.seconds.toFixed(3) + " s  ";
  };
  view.update(first);
  const compare = document.createElement("label");
  compare.className = "button";
  compare.textContent = "compare with your PNG";
  const input = document.createElement("input");
  input.type = "file";
  input.accept = "image/png,image/*";
  compare.appendChild(input);
  const figures = document.createElement("div");
  figures.className = "figures";
  const toggle = document.createElement("label");
  toggle.hidden = true;
  const check = document.createElement("input");
  check.type = "checkbox";
  check.checked = true;
  toggle.append(check, " heatmap over the image");
  input.onchange = () => input.files[0] && compareWith(input.files[0], view.img, stack, figures, toggle, check, camera);
  canvas.onclick = (ev) => {
    const p = pixelOf(ev, canvas, first.width, first.height);
    traceAt(camera, p.x, p.y);
  };
  box.append(stack, caption, compare, " ", toggle, figures);
  $("images").appendChild(box);
  return view;
}

async function decodePng(file) {
  const bitmap = await createImageBitmap(file, { premultiplyAlpha: "none", colorSpaceConversion: "none" });
  const c = document.createElement("canvas");
  c.width = bitmap.width;
  c.height = bitmap.height;
  const g = c.getContext("2d");
  g.drawImage(bitmap, 0, 0);
  return { width: bitmap.width, height: bitmap.height, rgba: new Uint8Array(g.getImageData(0, 0, c.width, c.height).data.buffer) };
}

async function compareWith(file, img, stack, figures, toggle, check, camera) {
  try {
    const theirs = await decodePng(file);
    if (theirs.width !== img.width || theirs.height !== img.height) {
      figures.textContent = file.name + " is " + theirs.width + "x" + theirs.height + ", this image " + img.width + "x" +
                            img.height + ": totally different";
      return;
    }
    const { figures: f, heat } = await raytracer.compare(img.rgba, theirs.rgba, img.width, img.height, 1);
    figures.textContent = "ours vs " + file.name + ": max " + f.max_diff + ", mean " + f.mean_diff.toFixed(4) + ", " +
      f.pixels_over + " of " + f.pixels + " pixels (" + f.pct_over.toFixed(4) + "%) off by more than 1, PSNR " + f.text +
      ", box " + (f.box ? "x " + f.box[0] + ".." + f.box[2] + " y " + f.box[1] + ".." + f.box[3] : "none") +
      (f.pixels_over ? "; click a red pixel to trace it" : "");
    stack.querySelectorAll("canvas.heat").forEach((c) => c.remove());
    const h = canvasOf(img.width, img.height, heat);
    h.className = "heat";
    h.onclick = (ev) => {
      const p = pixelOf(ev, h, img.width, img.height);
      traceAt(camera, p.x, p.y);
    };
    stack.appendChild(h);
    toggle.hidden = false;
    check.onchange = () => { h.hidden = !check.checked; };
  } catch (e) {
    // raytracer.js's errors are whole lines already; the PNG decoder's name nothing.
    figures.textContent = /^error: /.test(e.message) ? e.message : "error: " + file.name + ": " + e.message;
  }
}

const fmt = (v) => Array.isArray(v) ? "(" + v.map(fmt).join(", ") + ")" : typeof v === "number" ? String(+v.toPrecision(6)) : String(v);

function entry(dl, key, value) {
  if (value === null || value === undefined) return;
  const dt = document.createElement("dt");
  dt.textContent = key;
  const dd = document.createElement("dd");
  if (typeof value === "object" && !Array.isArray(value))
    dd.textContent = Object.entries(value).filter(([, v]) => v !== null).map(([k, v]) => k + " " + fmt(v)).join(", ");
  else dd.textContent = fmt(value);
  dl.append(dt, dd);
}

function swatch(rgb) {
  const s = document.createElement("span");
  s.className = "swatch";
  const c = rgb.map((v) => Math.max(0, Math.min(255, Math.round(v))));
  s.style.background = "rgb(" + c.join(",") + ")";
  return s;
}

// One ray of the tree: what it hit, the lights, the Fresnel terms, its colour; its
// children (reflection, refraction) below it. `timed`: the pixel's samples draw times.
function rayNode(ray, timed) {
  const d = document.createElement("details");
  d.open = ray.depth < 2;
  const s = document.createElement("summary");
  const what = !ray.traced ? "not traced" : ray.hit ? "hit " + ray.hit.object + (ray.hit.material ? ", material " + ray.hit.material.id + " (" + ray.hit.material.type + ")" : "") : "miss";
  s.append(ray.kind + " ray, depth " + ray.depth + ": " + what + ", returns ", swatch(ray.radiance || [0, 0, 0]), " " + fmt(ray.radiance || []));
  d.appendChild(s);
  const dl = document.createElement("dl");
  for (const k of ["origin", "direction", "ideal_direction", "weight", "factor", "tmin", "tmax", "cull", "culled", "inside_material"]) entry(dl, k, ray[k]);
  if (timed) entry(dl, "time", ray.time);
  if (ray.hit) for (const [k, v] of Object.entries(ray.hit)) entry(dl, "hit." + k, v);
  for (const k of ["ambient", "local", "fresnel", "beer", "depth_limit"]) entry(dl, k, ray[k]);
  d.appendChild(dl);
  for (const l of ray.lights || []) {
    const ld = document.createElement("details");
    const ls = document.createElement("summary");
    ls.textContent = "light " + l.light + (l.area_point ? " (area, at " + fmt(l.area_point) + ")" : "") + (l.shadowed ? ": shadowed by " + (l.occluder && l.occluder.object ? l.occluder.object : "an object") : l.facing === false ? ": faces away" : ": adds " + fmt(l.added || []));
    ld.appendChild(ls);
    const ldl = document.createElement("dl");
    for (const [k, v] of Object.entries(l)) if (k !== "light") entry(ldl, k, v);
    ld.appendChild(ldl);
    d.appendChild(ld);
  }
  for (const c of ray.children || []) d.appendChild(rayNode(c, timed));
  return d;
}

// Traces sample `trace sample` of a pixel with the options its image was rendered with.
async function traceAt(camera, x, y) {
  state.traced = { camera, x, y };
  try {
    const sample = Number($("sample").value || 0);
    const opts = state.options || options();
    const t = await raytracer.trace({ files: state.files, scene: state.scene, options: opts, camera, x, y, sample });
    setError("");
    const s = t.sample;
    // The seed as given: the trace's, a JSON number, loses digits beyond 2^53 in JavaScript.
    $("trace-where").textContent = "pixel " + x + "," + y + " of camera " + (camera + 1) +
      (s ? ", sample " + s.index + " of " + t.samples + " (seed " + (opts.seed === undefined ? 0 : opts.seed) + ")" : "") +
      " (pixel value " + fmt(t.pixel) + ")";
    // The sample's figures: where it fell in the pixel, on the lens and in the shutter,
    // its own radiance, and the mean of the pixel's samples that the image holds.
    // Without motion every time is 0, and not shown.
    const timed = s !== null && s.time !== 0;
    const dl = $("trace-sample");
    dl.textContent = "";
    if (s) {
      entry(dl, "pixel_offset", s.pixel_offset);
      entry(dl, "lens", s.lens);
      if (timed) entry(dl, "time", s.time);
      entry(dl, "radiance", t.radiance);
      entry(dl, "clamped", t.clamped);
      entry(dl, "mean", s.mean);
    }
    const tree = $("trace-tree");
    tree.textContent = "";
    tree.appendChild(rayNode(t.ray, timed));
    $("trace").hidden = false;
    state.lastTrace = t;
  } catch (e) {
    setError(e.message);
  }
}

async function loadBundled(name) {
  const s = state.bundled.find((b) => b.name === name);
  if (!s) return;
  const given = {};
  for (const f of s.files) given[f] = new Uint8Array(await (await fetch("scenes/" + f)).arrayBuffer());
  useFiles(given);
  state.scene = s.scene;
}

function setup() {
  const drop = $("drop");
  drop.ondragover = (e) => { e.preventDefault(); drop.classList.add("over"); };
  drop.ondragleave = () => drop.classList.remove("over");
  drop.ondrop = (e) => {
    e.preventDefault();
    drop.classList.remove("over");
    readFiles(e.dataTransfer.files);
  };
  $("files").onchange = (e) => readFiles(e.target.files);
  $("render").onclick = render;
  $("sample").onchange = () => state.traced && !$("trace").hidden && traceAt(state.traced.camera, state.traced.x, state.traced.y);
  $("bundled").onchange = (e) => loadBundled(e.target.value);
  $("workers").placeholder = String(raytracer.defaultWorkers());
  fetch("scenes/index.json").then((r) => r.json()).then((list) => {
    state.bundled = list;
    for (const s of list) {
      const o = document.createElement("option");
      o.value = o.textContent = s.name;
      $("bundled").appendChild(o);
    }
  }).catch(() => {});
}

setup();
