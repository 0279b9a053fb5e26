#!/usr/bin/python3
"""make check-gltf and make check-blender (docs/gltf.md): glTF round trips of the course's
scenes, each image compared with ./raytracer's image of the scene itself.

  check-gltf     every complete scene of ../shared (hw1, hw2): JSON -> glTF (.gltf, or .glb
                 for every other scene) -> JSON through ./rtconvert; each image byte-identical
                 to the original's; with the spheres left tessellated (their extras dropped),
                 within 0.5% of pixels. Also reported, not checked: the round trip with all
                 the "ceng795" extras stripped, what a tool that drops them gives back.
  check-blender  (--blender) the same scenes through Debian's Blender as well: our glTF
                 imported by Blender's glTF importer and exported again by its exporter, then
                 converted back; each image within 0.5% of pixels (some channel off by more
                 than 1) of the original's. Then a scene built in Blender from Python
                 (tests/gltf/blender_scene.py), exported, converted and rendered, against the
                 same scene written directly in the course's format (blender_scene_json).

The table goes to build/gltf/<check>.md. Exit status 0 when every check passed, 1 otherwise;
without ../shared (RT_SHARED_DIR) or Blender it fails loudly, never skips."""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
from shared_scenes import REPO, RAYTRACER, RTDIFF, check, complete_scenes, failures, identical, shared_dir  # noqa: E402

RTCONVERT = os.path.join(REPO, "rtconvert")
HERE = os.path.dirname(os.path.abspath(__file__))
OUT = os.path.join(REPO, "build", "gltf")
BLENDER = shutil.which("blender") or "blender"
LIMIT = 0.5  # % of pixels the Blender round trips may differ by


def run(cmd, **kw):
    r = subprocess.run(cmd, capture_output=True, text=True, **kw)
    if r.returncode != 0:
        raise RuntimeError(" ".join(cmd) + ": exit " + str(r.returncode) + ": " + (r.stderr or r.stdout).strip()[-400:])
    return r


def render(scene, out, options=()):
    """./raytracer's images of `scene` in `out` (with `options`): {image file name: path}, PNG
    or PPM as the scene names them (xml2021's cornellbox, mirror_spheres and
    simple_reflectance write PPM); an error when there is none."""
    os.makedirs(out, exist_ok=True)
    run([RAYTRACER, "-q"] + list(options) + ["-o", out, scene])
    images = {n: os.path.join(out, n) for n in sorted(os.listdir(out)) if n.endswith((".png", ".ppm"))}
    if not images:
        raise RuntimeError("%s: ./raytracer wrote no image in %s" % (scene, out))
    return images


def difference(a, b):
    """(% of pixels with some channel off by more than 1, largest channel difference)."""
    r = subprocess.run([RTDIFF, a, b], capture_output=True, text=True)
    m = re.search(r"max (\d+),.*\(([\d.]+)%\) off by more than 1", r.stdout)
    if not m:
        return 100.0, 255
    return float(m.group(2)), int(m.group(1))


def strip_extras(src, dst, keys=None):
    """A copy of the .gltf `src` without the "ceng795" extras (or only without those of
    `keys` in them), as a tool that drops them writes it."""
    with open(src, encoding="utf-8") as f:
        g = json.load(f)
    found = [False]

    def strip(v):
        if isinstance(v, dict):
            ours = v.get("extras", {}).get("ceng795") if isinstance(v.get("extras"), dict) else None
            if isinstance(ours, dict):
                for k in list(ours) if keys is None else [k for k in keys if k in ours]:
                    del ours[k]
                    found[0] = True
                if not ours:
                    del v["extras"]["ceng795"]
                if not v["extras"]:
                    del v["extras"]
            for x in v.values():
                strip(x)
        elif isinstance(v, list):
            for x in v:
                strip(x)

    strip(g)
    with open(dst, "w", encoding="utf-8") as f:
        json.dump(g, f)
    shutil.copy(os.path.splitext(src)[0] + ".bin", os.path.splitext(dst)[0] + ".bin")
    return found[0]


def variant(d, name, full, keys, size):
    """The images of `full` come back without (some of) its extras; None when there were
    none of `keys` to strip."""
    if not strip_extras(os.path.join(d, full), os.path.join(d, name + ".gltf"), keys) and keys is not None:
        return None
    run([RTCONVERT, "-q", "--camera", "all"] + (["--size", "%dx%d" % size] if size else []) +
        [os.path.join(d, name + ".gltf"), os.path.join(d, name + ".json")])
    return render(os.path.join(d, name + ".json"), os.path.join(d, name))


def scene_name(hw, rel):
    return hw + "_" + os.path.splitext(rel)[0].replace("/", "_")


def round_trips(shared, blender):
    rows = []
    for i, (hw, rel) in enumerate(complete_scenes(shared)):
        scene = os.path.join(shared, "scenes", hw, rel)
        d = os.path.join(OUT, "blender" if blender else "rtconvert", scene_name(hw, rel))
        shutil.rmtree(d, ignore_errors=True)
        os.makedirs(d)
        original = render(scene, os.path.join(d, "original"))
        ext = ".glb" if i % 2 else ".gltf"
        if not blender:
            run([RTCONVERT, "-q", scene, os.path.join(d, "scene" + ext)])
            run([RTCONVERT, "-q", "--camera", "all", os.path.join(d, "scene" + ext), os.path.join(d, "back.json")])
            back = render(os.path.join(d, "back.json"), os.path.join(d, "back"))
            # Spheres left tessellated (their extras dropped): within 0.5% too. Reported only:
            # what a tool that drops every extra gives back (the first camera's image).
            run([RTCONVERT, "-q", scene, os.path.join(d, "full.gltf")])
            first, first_path = next(iter(original.items()))
            size = image_size(first_path)
            reported = []
            # (the plain one at the original's size: without extras it would be 600 high)
            for label, keys in (("tessellated", ["sphere"]), ("plain", None)):
                images = variant(d, label, "full.gltf", keys, size if keys is None else None)
                if images is None:
                    reported.append("-")
                else:  # without extras the image is named after the file: the first one
                    image = images.get(first) or next(iter(images.values()))
                    pct, mx = difference(first_path, image)
                    reported.append("%.4f%%" % pct)
                    if keys is not None:
                        check(pct <= LIMIT, "%s %s with its spheres tessellated: %.4f%% of pixels off, max %d "
                              "(limit %.1f%%)" % (scene_name(hw, rel), first, pct, mx, LIMIT))
            for name, path in original.items():
                same, line = identical(path, back.get(name, "missing"))
                check(same, "%s %s through %s: byte-identical (%s)" % (scene_name(hw, rel), name, ext, line[0]))
                rows.append((hw + "/" + rel, name, ext, "identical" if same else "differs",
                             *(reported if name == first else ("", ""))))
        else:
            run([RTCONVERT, "-q", scene, os.path.join(d, "scene.gltf")])
            run([BLENDER, "-b", "--factory-startup", "--python", os.path.join(HERE, "blender_round_trip.py"), "--",
                 os.path.join(d, "scene.gltf"), os.path.join(d, "blender.gltf")])
            run([RTCONVERT, "-q", "--camera", "all", os.path.join(d, "blender.gltf"), os.path.join(d, "back.json")])
            back = render(os.path.join(d, "back.json"), os.path.join(d, "back"))
            for name, path in original.items():
                pct, mx = difference(path, back.get(name, "missing"))
                check(pct <= LIMIT, "%s %s through Blender: %.4f%% of pixels off, max %d (limit %.1f%%)" %
                      (scene_name(hw, rel), name, pct, mx, LIMIT))
                rows.append((hw + "/" + rel, name, "%.4f%%" % pct, str(mx)))
    return rows


def image_size(png):
    with open(png, "rb") as f:
        head = f.read(24)
    return int.from_bytes(head[16:20], "big"), int.from_bytes(head[20:24], "big")


# ---- The scene built in Blender, written directly in the course's format ------------------

def blender_scene_json():
    """tests/gltf/blender_scene.py's scene as a course scene: Blender's Z-up coordinates
    (x, y, z) are glTF's (x, z, -y); materials by the table of docs/gltf.md, by hand."""
    def to_gltf(p):
        return (p[0], p[2], -p[1])

    def cube(center, angle_z=0.0, scale=1.0):
        c, s = math.cos(math.radians(angle_z)), math.sin(math.radians(angle_z))
        out = []
        for x, y, z in [(-1, -1, -1), (1, -1, -1), (1, 1, -1), (-1, 1, -1),
                        (-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)]:
            x, y, z = x * scale, y * scale, z * scale
            out.append(to_gltf((center[0] + c * x - s * y, center[1] + s * x + c * y, center[2] + z)))
        return out
    # Counter-clockwise seen from outside (Blender's z up), 1-based within the cube.
    cube_faces = [(1, 4, 3), (1, 3, 2), (5, 6, 7), (5, 7, 8), (1, 2, 6), (1, 6, 5),
                  (2, 3, 7), (2, 7, 6), (3, 4, 8), (3, 8, 7), (4, 1, 5), (4, 5, 8)]
    objects = [("ground", [to_gltf(p) for p in [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)]],
                [(1, 2, 3), (1, 3, 4)], 1),
               ("red", cube((-2.5, 0, 1)), cube_faces, 2),
               ("metal", cube((0, 0, 1), angle_z=30), cube_faces, 3),
               ("glass", cube((2.5, 0, 1), scale=0.8), cube_faces, 4)]
    vertices, meshes = [], []
    for i, (_, points, faces, material) in enumerate(objects):
        base = len(vertices)
        vertices += points
        meshes.append({"_id": str(i + 1), "Material": str(material),
                       "Faces": {"_data": " ".join("%d %d %d" % tuple(base + k for k in f) for f in faces)}})

    def vec(v):
        return " ".join(repr(float(x)) for x in v)
    a = math.radians(80)  # the camera's turn about Blender's x
    top = math.tan(math.radians(20))
    intensity = 1000 * 255 / (4 * math.pi ** 2)  # W / (4 pi) * 683 cd, times --light-scale 255 / (683 pi)
    materials = [
        # base colour b, metallic 0, roughness r: diffuse = ambient = b, specular 1 - r,
        # PhongExponent 2 / r^4 - 2 (at least 1)
        {"_id": "1", "AmbientReflectance": "0.8 0.8 0.8", "DiffuseReflectance": "0.8 0.8 0.8",
         "SpecularReflectance": "0 0 0", "PhongExponent": "1"},
        {"_id": "2", "AmbientReflectance": "0.8 0.1 0.1", "DiffuseReflectance": "0.8 0.1 0.1",
         "SpecularReflectance": "0.5 0.5 0.5", "PhongExponent": "30"},
        # metallic 1: a conductor n = 1, k = 10, MirrorReflectance b, specular b (1 - r)
        {"_id": "3", "_type": "conductor", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
         "SpecularReflectance": "0.45 0.35 0.15", "PhongExponent": "30", "MirrorReflectance": "0.9 0.7 0.3",
         "RefractionIndex": "1", "AbsorptionIndex": "10"},
        # transmission 1: a dielectric of the IOR; roughness 0: specular 1, exponent 1e6
        {"_id": "4", "_type": "dielectric", "AmbientReflectance": "0 0 0", "DiffuseReflectance": "0 0 0",
         "SpecularReflectance": "1 1 1", "PhongExponent": "1000000", "MirrorReflectance": "1 1 1",
         "RefractionIndex": "1.5"}]
    return {"Scene": {
        "BackgroundColor": "40 44 56", "MaxRecursionDepth": "6",
        "Cameras": {"Camera": {"_id": "1", "Position": vec(to_gltf((0, -10, 3))),
                               "Gaze": vec(to_gltf((0, math.sin(a), -math.cos(a)))),
                               "Up": vec(to_gltf((0, math.cos(a), math.sin(a)))),
                               "NearPlane": vec((-top * 4 / 3, top * 4 / 3, -top, top)), "NearDistance": "1",
                               "ImageResolution": "320 240", "ImageName": "direct.png"}},
        "Lights": {"AmbientLight": "0 0 0",
                   "PointLight": {"_id": "1", "Position": vec(to_gltf((0, -4, 6))), "Intensity": vec([intensity] * 3)}},
        "Materials": {"Material": materials},
        "VertexData": {"_data": " ".join(vec(v) for v in vertices)},
        "Objects": {"Mesh": meshes}}}


def built_in_blender():
    d = os.path.join(OUT, "blender_scene")
    shutil.rmtree(d, ignore_errors=True)
    os.makedirs(d)
    run([BLENDER, "-b", "--factory-startup", "--python", os.path.join(HERE, "blender_scene.py"), "--",
         os.path.join(d, "built.gltf")])
    r = run([RTCONVERT, "--size", "320x240", "--image", "built.png", os.path.join(d, "built.gltf"),
             os.path.join(d, "built.json")])
    print("    " + "\n    ".join(r.stderr.strip().splitlines()))
    with open(os.path.join(d, "direct.json"), "w", encoding="utf-8") as f:
        json.dump(blender_scene_json(), f, indent=1)
    built = render(os.path.join(d, "built.json"), os.path.join(d, "images"))["built.png"]
    direct = render(os.path.join(d, "direct.json"), os.path.join(d, "images"))["direct.png"]
    pct, mx = difference(direct, built)
    check(pct <= LIMIT, "blender_scene: built in Blender, exported, converted: %.4f%% of pixels off the scene "
          "written directly, max %d (limit %.1f%%)" % (pct, mx, LIMIT))
    return pct, mx


def write_report(name, header, rows, extra=""):
    os.makedirs(OUT, exist_ok=True)
    with open(os.path.join(OUT, name + ".md"), "w", encoding="utf-8") as f:
        f.write("| " + " | ".join(header) + " |\n|" + "---|" * len(header) + "\n")
        for r in rows:
            f.write("| " + " | ".join(r) + " |\n")
        f.write(extra)
    print("report: " + os.path.join(OUT, name + ".md"))


def main():
    blender = "--blender" in sys.argv[1:]
    shared = shared_dir()
    if not check(bool(shared), "../shared found (RT_SHARED_DIR)"):
        return 1
    for tool in [RAYTRACER, RTCONVERT, RTDIFF] + ([BLENDER] if blender else []):
        if not check(shutil.which(tool) is not None, tool + " is there"):
            return 1
    start = time.time()
    try:
        if blender:
            rows = round_trips(shared, True)
            pct, mx = built_in_blender()
            write_report("check-blender", ["scene", "image", "pixels off", "max"], rows,
                         "\nBuilt in Blender (tests/gltf/blender_scene.py) against the course scene written "
                         "directly: %.4f%% of pixels off, max %d.\n" % (pct, mx))
        else:
            rows = round_trips(shared, False)
            write_report("check-gltf", ["scene", "image", "through", "back", "spheres tessellated: pixels off",
                                        "no extras: pixels off"], rows)
    except RuntimeError as e:
        check(False, str(e))
    name = "check-blender" if blender else "check-gltf"
    print("%s: %d failure(s)" % (name, len(failures)) if failures else "%s: every check passed" % name,
          "(%.0f s)" % (time.time() - start))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
