#!/usr/bin/env python3
"""The page's bundled scenes (make web): copies every scene file under SRC (JSON) and the
PLY files it names into DST, keeping their relative paths, and writes DST/index.json:
[{"name": "showcase", "scene": "showcase.json", "files": ["showcase.json", ...]}, ...],
the list the page offers and the files each scene needs."""
import json
import os
import shutil
import sys


def ply_files(scene):
    """The _plyFile values of a scene tree, wherever they are."""
    out = []
    if isinstance(scene, dict):
        for k, v in scene.items():
            if k == "_plyFile" and isinstance(v, str):
                out.append(v)
            else:
                out += ply_files(v)
    elif isinstance(scene, list):
        for v in scene:
            out += ply_files(v)
    return out


def main(src, dst):
    index = []
    for folder, _, names in sorted(os.walk(src)):
        for name in sorted(names):
            if not name.endswith(".json"):
                continue
            path = os.path.join(folder, name)
            try:
                with open(path, encoding="utf-8") as f:
                    tree = json.load(f)
            except (OSError, ValueError):
                continue
            if not isinstance(tree, dict) or "Scene" not in tree:
                continue
            rel = os.path.relpath(path, src)
            files = [rel] + [os.path.normpath(os.path.join(os.path.dirname(rel), p)) for p in ply_files(tree)]
            for f in files:
                os.makedirs(os.path.dirname(os.path.join(dst, f)) or dst, exist_ok=True)
                shutil.copyfile(os.path.join(src, f), os.path.join(dst, f))
            index.append({"name": os.path.splitext(rel)[0], "scene": rel, "files": files})
    with open(os.path.join(dst, "index.json"), "w", encoding="utf-8") as f:
        json.dump(index, f, indent=1)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
