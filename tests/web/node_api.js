// raytracer.js under Node, without the WebAssembly module (no `make web` needed), its
// workers stand-ins. Errors: their answers carry one, as the module's session gives it
// ("bad.json: parse error ..."), and every request must reject with the command line's one
// line, "error: " once. Passes: they render an image with samples as the module would,
// pass after pass (each pixel of a part holding the samples added so far), and the images
// shown must be every pass's, merged from every worker's parts, in order. Run by the test
// suite (WebSession.ApiErrorsHaveOnePrefix) and standalone: node tests/web/node_api.js.
// Exit status 0 when every check passed.
"use strict";
const fs = require("fs");
const path = require("path");
const vm = require("vm");

const kParseError = "bad.json: parse error at line 5, column 3: syntax error while parsing object";

// With StandIn.error set, a worker that answers every request at once with it (or a trace
// carrying it); without, one that loads a 5x3 image of 40 samples and refines it: pixel i
// is part i % total's, its red the samples it holds, its green its part.
class StandIn {
  postMessage(m) {
    const send = (data) => setImmediate(() => this.onmessage({ data: { id: m.id, ...data } }));
    if (StandIn.error) {
      send({ type: "done", ...(m.type === "trace" ? { trace: { error: StandIn.error } } : { error: StandIn.error }) });
    } else if (m.type === "load") {
      send({ type: "done", error: "", info: { cameras: [{ name: "a.png", ...kImage }], warnings: [] } });
    } else if (m.type === "refine") {
      const rgba = new Uint8Array(kImage.width * kImage.height * 4);
      for (let i = 0; i + 1 < m.bounds.length; ++i) {
        for (const part of m.parts) {
          for (let p = part; p < kImage.width * kImage.height; p += m.total) rgba.set([m.bounds[i + 1], part, 0, 255], 4 * p);
          send({ type: "progress", samples: m.bounds[i + 1] - m.bounds[i] });
        }
        send({ type: "pass", pass: i, rgba: rgba.slice() });
      }
      send({ type: "done" });
    } else {
      send({ type: "done", error: "stand-in: no " + m.type });
    }
  }
  terminate() {}
}
const kImage = { width: 5, height: 3, samples: 40 };

const context = { Worker: StandIn, performance, setImmediate, console };
context.self = context;
vm.createContext(context);
vm.runInContext(fs.readFileSync(path.join(__dirname, "..", "..", "src", "web", "raytracer.js"), "utf8"), context);
const rt = context.raytracer;

let failed = 0;
async function expectRejects(what, promise, message) {
  try {
    await promise;
    console.log("FAIL " + what + ": no error");
    failed = 1;
  } catch (e) {
    const ok = e.message === message;
    console.log((ok ? "ok   " : "FAIL ") + what + ": " + JSON.stringify(e.message));
    if (!ok) failed = 1;
  }
}

function expect(what, got, want) {
  const ok = got === want;
  console.log((ok ? "ok   " : "FAIL ") + what + (ok ? "" : ": " + got + ", not " + want));
  if (!ok) failed = 1;
}

(async () => {
  const files = { "bad.json": new Uint8Array([123]) };
  for (const given of [kParseError, "error: " + kParseError]) {
    StandIn.error = given;
    const req = { files, scene: "bad.json", options: { workers: 2 } };
    await expectRejects("render (" + given.slice(0, 12) + "...)", rt.render(req), "error: " + kParseError);
    await expectRejects("trace (" + given.slice(0, 12) + "...)", rt.trace({ ...req, x: 0, y: 0 }), "error: " + kParseError);
    await expectRejects("compare", rt.compare(new Uint8Array(4), new Uint8Array(4), 1, 1), "error: " + kParseError);
  }
  StandIn.error = "";
  expect("passes of 4, 16, 17, 100 and no samples", JSON.stringify([4, 16, 17, 100, 0].map((n) => [...rt.passes(n)])),
         "[[1,4],[1,16],[1,16,17],[1,16,32,64,100],[1]]");
  const shown = [];
  let progress = null;
  const r = await rt.render({ files: { "ok.json": files["bad.json"] }, scene: "ok.json", options: {
    workers: 3,
    onPass: (img) => shown.push([img.samplesDone, img.pass, img.secondsLeft > 0, [...img.rgba]]),
    onProgress: (c, done, total) => { progress = [done, total]; },
  } });
  expect("an image's passes are shown in order", JSON.stringify(shown.map((p) => p.slice(0, 3))),
         "[[1,1,true],[16,2,true],[32,3,true],[40,4,false]]");
  const whole = (k) => JSON.stringify(Array.from({ length: 15 }, (_, p) => [k, p % 24, 0, 255]).flat());
  expect("each pass merges every worker's parts", JSON.stringify(shown.map((p) => JSON.stringify(p[3]))),
         JSON.stringify([1, 16, 32, 40].map(whole)));
  expect("the image is the last pass's", JSON.stringify([...r.images[0].rgba]) + " " + r.images[0].passes, whole(40) + " 1,16,32,40");
  expect("progress ends at the whole", JSON.stringify(progress), "[960,960]");
  await expectRejects("a scene not among the files", rt.render({ files, scene: "other.json" }),
                      "error: other.json: not among the files given");
  await expectRejects("a sample not a whole number", rt.trace({ files, scene: "bad.json", x: 0, y: 0, sample: 1.5 }),
                      "error: sample 1.5: not a whole number");
  process.exit(failed);
})();
