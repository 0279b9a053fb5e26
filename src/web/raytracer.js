// The renderer's JavaScript API (docs/web.md), used by the page and by tests:
//   await raytracer.render({files: {name: Uint8Array, ...}, scene: "name.json", options: {...}})
//     -> {images: [{name, width, height, samples, passes, rgba: Uint8Array, seconds}], seconds, warnings}
//   await raytracer.trace({files, scene, options, camera, x, y, sample}) -> the --trace-json object
//   await raytracer.compare(a, b, width, height, tolerance) -> {figures, heat}
//   raytracer.passes(samples) -> the samples per pixel after each pass of a progressive image
// options: cull (true), precision ("double" | "float"), max_depth (-1: the scene's),
// epsilon_scale (1), min_weight (1e-4), rounding ("truncate" | "nearest"), samples (0:
// each camera's NumSamples), seed (0; beyond 2^53 a string of digits), sampler ("random" |
// "stratified" | "sobol"), workers (how many Web Workers render, default one per core),
// onProgress(camera, done, total) (done / total: the share of the image's work done),
// onPass(image) (each image after each of its passes: {camera, name, width, height,
// samples, samplesDone, pass, passes, rgba, seconds, secondsLeft}).
// Each worker holds its own WebAssembly module and copy of the scene; an image's 16x16
// tiles are dealt to them in turn, and every pixel is the same whichever renders it. An
// image with samples renders progressively: pass after pass, each worker adds samples to
// its own tiles' pixels (rtw_refine_part), and the mean image is shown after every pass;
// the last is the image of all the samples, the native one.
// Errors reject with an Error whose message is the command line's one line ("error: ...").
"use strict";

(function (global) {
  const base = (global.document && global.document.currentScript && global.document.currentScript.src) || "";
  const here = base ? base.slice(0, base.lastIndexOf("/") + 1) : "";

  class Worker1 {
    constructor(url) {
      this.w = new Worker(url);
      this.next = 0;
      this.pending = new Map();
      this.w.onmessage = (e) => {
        const m = e.data;
        const p = this.pending.get(m.id);
        if (!p) return;
        if (m.type === "progress" || m.type === "pass") {
          if (p.on[m.type]) p.on[m.type](m);
          return;
        }
        this.pending.delete(m.id);
        p.resolve(m);
      };
      this.w.onerror = (e) => {
        for (const p of this.pending.values()) p.reject(new Error("error: worker: " + (e.message || "failed")));
        this.pending.clear();
      };
    }
    // on: {progress(m), pass(m)}, called for the request's messages before its answer.
    ask(msg, on) {
      const id = ++this.next;
      return new Promise((resolve, reject) => {
        this.pending.set(id, { resolve, reject, on: on || {} });
        this.w.postMessage({ id, ...msg });
      });
    }
    terminate() {
      this.w.terminate();
    }
  }

  // What a request rejects with: the command line's one line, with one "error: " prefix
  // whether or not the message had it already.
  const failure = (message) => new Error(/^error: /.test(message) ? message : "error: " + message);

  const kRenderKeys = ["cull", "max_depth", "epsilon_scale", "min_weight", "rounding", "samples", "seed", "sampler"];

  // The samples per pixel after each pass of an image of `samples`: one (a first image at
  // once), then 16, 32, 64, ... (doubling: each pass halves the variance), then all of
  // them. Past the first, passes end at multiples of 16, whole packets of samples.
  function passes(samples) {
    const out = [1];
    for (let k = 16; k < samples; k *= 2) out.push(k);
    if (samples > 1) out.push(samples);
    return out;
  }

  // The parts' images (alpha 255 where a part rendered a pixel) merged into the first.
  function merge(images) {
    const rgba = images[0];
    for (const r of images.slice(1))
      for (let i = 3; i < rgba.length; i += 4)
        if (r[i]) {
          rgba[i - 3] = r[i - 3];
          rgba[i - 2] = r[i - 2];
          rgba[i - 1] = r[i - 1];
          rgba[i] = 255;
        }
    return rgba;
  }

  class Raytracer {
    constructor() {
      this.workers = [];
      this.loaded = null;  // what every worker holds: {files, scene, key}
      this.queue = Promise.resolve();  // one request at a time
    }

    defaultWorkers() {
      return Math.max(1, Math.min((global.navigator && global.navigator.hardwareConcurrency) || 1, 8));
    }

    pool(n) {
      while (this.workers.length < n) {
        this.workers.push(new Worker1(here + "worker.js"));
        this.loaded = null;  // the new one has no scene yet
      }
      while (this.workers.length > n) this.workers.pop().terminate();
      return this.workers;
    }

    // Runs `job` after the requests before it: the workers hold one scene at a time.
    serial(job) {
      const run = this.queue.then(job, job);
      this.queue = run.catch(() => {});
      return run;
    }

    async load(req, n) {
      const options = req.options || {};
      const renderOptions = {};
      for (const k of kRenderKeys) if (options[k] !== undefined) renderOptions[k] = options[k];
      const precision = options.precision || "double";
      const key = JSON.stringify([req.scene, renderOptions, precision]);
      const workers = this.pool(n);
      if (this.loaded && this.loaded.files === req.files && this.loaded.key === key) return this.loaded.info;
      this.loaded = null;
      if (!req.files || !req.scene || !(req.scene in req.files))
        throw failure((req.scene || "no scene") + ": not among the files given");
      const replies = await Promise.all(
        workers.map((w) => w.ask({ type: "load", files: req.files, scene: req.scene, options: renderOptions, precision })));
      const bad = replies.find((r) => r.error);
      if (bad) throw failure(bad.error);
      this.loaded = { files: req.files, key, info: replies[0].info };
      return replies[0].info;
    }

    render(req) {
      return this.serial(async () => {
        const options = req.options || {};
        const n = Math.max(1, Math.min(options.workers || this.defaultWorkers(), 64));
        const t0 = performance.now();
        const info = await this.load(req, n);
        const loadSeconds = (performance.now() - t0) / 1000;
        const images = [];
        let seconds = 0;
        for (let c = 0; c < info.cameras.length; ++c) {
          const image = await (info.cameras[c].samples > 1 ? this.refine(c, info.cameras[c], n, options)
                                                            : this.renderOnce(c, info.cameras[c], n, options));
          seconds += image.seconds;
          images.push(image);
        }
        return { images, seconds, loadSeconds, warnings: info.warnings, workers: n };
      });
    }

    // An image's parts (n * 8 of them) dealt to the n workers in turn, a request to each
    // (ask(worker, its parts, total)); their answers, checked.
    async spread(n, ask) {
      const total = n * 8;  // parts: progress moves in steps of 1/total
      const replies = await Promise.all(this.workers.map((w, k) => {
        const parts = [];
        for (let p = k; p < total; p += n) parts.push(p);
        return ask(w, parts, total);
      }));
      const bad = replies.find((r) => r.error);
      if (bad) throw failure(bad.error);
      return replies;
    }

    // An image in one pass (a camera without samples: one ray a pixel).
    async renderOnce(c, cam, n, options) {
      let done = 0;
      const t1 = performance.now();
      const replies = await this.spread(n, (w, parts, total) => w.ask({ type: "render", camera: c, parts, total }, {
        progress: () => { if (options.onProgress) options.onProgress(c, ++done, total); },
      }));
      const rgba = merge(replies.map((r) => r.rgba));
      const seconds = (performance.now() - t1) / 1000;
      const image = { name: cam.name, width: cam.width, height: cam.height, samples: cam.samples, passes: [1], rgba, seconds };
      if (options.onPass) options.onPass({ camera: c, ...image, samplesDone: 1, pass: 1, secondsLeft: 0 });
      return image;
    }

    // An image with samples, pass after pass: each worker adds each pass's samples to its
    // parts' pixels; a pass is shown once every worker has sent its parts of it.
    async refine(c, cam, n, options) {
      const after = passes(cam.samples), bounds = [0, ...after];
      const got = after.map(() => []);
      let done = 0, last = null;
      const t1 = performance.now();
      const elapsed = () => (performance.now() - t1) / 1000;
      const image = { name: cam.name, width: cam.width, height: cam.height, samples: cam.samples, passes: after };
      await this.spread(n, (w, parts, total) => w.ask({ type: "refine", camera: c, parts, total, bounds }, {
        progress: (m) => { done += m.samples; if (options.onProgress) options.onProgress(c, done, total * cam.samples); },
        pass: (m) => {
          // A worker's passes come in order, so pass i completes after pass i - 1.
          got[m.pass].push(m.rgba);
          if (got[m.pass].length < n) return;
          last = merge(got[m.pass]);
          got[m.pass] = null;
          const k = after[m.pass], s = elapsed();
          if (options.onPass)
            options.onPass({ camera: c, ...image, rgba: last, seconds: s, samplesDone: k, pass: m.pass + 1,
                             secondsLeft: s * (cam.samples - k) / k });
        },
      }));
      return { ...image, rgba: last, seconds: elapsed() };
    }

    trace(req) {
      return this.serial(async () => {
        // The module takes a 32-bit integer, which would truncate anything else silently.
        const sample = req.sample === undefined ? 0 : req.sample;
        if (!Number.isInteger(sample) || Math.abs(sample) > 0x7fffffff)
          throw failure("sample " + JSON.stringify(sample) + ": not a whole number");
        const n = this.loaded ? this.workers.length : 1;
        await this.load(req, Math.max(1, n));
        const r = await this.workers[0].ask({ type: "trace", camera: req.camera || 0, x: req.x, y: req.y, sample });
        if (r.error) throw failure(r.error);
        if (r.trace.error) throw failure(r.trace.error);
        return r.trace;
      });
    }

    compare(a, b, width, height, tolerance = 1) {
      return this.serial(async () => {
        const workers = this.workers.length ? this.workers : this.pool(1);
        const r = await workers[0].ask({ type: "compare", a, b, width, height, tolerance });
        if (r.error) throw failure(r.error);
        return { figures: r.figures, heat: r.heat };
      });
    }
  }

  global.raytracer = new Raytracer();
  global.raytracer.passes = passes;
})(typeof window !== "undefined" ? window : self);
