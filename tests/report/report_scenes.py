"""report.py's scenes: the course's complete official scenes with their references, ours
(scenes/), the official ones moved far from the origin, and a generated 1M-triangle mesh."""
import json
import os
import subprocess

from report_common import REPO, log, loud


class Scene:
    def __init__(self, key, path, kind, refs=None, label=None):
        self.key = key            # unique, file-name safe
        self.path = path          # the scene file
        self.kind = kind          # official | ours | far | big
        self.refs = refs or {}    # image name -> reference PNG
        self.label = label or os.path.basename(path)
        self.reflective = has_reflective_material(path)


def has_reflective_material(path):
    try:
        with open(path, encoding="utf-8") as f:
            doc = json.load(f)
        mats = doc["Scene"]["Materials"]["Material"]
    except (OSError, ValueError, KeyError, TypeError):
        return False
    if isinstance(mats, dict):
        mats = [mats]
    return any(isinstance(m, dict) and m.get("_type") in ("mirror", "conductor", "dielectric") for m in mats)


def official_scenes(shared):
    manifest = os.path.join(shared, "scenes", "hw1", "MANIFEST.tsv")
    scenes, order = {}, []
    with open(manifest, encoding="utf-8") as f:
        for line in f:
            if not line.strip() or line.startswith("#"):
                continue
            cols = line.rstrip("\n").split("\t")
            if len(cols) < 4 or cols[3].strip() != "complete":
                continue
            rel, image, ref = cols[0], cols[1], cols[2]
            if rel not in scenes:
                key = rel[:-5].replace("/", "_") if rel.endswith(".json") else rel.replace("/", "_")
                scenes[rel] = Scene(key, os.path.join(shared, "scenes", "hw1", rel), "official", label=rel)
                order.append(rel)
            ref_path = os.path.join(shared, ref)
            if os.path.isfile(ref_path):
                scenes[rel].refs[image] = ref_path
    return [scenes[r] for r in order]


def our_scenes():
    out = []
    root = os.path.join(REPO, "scenes")
    for dirpath, dirnames, filenames in os.walk(root):
        dirnames[:] = sorted(d for d in dirnames if d not in ("tools", "renders"))
        for name in sorted(filenames):
            if name.endswith(".json"):
                path = os.path.join(dirpath, name)
                rel = os.path.relpath(path, REPO)
                out.append(Scene("ours_" + name[:-5], path, "ours", label=rel))
    return out


def offset_scene(src, dst, offset):
    """Writes `src` moved by (offset, offset, offset): vertices, camera, gaze point, lights."""
    with open(src, encoding="utf-8") as f:
        doc = json.load(f)
    s = doc["Scene"]

    def shift(text):
        v = [float(x) for x in str(text).split()]
        return " ".join(repr(x + offset) for x in v)

    vd = s.get("VertexData")
    if isinstance(vd, dict):
        nums = [float(x) for x in str(vd["_data"]).split()]
        vd["_data"] = " ".join(repr(x + offset) for x in nums)
    elif isinstance(vd, str):
        nums = [float(x) for x in vd.split()]
        s["VertexData"] = " ".join(repr(x + offset) for x in nums)
    cams = s["Cameras"]["Camera"]
    for c in cams if isinstance(cams, list) else [cams]:
        c["Position"] = shift(c["Position"])
        if "GazePoint" in c:
            c["GazePoint"] = shift(c["GazePoint"])
    lights = s.get("Lights", {}).get("PointLight", [])
    for l in lights if isinstance(lights, list) else [lights]:
        l["Position"] = shift(l["Position"])
    with open(dst, "w", encoding="utf-8") as f:
        json.dump(doc, f, indent=2)


def far_scenes(shared, work):
    out = []
    folder = os.path.join(work, "scenes", "far")
    os.makedirs(folder, exist_ok=True)
    for name in ("simple", "spheres"):
        src = os.path.join(shared, "scenes", "hw1", name + ".json")
        ref = os.path.join(shared, "references", "hw1", name + ".png")
        if not os.path.isfile(src):
            continue
        for exp in (2, 3, 4):
            dst = os.path.join(folder, f"{name}_1e{exp}.json")
            offset_scene(src, dst, 10.0 ** exp)
            refs = {name + ".png": ref} if os.path.isfile(ref) else {}
            out.append(Scene(f"far_{name}_1e{exp}", dst, "far", refs, label=f"{name}.json + 1e{exp}"))
    return out


def big_scene(gen_mesh, work):
    folder = os.path.join(work, "scenes")
    os.makedirs(folder, exist_ok=True)
    scene = os.path.join(folder, "knot_1m_plain.json")
    if not os.path.isfile(scene) or os.path.getmtime(scene) < os.path.getmtime(gen_mesh):
        log("generating a 1M-triangle mesh (tests/bench/gen_mesh) ...")
        r = subprocess.run([gen_mesh, "--out-dir", folder, "--name", "knot_1m", "1M"], capture_output=True, text=True)
        if r.returncode != 0:
            loud("gen_mesh failed: " + r.stderr.strip())
            return None
    return Scene("knot_1m_plain", scene, "big", label="knot_1m_plain.json (generated, 1M triangles)")
