// The Khronos glTF Validator (npm gltf-validator, installed into build/npm by
// tests/gltf/check_gltf.py) on each file named: one JSON line per file, its counts of errors,
// warnings, infos and hints and its messages (code, severity, pointer, message).
// NODE_PATH names the node_modules folder. Exit status 0 when every file was read.
"use strict";
const fs = require("fs");
const path = require("path");
const validator = require("gltf-validator");

async function validate(file) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
        uri: path.basename(file),
        maxIssues: 100,
        externalResourceFunction: (uri) =>
            new Promise((resolve, reject) => {
                fs.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)), (err, data) =>
                    err ? reject(err.toString()) : resolve(new Uint8Array(data)));
            }),
    });
    const i = report.issues;
    return {
        file,
        errors: i.numErrors,
        warnings: i.numWarnings,
        infos: i.numInfos,
        hints: i.numHints,
        messages: i.messages.map((m) => ({code: m.code, severity: m.severity, pointer: m.pointer, message: m.message})),
    };
}

(async () => {
    let ok = true;
    for (const file of process.argv.slice(2)) {
        try {
            console.log(JSON.stringify(await validate(file)));
        } catch (e) {
            console.log(JSON.stringify({file, failed: String(e)}));
            ok = false;
        }
    }
    process.exit(ok ? 0 : 1);
})();
