// The renderer's JavaScript API (docs/web.md), used by the page and by tests:
//   await raytracer.render({files: {name: Uint8Array, ...}, scene: "name.json", options: {...}})
//     -> {images: [{name, width, height, samples, rgba: Uint8Array}], seconds, warnings}
//   await raytracer.trace({files, scene, options, camera, x, y, sample}) -> the --trace-json object
//   await raytracer.compare(a, b, width, height, tolerance) -> {figures, heat}
// options: cull (true), precision ("double" | "float"), max_depth (-1: the scene's),
// epsilon_scale (1), min_weight (1e-4), rounding ("truncate" | "nearest"), samples (0:
// each camera's NumSamples), seed (0; beyond 2^53 a string of digits), workers (how many
// Web Workers render, default one per core), onProgress(done, total).
// Each worker holds its own WebAssembly module and copy of the scene; an image's 16x16
// tiles are dealt to them in turn, and every pixel is the same whichever renders it.
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
        if (m.type === "progress") {
          if (p.progress) p.progress();
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
    ask(msg, progress, transfer) {
      const id = ++this.next;
      return new Promise((resolve, reject) => {
        this.pending.set(id, { resolve, reject, progress });
        this.w.postMessage({ id, ...msg }, transfer || []);
      });
    }
    terminate() {
      this.w.terminate();
    }
  }

  // What a request rejects with: the command line's one line, with one "error: " prefix
  // whether or not the message had it already.
  const failure = (message) => new Error(/^error: /.test(message) ? message : "error: " + message);

  const kRenderKeys = ["cull", "max_depth", "epsilon_scale", "min_weight", "rounding", "samples", "seed"];

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
          const cam = info.cameras[c];
          const total = n * 8;  // parts: progress moves in steps of 1/total
          let done = 0;
          const t1 = performance.now();
          const replies = await Promise.all(this.workers.map((w, k) => {
            const parts = [];
            for (let p = k; p < total; p += n) parts.push(p);
            return w.ask({ type: "render", camera: c, parts, total }, () => {
              ++done;
              if (options.onProgress) options.onProgress(c, done, total);
            });
          }));
          const bad = replies.find((r) => r.error);
          if (bad) throw failure(bad.error);
          const rgba = replies[0].rgba;
          for (const r of replies.slice(1))
            for (let i = 3; i < rgba.length; i += 4)
              if (r.rgba[i]) {
                rgba[i - 3] = r.rgba[i - 3];
                rgba[i - 2] = r.rgba[i - 2];
                rgba[i - 1] = r.rgba[i - 1];
                rgba[i] = 255;
              }
          const s = (performance.now() - t1) / 1000;
          seconds += s;
          images.push({ name: cam.name, width: cam.width, height: cam.height, samples: cam.samples, rgba, seconds: s });
        }
        return { images, seconds, loadSeconds, warnings: info.warnings, workers: n };
      });
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
})(typeof window !== "undefined" ? window : self);
