// A scene's files, one way for the page (app.js), its workers (worker.js) and the Node test
// of the module (tests/web/node_render.js): in a browser `sceneFiles`, under Node the module.
"use strict";

(function (exports) {
  // The _plyFile paths a scene tree names, wherever they are.
  exports.plyPaths = function plyPaths(tree, out = []) {
    if (Array.isArray(tree)) tree.forEach((v) => plyPaths(v, out));
    else if (tree && typeof tree === "object")
      for (const [k, v] of Object.entries(tree)) {
        if (k === "_plyFile" && typeof v === "string") out.push(v);
        else plyPaths(v, out);
      }
    return out;
  };

  // Writes `files` ({path: Uint8Array}, paths relative to the scene's folder) under the
  // folder `root` of an Emscripten module's file system, making the folders they name.
  exports.writeFiles = function writeFiles(FS, root, files) {
    FS.mkdir(root);
    for (const [path, bytes] of Object.entries(files)) {
      const parts = path.split("/").filter((p) => p && p !== ".");
      let dir = root;
      for (const p of parts.slice(0, -1)) {
        dir += "/" + p;
        if (!FS.analyzePath(dir).exists) FS.mkdir(dir);
      }
      FS.writeFile(root + "/" + parts.join("/"), bytes);
    }
  };
})(typeof module !== "undefined" && module.exports ? module.exports : (self.sceneFiles = {}));
