// raytracer.js's errors under Node, without the WebAssembly module (no `make web` needed):
// its workers are stand-ins whose answers carry an error, as the module's session gives
// it ("bad.json: parse error ..."), and every request must reject with the command line's
// one line, "error: " once. Run by the test suite (Web.ApiErrorsHaveOnePrefix) and
// standalone: node tests/web/node_api.js. Exit status 0 when every check passed.
"use strict";
const fs = require("fs");
const path = require("path");
const vm = require("vm");

const kParseError = "bad.json: parse error at line 5, column 3: syntax error while parsing object";

// A worker that answers every request at once with `error` (or a trace carrying it).
class StandIn {
  postMessage(m) {
    const reply = m.type === "trace" ? { trace: { error: StandIn.error } } : { error: StandIn.error };
    setImmediate(() => this.onmessage({ data: { id: m.id, type: "done", ...reply } }));
  }
  terminate() {}
}

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

(async () => {
  const files = { "bad.json": new Uint8Array([123]) };
  for (const given of [kParseError, "error: " + kParseError]) {
    StandIn.error = given;
    const req = { files, scene: "bad.json", options: { workers: 2 } };
    await expectRejects("render (" + given.slice(0, 12) + "...)", rt.render(req), "error: " + kParseError);
    await expectRejects("trace (" + given.slice(0, 12) + "...)", rt.trace({ ...req, x: 0, y: 0 }), "error: " + kParseError);
    await expectRejects("compare", rt.compare(new Uint8Array(4), new Uint8Array(4), 1, 1), "error: " + kParseError);
  }
  await expectRejects("a scene not among the files", rt.render({ files, scene: "other.json" }),
                      "error: other.json: not among the files given");
  await expectRejects("a sample not a whole number", rt.trace({ files, scene: "bad.json", x: 0, y: 0, sample: 1.5 }),
                      "error: sample 1.5: not a whole number");
  process.exit(failed);
})();
