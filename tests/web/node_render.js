// Renders scene files with the WebAssembly module alone (build/web/rt.js) under Node, one
// thread, as the page's workers do: node node_render.js OUT_DIR [--precision float]
// [--options JSON] [--passes] SCENE.json... (JSON: the page's load options, {"samples": 4,
// "seed": 7}) writes OUT_DIR/<ImageName without extension>.ppm for every camera and prints
// one line per image: "<ppm path>\t<render seconds>". An image with samples renders
// progressively, in the page's passes (raytracer.passes, rtw_refine_part); --passes writes
// each pass's image too, <name>.<samples per pixel>.ppm, with a line "<ppm path>\t<seconds
// so far>\t<samples per pixel>" (the last pass's file is the image's). Errors: one line,
// exit 1.
// Run with --no-experimental-fetch under Node 18 and later (docs/web.md).
"use strict";
const fs = require("fs");
const path = require("path");
const vm = require("vm");
// Another build's module: RT_WEB_DIR (as check_web.py).
const { plyPaths, writeFiles } = require(path.join(__dirname, "..", "..", "src", "web", "scene_files.js"));
const createRaytracerModule = require(path.join(process.env.RT_WEB_DIR || path.join(__dirname, "..", "..", "build", "web"), "rt.js"));

// The page's passes (raytracer.js, which needs no worker until it renders).
const api = { performance, console };
api.self = api;
vm.createContext(api);
vm.runInContext(fs.readFileSync(path.join(__dirname, "..", "..", "src", "web", "raytracer.js"), "utf8"), api);
const passes = api.raytracer.passes;

function cString(M, s) {
  const n = M.lengthBytesUTF8(s) + 1;
  const p = M._malloc(n);
  M.stringToUTF8(s, p, n);
  return p;
}

function writePpm(file, cam, rgba) {
  const rgb = Buffer.alloc(cam.width * cam.height * 3);
  for (let k = 0; k < cam.width * cam.height; ++k) {
    rgb[3 * k] = rgba[4 * k];
    rgb[3 * k + 1] = rgba[4 * k + 1];
    rgb[3 * k + 2] = rgba[4 * k + 2];
  }
  fs.writeFileSync(file, Buffer.concat([Buffer.from(`P6\n${cam.width} ${cam.height}\n255\n`), rgb]));
}

async function main() {
  const args = process.argv.slice(2);
  const option = (name, otherwise) => {
    const i = args.indexOf(name);
    return i >= 0 ? args.splice(i, 2)[1] : otherwise;
  };
  const precision = option("--precision", "double");
  const options = option("--options", "");
  const everyPass = args.includes("--passes");
  if (everyPass) args.splice(args.indexOf("--passes"), 1);
  const [out, ...scenes] = args;
  fs.mkdirSync(out, { recursive: true });
  const M = await createRaytracerModule();
  let n = 0;
  for (const scene of scenes) {
    // The scene and its PLY files, under a folder of their own, as the page writes them.
    const root = "/s" + ++n;
    const name = path.basename(scene);
    const files = { [name]: fs.readFileSync(scene) };
    let tree = null;
    try {
      tree = JSON.parse(files[name].toString("utf8"));
    } catch (e) {
      // not JSON: the module says where
    }
    for (const p of plyPaths(tree)) {
      const from = path.join(path.dirname(scene), p);
      if (fs.existsSync(from)) files[p] = fs.readFileSync(from);
    }
    writeFiles(M.FS, root, files);
    M.FS.chdir(root);
    const ptrs = [name, options, precision].map((s) => cString(M, s));
    const error = M.UTF8ToString(M._rtw_load(...ptrs));
    ptrs.forEach((p) => M._free(p));
    if (error) {
      process.stderr.write("error: " + error + "\n");
      process.exit(1);
    }
    const info = JSON.parse(M.UTF8ToString(M._rtw_scene()));
    info.cameras.forEach((cam, c) => {
      const bytes = cam.width * cam.height * 4;
      const buf = M._malloc(bytes);
      const base = path.join(out, cam.name.replace(/\.[^.]*$/, ""));
      const t0 = process.hrtime.bigint();
      const seconds = () => (Number(process.hrtime.bigint() - t0) / 1e9).toFixed(4);
      const fail = (e) => {
        process.stderr.write("error: " + e + "\n");
        process.exit(1);
      };
      if (cam.samples > 1) {
        let k0 = 0;
        for (const k1 of passes(cam.samples)) {
          const e = M.UTF8ToString(M._rtw_refine_part(c, 0, 1, k0, k1, buf));
          if (e) fail(e);
          k0 = k1;
          if (everyPass) {
            const file = base + "." + k1 + ".ppm";
            writePpm(file, cam, M.HEAPU8.subarray(buf, buf + bytes));
            process.stdout.write(file + "\t" + seconds() + "\t" + k1 + "\n");
          }
        }
      } else {
        const e = M.UTF8ToString(M._rtw_render_part(c, 0, 1, buf));
        if (e) fail(e);
      }
      const time = seconds();
      writePpm(base + ".ppm", cam, M.HEAPU8.subarray(buf, buf + bytes));
      M._free(buf);
      process.stdout.write(base + ".ppm\t" + time + "\n");
    });
    M.FS.chdir("/");
  }
}

main().catch((e) => {
  process.stderr.write("error: " + (e && e.message ? e.message : e) + "\n");
  process.exit(1);
});
