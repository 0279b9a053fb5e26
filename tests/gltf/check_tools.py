#!/usr/bin/python3
"""Part of make check-gltf (docs/gltf.md, "Checks"): our exports against the glTF world's two
tools, installed by this script into build/npm at the versions tests/gltf/package-lock.json
pins (npm ci; Node.js and npm from Debian).

  validator   every complete official scene (hw1, hw2, hw3, xml2021) exported as .gltf and as
              .glb, each file through the Khronos glTF Validator (tests/gltf/validate.js):
              0 errors and 0 warnings each (infos, such as an unused material, may stay).
  pipelines   glTF Transform's quantize, meshopt, draco and optimize (also without its
              simplify, and without its simplify and join) on the .glb of a few
              scenes (PIPELINE_SCENES; --all: every one), each result validated, imported by
              ./rtconvert and rendered: each image within 0.5% of pixels (some channel off by
              more than 1) of the original scene's. Assignment 3's scenes at 4 samples a pixel.

The tables go to build/gltf/check-gltf-tools.md. Exit status 0 when every check passed."""
import json
import os
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_gltf import LIMIT, RTCONVERT, difference, render, run  # noqa: E402
from shared_scenes import HW3_CHECK_SAMPLES, REPO, check, complete_scenes, failures, shared_dir  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
NPM = os.path.join(REPO, "build", "npm")
OUT = os.path.join(REPO, "build", "gltf", "tools")
# Each variant: glTF Transform's command and its options. optimize's simplify step removes
# vertices, and its join makes one mesh of small and large ones, which its quantisation then
# quantises in the large one's extent (docs/gltf.md): optimize is run without them too.
VARIANTS = {"quantize": ["quantize"], "meshopt": ["meshopt"], "draco": ["draco"], "optimize": ["optimize"],
            "optimize-nosimplify": ["optimize", "--simplify", "false"],
            "optimize-nosimplify-nojoin": ["optimize", "--simplify", "false", "--join", "false"]}
# The scenes make check-gltf puts through the pipelines: flat and instanced meshes, glass and
# spheres, transformations, metals, an XML scene; cornellbox's 5 materials, which optimize's
# palette step merges, and mirror_room's planes, which its join merges (docs/gltf.md).
PIPELINE_SCENES = ["hw1/bunny.json", "hw1/scienceTree_glass.json", "hw2/simple_transform.json",
                   "hw2/metal_glass_plates.json", "xml2021/two_spheres.xml", "hw1/cornellbox.json",
                   "hw2/mirror_room.json"]


def install_tools():
    """npm ci into build/npm from the pinned lock file, unless that is already there."""
    lock = os.path.join(HERE, "package-lock.json")
    installed = os.path.join(NPM, "package-lock.json")
    if os.path.exists(installed) and open(installed, "rb").read() == open(lock, "rb").read() and \
            os.path.isdir(os.path.join(NPM, "node_modules", "gltf-validator")):
        return
    os.makedirs(NPM, exist_ok=True)
    for f in ("package.json", "package-lock.json"):
        shutil.copy(os.path.join(HERE, f), os.path.join(NPM, f))
    run(["npm", "ci", "--prefix", NPM, "--no-audit", "--no-fund", "--loglevel=error"])


def validate(files):
    """{file: validator report line} for every file, in one run of the validator."""
    r = subprocess.run(["node", os.path.join(HERE, "validate.js")] + files, capture_output=True, text=True,
                       env=dict(os.environ, NODE_PATH=os.path.join(NPM, "node_modules")))
    out = {}
    for line in r.stdout.splitlines():
        report = json.loads(line)
        out[report["file"]] = report
    for f in files:
        check(f in out and "failed" not in out[f], "the validator read " + os.path.basename(f))
    return out


def counts(report):
    return "%d / %d / %d" % (report.get("errors", -1), report.get("warnings", -1), report.get("infos", -1))


def first_messages(report):
    return "; ".join("%s %s" % (m["code"], m["pointer"]) for m in report.get("messages", [])
                     if m["severity"] <= 1)[:300]


def scenes(shared):
    """(assignment, path relative to its scene folder) of every complete official scene; all
    of xml2021's are (they read no PLY file)."""
    out = complete_scenes(shared, ("hw1", "hw2", "hw3"))
    xml = os.path.join(shared, "scenes", "xml2021")
    out += [("xml2021", f) for f in sorted(os.listdir(xml)) if f.endswith(".xml")]
    return out


def name_of(hw, rel):
    return hw + "_" + os.path.splitext(rel)[0].replace("/", "_")


def exports(shared, all_scenes):
    """Every scene as .gltf and .glb, validated; the table's rows."""
    d = os.path.join(OUT, "exports")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    files = []
    for hw, rel in all_scenes:
        for ext in (".gltf", ".glb"):
            f = os.path.join(d, name_of(hw, rel) + ext)
            run([RTCONVERT, "-q", os.path.join(shared, "scenes", hw, rel), f])
            files.append(f)
    reports = validate(files)
    rows = []
    for hw, rel in all_scenes:
        row = [hw + "/" + rel]
        for ext in (".gltf", ".glb"):
            rep = reports.get(os.path.join(d, name_of(hw, rel) + ext), {})
            ok = rep.get("errors") == 0 and rep.get("warnings") == 0
            check(ok, "%s%s validates: %s errors / warnings / infos %s" % (name_of(hw, rel), ext, counts(rep),
                                                                          first_messages(rep)))
            row.append(counts(rep))
        rows.append(row)
    return rows


def pipelines(shared, chosen):
    """Each variant of each chosen scene imported and rendered against the original; rows."""
    cli = os.path.join(NPM, "node_modules", "@gltf-transform", "cli", "bin", "cli.js")
    rows = []
    for hw, rel in chosen:
        scene = os.path.join(shared, "scenes", hw, rel)
        d = os.path.join(OUT, "pipelines", name_of(hw, rel))
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        samples = ["--samples", HW3_CHECK_SAMPLES] if hw == "hw3" else []
        original = render(scene, os.path.join(d, "original"), samples)
        run([RTCONVERT, "-q", scene, os.path.join(d, "scene.glb")])
        made = {}
        for v in VARIANTS:
            made[v] = os.path.join(d, v + ".glb")
            run(["node", cli, VARIANTS[v][0], os.path.join(d, "scene.glb"), made[v]] + VARIANTS[v][1:])
        reports = validate(list(made.values()))
        for v in VARIANTS:
            rep = reports.get(made[v], {})
            check(rep.get("errors") == 0, "%s %s: glTF Transform's file validates (%s)" % (name_of(hw, rel), v,
                                                                                         counts(rep)))
            r = subprocess.run([RTCONVERT, "-q", "--camera", "all", made[v], os.path.join(d, v + ".json")],
                               capture_output=True, text=True)
            if not check(r.returncode == 0, "%s %s imports: %s" % (name_of(hw, rel), v, r.stderr.strip()[:300])):
                rows.append((hw + "/" + rel, v, "refused: " + r.stderr.strip()[:120], "", ""))
                continue
            back = render(os.path.join(d, v + ".json"), os.path.join(d, v), samples)
            for image, path in original.items():
                pct, mx = difference(path, back.get(image, "missing"))
                check(pct <= LIMIT, "%s %s %s: %.4f%% of pixels off, max %d (limit %.1f%%)" %
                      (name_of(hw, rel), v, image, pct, mx, LIMIT))
                rows.append((hw + "/" + rel, v, "imported", image, "%.4f%% (max %d)" % (pct, mx)))
    return rows


def write_report(sections):
    os.makedirs(os.path.dirname(OUT), exist_ok=True)
    path = os.path.join(os.path.dirname(OUT), "check-gltf-tools.md")
    with open(path, "w", encoding="utf-8") as f:
        for title, header, rows in sections:
            f.write("## " + title + "\n\n| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n")
            for r in rows:
                f.write("| " + " | ".join(r) + " |\n")
            f.write("\n")
    print("report: " + path)


def main():
    shared = shared_dir()
    if not check(bool(shared), "../shared found (RT_SHARED_DIR)"):
        return 1
    for tool in ["node", "npm", RTCONVERT]:
        if not check(shutil.which(tool) is not None, tool + " is there"):
            return 1
    start = time.time()
    try:
        install_tools()
        print("glTF tools installed in build/npm (%.0f s)" % (time.time() - start), flush=True)
        all_scenes = scenes(shared)
        export_rows = exports(shared, all_scenes)
        chosen = all_scenes if "--all" in sys.argv[1:] else \
            [(p.split("/", 1)[0], p.split("/", 1)[1]) for p in PIPELINE_SCENES]
        pipeline_rows = pipelines(shared, chosen)
        write_report([("Khronos glTF Validator on every export", ["scene", ".gltf: errors / warnings / infos",
                                                                 ".glb: errors / warnings / infos"], export_rows),
                      ("glTF Transform's pipelines", ["scene", "variant", "import", "image", "pixels off"],
                       pipeline_rows)])
    except RuntimeError as e:
        check(False, str(e))
    print("check-gltf tools: %d failure(s)" % len(failures) if failures else "check-gltf tools: every check passed",
          "(%.0f s)" % (time.time() - start))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
