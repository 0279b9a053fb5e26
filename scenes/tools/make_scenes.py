#!/usr/bin/env python3
"""Writes scenes/glass_checker.json and scenes/mirror_box.json (plain JSON scenes in the
course's format; this script only saves typing out their checkerboard floors and boxes).

    python3 scenes/tools/make_scenes.py      # from the repository root
"""
import json
import math
import os


class Builder:
    def __init__(self):
        self.vertices = []  # (x, y, z)

    def vertex(self, p):
        self.vertices.append(p)
        return len(self.vertices)  # 1-based ids

    def quad(self, a, b, c, d):
        """Ids of two triangles a b c, a c d (counter-clockwise a b c d is the front)."""
        ids = [self.vertex(p) for p in (a, b, c, d)]
        return [ids[0], ids[1], ids[2], ids[0], ids[2], ids[3]]

    def vertex_data(self):
        return {"_data": "  ".join(" ".join(fmt(x) for x in v) for v in self.vertices), "_type": "xyz"}


def fmt(x):
    x = round(x, 5)
    return str(int(x)) if x == int(x) else repr(x)


def faces(ids):
    return {"_data": " ".join(str(i) for i in ids), "_type": "triangle"}


def checker(b, x0, x1, z0, z1, n_x, n_z, y=0.0):
    """Two face lists (light and dark tiles) of a floor facing +y."""
    light, dark = [], []
    sx, sz = (x1 - x0) / n_x, (z1 - z0) / n_z
    for i in range(n_x):
        for k in range(n_z):
            xa, xb = x0 + i * sx, x0 + (i + 1) * sx
            za, zb = z0 + k * sz, z0 + (k + 1) * sz
            # counter-clockwise seen from above (+y): (xa,zb) (xb,zb) (xb,za) (xa,za)
            ids = b.quad((xa, y, zb), (xb, y, zb), (xb, y, za), (xa, y, za))
            (light if (i + k) % 2 == 0 else dark).extend(ids)
    return light, dark


def box(b, center, size, yaw_deg, inward=False):
    """12 triangles of a box rotated about y; faces point out (or in)."""
    cx, cy, cz = center
    hx, hy, hz = (s / 2 for s in size)
    c, s = math.cos(math.radians(yaw_deg)), math.sin(math.radians(yaw_deg))

    def p(x, y, z):
        return (cx + c * x + s * z, cy + y, cz - s * x + c * z)

    corners = {(i, j, k): p(i * hx, j * hy, k * hz) for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)}
    # each face counter-clockwise seen from outside
    quads = [
        [(1, -1, -1), (1, 1, -1), (1, 1, 1), (1, -1, 1)],      # +x
        [(-1, -1, 1), (-1, 1, 1), (-1, 1, -1), (-1, -1, -1)],  # -x
        [(-1, 1, 1), (1, 1, 1), (1, 1, -1), (-1, 1, -1)],      # +y
        [(-1, -1, -1), (1, -1, -1), (1, -1, 1), (-1, -1, 1)],  # -y
        [(-1, -1, 1), (1, -1, 1), (1, 1, 1), (-1, 1, 1)],      # +z
        [(1, -1, -1), (-1, -1, -1), (-1, 1, -1), (1, 1, -1)],  # -z
    ]
    out = []
    for q in quads:
        pts = [corners[k] for k in q]
        if inward:
            pts.reverse()
        out.extend(b.quad(*pts))
    return out


def octahedron(b, center, radius, height, yaw_deg):
    """A gem: 8 triangles, apexes along y, faces pointing out."""
    cx, cy, cz = center
    top = b.vertex((cx, cy + height, cz))
    bottom = b.vertex((cx, cy - height, cz))
    ring = []
    for k in range(4):
        a = math.radians(yaw_deg + 90 * k)
        ring.append(b.vertex((cx + radius * math.cos(a), cy, cz - radius * math.sin(a))))
    ids = []
    for k in range(4):
        a, n = ring[k], ring[(k + 1) % 4]
        ids += [top, a, n]       # counter-clockwise seen from outside (angles grow anticlockwise about +y)
        ids += [bottom, n, a]
    return ids


def material(id_, kind=None, **fields):
    m = {"_id": str(id_)}
    if kind:
        m["_type"] = kind
    m.update({k: v for k, v in fields.items()})
    return m


def camera(position, gaze_point, fovy, width, height, image):
    return {"_id": "1", "_type": "lookAt", "Position": position, "GazePoint": gaze_point, "Up": "0 1 0",
            "FovY": str(fovy), "NearDistance": "1", "ImageResolution": f"{width} {height}", "ImageName": image}


def glass_checker():
    b = Builder()
    light, dark = checker(b, -7, 7, -9, 5, 14, 14)
    cube = box(b, (1.55, 0.801, 0.4), (1.6, 1.6, 1.6), 32)  # 1 mm above the floor, not in it
    gem = octahedron(b, (-0.1, 0.85, 2.3), 0.75, 0.85, 20)
    amber_center = b.vertex((-1.75, 1.05, -0.2))
    glass = dict(AmbientReflectance="0 0 0", DiffuseReflectance="0 0 0", SpecularReflectance="0.7 0.7 0.7",
                 PhongExponent="120", MirrorReflectance="1 1 1")
    return {"Scene": {
        "BackgroundColor": "70 95 130",
        "ShadowRayEpsilon": "1e-4",
        "MaxRecursionDepth": "8",
        "Cameras": {"Camera": camera("0.4 3.3 7.6", "0 0.75 0", 38, 800, 500, "glass_checker.png")},
        "Lights": {"AmbientLight": "22 22 22", "PointLight": [
            {"_id": "1", "Position": "-4 8 6", "Intensity": "42000 42000 42000"},
            {"_id": "2", "Position": "6 5 -3", "Intensity": "12000 10500 9000"}]},
        "Materials": {"Material": [
            material(1, AmbientReflectance="0.9 0.9 0.88", DiffuseReflectance="0.85 0.85 0.82",
                     SpecularReflectance="0.1 0.1 0.1", PhongExponent="10"),
            material(2, AmbientReflectance="0.15 0.18 0.25", DiffuseReflectance="0.12 0.15 0.22",
                     SpecularReflectance="0.1 0.1 0.1", PhongExponent="10"),
            material(3, "dielectric", **glass, RefractionIndex="1.5", AbsorptionCoefficient="0.04 0.3 1.0"),   # amber
            material(4, "dielectric", **glass, RefractionIndex="1.52", AbsorptionCoefficient="0.8 0.15 0.22"),  # teal
            material(5, "dielectric", **glass, RefractionIndex="1.76", AbsorptionCoefficient="0.08 1.8 1.3"),  # ruby
        ]},
        "VertexData": b.vertex_data(),
        "Objects": {
            "Mesh": [
                {"_id": "1", "Material": "1", "Faces": faces(light)},
                {"_id": "2", "Material": "2", "Faces": faces(dark)},
                {"_id": "3", "Material": "4", "Faces": faces(cube)},
                {"_id": "4", "Material": "5", "Faces": faces(gem)},
            ],
            "Sphere": {"_id": "1", "Material": "3", "Center": str(amber_center), "Radius": "1.05"},
        },
    }}


def mirror_box():
    b = Builder()
    x0, x1, y0, y1, z0, z1 = -4, 4, 0, 5, -6, 5
    light, dark = checker(b, x0, x1, z0, z1, 8, 11)
    ceiling = b.quad((x0, y1, z0), (x1, y1, z0), (x1, y1, z1), (x0, y1, z1))  # facing down
    back = b.quad((x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0))     # facing +z
    front = b.quad((x1, y0, z1), (x0, y0, z1), (x0, y1, z1), (x1, y1, z1))    # facing -z
    left = b.quad((x0, y0, z1), (x0, y0, z0), (x0, y1, z0), (x0, y1, z1))     # facing +x
    right = b.quad((x1, y0, z0), (x1, y0, z1), (x1, y1, z1), (x1, y1, z0))    # facing -x
    gold, copper, chalk = b.vertex((-1.3, 1.2, -1.4)), b.vertex((1.35, 0.95, -0.4)), b.vertex((0.1, 0.45, 1.2))
    return {"Scene": {
        "BackgroundColor": "0 0 0",
        "ShadowRayEpsilon": "1e-4",
        "MaxRecursionDepth": "12",
        "Cameras": {"Camera": camera("0.5 2.3 4.2", "0 1.2 -1.5", 55, 800, 500, "mirror_box.png")},
        "Lights": {"AmbientLight": "14 14 14", "PointLight": [
            {"_id": "1", "Position": "0 4.6 1.5", "Intensity": "15000 14500 13500"},
            {"_id": "2", "Position": "-2.5 3 3.5", "Intensity": "5000 5000 5500"}]},
        "Materials": {"Material": [
            material(1, AmbientReflectance="0.8 0.75 0.65", DiffuseReflectance="0.75 0.7 0.6",
                     SpecularReflectance="0.05 0.05 0.05", PhongExponent="5"),
            material(2, AmbientReflectance="0.35 0.12 0.08", DiffuseReflectance="0.35 0.12 0.08",
                     SpecularReflectance="0.05 0.05 0.05", PhongExponent="5"),
            material(3, AmbientReflectance="0.9 0.9 0.9", DiffuseReflectance="0.85 0.85 0.85",
                     SpecularReflectance="0 0 0", PhongExponent="1"),
            material(4, AmbientReflectance="0.1 0.15 0.35", DiffuseReflectance="0.1 0.16 0.4",
                     SpecularReflectance="0 0 0", PhongExponent="1"),
            material(5, "mirror", AmbientReflectance="0.02 0.02 0.02", DiffuseReflectance="0.02 0.02 0.02",
                     SpecularReflectance="0 0 0", PhongExponent="1", MirrorReflectance="0.88 0.9 0.9"),
            material(6, "conductor", AmbientReflectance="0 0 0", DiffuseReflectance="0 0 0",
                     SpecularReflectance="1 0.86 0.57", PhongExponent="60", MirrorReflectance="1 0.86 0.57",
                     RefractionIndex="0.37", AbsorptionIndex="2.82"),   # gold
            material(7, "conductor", AmbientReflectance="0 0 0", DiffuseReflectance="0 0 0",
                     SpecularReflectance="0.98 0.64 0.54", PhongExponent="60", MirrorReflectance="0.98 0.64 0.54",
                     RefractionIndex="0.27", AbsorptionIndex="3.41"),   # copper
            material(8, AmbientReflectance="0.8 0.8 0.8", DiffuseReflectance="0.8 0.8 0.78",
                     SpecularReflectance="0.3 0.3 0.3", PhongExponent="40"),
            material(9, AmbientReflectance="0.1 0.3 0.25", DiffuseReflectance="0.1 0.35 0.3",
                     SpecularReflectance="0 0 0", PhongExponent="1"),
        ]},
        "VertexData": b.vertex_data(),
        "Objects": {
            "Mesh": [
                {"_id": "1", "Material": "1", "Faces": faces(light)},
                {"_id": "2", "Material": "2", "Faces": faces(dark)},
                {"_id": "3", "Material": "3", "Faces": faces(ceiling)},
                {"_id": "4", "Material": "4", "Faces": faces(left)},
                {"_id": "5", "Material": "9", "Faces": faces(right)},
                {"_id": "6", "Material": "5", "Faces": faces(back + front)},
            ],
            "Sphere": [
                {"_id": "1", "Material": "6", "Center": str(gold), "Radius": "1.2"},
                {"_id": "2", "Material": "7", "Center": str(copper), "Radius": "0.95"},
                {"_id": "3", "Material": "8", "Center": str(chalk), "Radius": "0.45"},
            ],
        },
    }}


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    for name, scene in (("glass_checker", glass_checker()), ("mirror_box", mirror_box())):
        path = os.path.join(here, "..", name + ".json")
        with open(path, "w") as f:
            json.dump(scene, f, indent=2)
            f.write("\n")
        print("wrote", os.path.normpath(path))


if __name__ == "__main__":
    main()
