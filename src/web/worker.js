// One renderer in a Web Worker (docs/web.md): its own WebAssembly module (rt.js, rt.wasm)
// with its own copy of the scene. raytracer.js sends it requests, each with an id that its
// answer carries back:
//   {type: "load", files: {path: Uint8Array}, scene, options, precision}
//       -> {error, info: {cameras: [{name, width, height}], warnings}}
//   {type: "render", camera, parts: [k, ...], total} -> {type: "progress"} per part, then
//       {rgba}: the image with the parts' tiles rendered (alpha 255), the rest zero
//   {type: "refine", camera, parts: [k, ...], total, bounds: [0, b1, ..., N]} -> pass i
//       adds samples [bounds[i], bounds[i + 1]) to each part: {type: "progress", samples}
//       per part, then {type: "pass", pass: i, rgba}: the parts' pixels' means so far; then {}
//   {type: "trace", camera, x, y, sample} -> {trace}: the --trace-json object
//   {type: "compare", a, b, width, height, tolerance} -> {figures, heat}
/* global createRaytracerModule, importScripts, sceneFiles */
"use strict";
importScripts("rt.js", "scene_files.js");

const ready = createRaytracerModule();
let loads = 0;

function cString(M, s) {
  const n = M.lengthBytesUTF8(s) + 1;
  const p = M._malloc(n);
  M.stringToUTF8(s, p, n);
  return p;
}

// Calls an export taking strings (freed after) and returning a string.
function callText(M, name, strings, numbers = []) {
  const ptrs = strings.map((s) => cString(M, s));
  try {
    return M.UTF8ToString(M[name](...ptrs, ...numbers));
  } finally {
    ptrs.forEach((p) => M._free(p));
  }
}

// Writes the files under a fresh folder and makes it the current one, so that messages
// name them as the command line run in the scene's folder would.
function writeFiles(M, files) {
  const root = "/scene" + ++loads;
  sceneFiles.writeFiles(M.FS, root, files);
  M.FS.chdir(root);
  return root;
}

function removeTree(M, dir) {
  for (const name of M.FS.readdir(dir)) {
    if (name === "." || name === "..") continue;
    const p = dir + "/" + name;
    if (M.FS.isDir(M.FS.stat(p).mode)) removeTree(M, p);
    else M.FS.unlink(p);
  }
  M.FS.rmdir(dir);
}

let current = null;  // the folder of the loaded scene's files

// Runs f(buf, bytes) with a zeroed RGBA image of camera `camera` in the module's memory.
function withImage(M, camera, f) {
  const cam = JSON.parse(M.UTF8ToString(M._rtw_scene())).cameras[camera];
  const bytes = cam.width * cam.height * 4;
  const buf = M._malloc(bytes);
  try {
    M.HEAPU8.fill(0, buf, buf + bytes);
    return f(buf, bytes);
  } finally {
    M._free(buf);
  }
}

const handlers = {
  load(M, m) {
    if (current) {
      M.FS.chdir("/");
      removeTree(M, current);
      current = null;
    }
    current = writeFiles(M, m.files);
    const error = callText(M, "_rtw_load", [m.scene, JSON.stringify(m.options || {}), m.precision || "double"]);
    const info = JSON.parse(M.UTF8ToString(M._rtw_scene()));
    return { error, info };
  },
  render(M, m, post) {
    return withImage(M, m.camera, (buf, bytes) => {
      for (const part of m.parts) {
        const error = M.UTF8ToString(M._rtw_render_part(m.camera, part, m.total, buf));
        if (error) return { error };
        post({ type: "progress" });
      }
      return { rgba: M.HEAPU8.slice(buf, buf + bytes) };
    });
  },
  refine(M, m, post) {
    return withImage(M, m.camera, (buf, bytes) => {
      for (let i = 0; i + 1 < m.bounds.length; ++i) {
        const k0 = m.bounds[i], k1 = m.bounds[i + 1];
        for (const part of m.parts) {
          const error = M.UTF8ToString(M._rtw_refine_part(m.camera, part, m.total, k0, k1, buf));
          if (error) return { error };
          post({ type: "progress", samples: k1 - k0 });
        }
        const rgba = M.HEAPU8.slice(buf, buf + bytes);
        post({ type: "pass", pass: i, rgba }, [rgba.buffer]);
      }
      return {};
    });
  },
  trace(M, m) {
    return { trace: JSON.parse(M.UTF8ToString(M._rtw_trace(m.camera, m.x, m.y, m.sample || 0))) };
  },
  compare(M, m) {
    const n = m.width * m.height * 4;
    const a = M._malloc(n), b = M._malloc(n), heat = M._malloc(n);
    try {
      M.HEAPU8.set(m.a, a);
      M.HEAPU8.set(m.b, b);
      const figures = JSON.parse(M.UTF8ToString(M._rtw_compare(a, b, m.width, m.height, m.tolerance, heat)));
      return { figures, heat: M.HEAPU8.slice(heat, heat + n) };
    } finally {
      [a, b, heat].forEach((p) => M._free(p));
    }
  },
};

self.onmessage = async (e) => {
  const m = e.data;
  const post = (reply, transfer) => self.postMessage({ id: m.id, ...reply }, transfer || []);
  try {
    const M = await ready;
    const result = handlers[m.type](M, m, post);
    const transfer = [result.rgba, result.heat].filter((x) => x).map((x) => x.buffer);
    self.postMessage({ id: m.id, type: "done", ...result }, transfer);
  } catch (err) {
    self.postMessage({ id: m.id, type: "done", error: "internal error: " + (err && err.message ? err.message : err) });
  }
};
