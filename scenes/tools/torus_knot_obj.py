#!/usr/bin/env python3
"""Writes a Wavefront OBJ + MTL of our own: a (2,3) torus knot tube standing on a round
mirror-topped pedestal. It is the input of scenes/knot/, made with rtconvert:

    python3 scenes/tools/torus_knot_obj.py /tmp/knot     # writes /tmp/knot/knot.obj, knot.mtl
    ./rtconvert /tmp/knot/knot.obj scenes/knot/knot.json

The OBJ uses what the importer must handle: quads, a 64-gon written with negative
(relative) indices, vertex normals (f v//vn), smoothing groups and three MTL materials.
"""
import math
import os
import sys

ALONG, AROUND = 360, 36          # tube segments: 360 x 36 quads = 25920 triangles
P, Q = 2, 3                      # the knot winds P times around the axis, Q times through the hole
R, r, TUBE = 1.0, 0.42, 0.17     # torus radii and the tube's radius
SIDES = 64                       # the pedestal


def knot(t):
    c = R + r * math.cos(Q * t)
    return (c * math.cos(P * t), r * math.sin(Q * t) * 2.2, c * math.sin(P * t))


def sub(a, b): return tuple(x - y for x, y in zip(a, b))
def cross(a, b): return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])
def norm(a):
    n = math.sqrt(sum(x * x for x in a))
    return tuple(x / n for x in a)


def main(out_dir):
    os.makedirs(out_dir, exist_ok=True)
    v, vn, lines = [], [], []
    lift = 1.35  # the knot floats above the pedestal top (y = 0)

    # Tube: rotation-minimising frames along the curve, so the quads do not twist.
    pts = [knot(2 * math.pi * i / ALONG) for i in range(ALONG)]
    tangents = [norm(sub(pts[(i + 1) % ALONG], pts[i - 1])) for i in range(ALONG)]
    normal = norm(cross(tangents[0], (0, 1, 0)))
    frames = []
    for i in range(ALONG):
        t = tangents[i]
        normal = norm(sub(normal, tuple(t[k] * sum(normal[j] * t[j] for j in range(3)) for k in range(3))))
        frames.append((normal, cross(t, normal)))
    # Close the frame: spread the twist left over at the seam along the tube.
    n0, b0 = frames[0]
    nl, bl = frames[-1]
    twist = math.atan2(sum(x * y for x, y in zip(nl, b0)), sum(x * y for x, y in zip(nl, n0)))
    for i in range(ALONG):
        for k in range(AROUND):
            a = 2 * math.pi * k / AROUND - twist * i / ALONG
            n, b = frames[i]
            d = tuple(math.cos(a) * n[j] + math.sin(a) * b[j] for j in range(3))
            p = pts[i]
            v.append((p[0] + TUBE * d[0], p[1] + TUBE * d[1] + lift, p[2] + TUBE * d[2]))
            vn.append(d)
    lines += ["o knot", "usemtl coral", "s 1"]
    for i in range(ALONG):
        for k in range(AROUND):
            a = i * AROUND + k + 1
            b = i * AROUND + (k + 1) % AROUND + 1
            c = ((i + 1) % ALONG) * AROUND + (k + 1) % AROUND + 1
            d = ((i + 1) % ALONG) * AROUND + k + 1
            lines.append(f"f {a}//{a} {b}//{b} {c}//{c} {d}//{d}")  # counter-clockwise from outside

    # Pedestal: a 64-gon mirror top (one polygon, negative indices) and flat sides.
    radius, height = 1.9, 0.35
    lines += ["o pedestal", "usemtl mirror", "s off"]
    top = []
    for k in range(SIDES):
        a = -2 * math.pi * k / SIDES  # counter-clockwise seen from above
        top.append((radius * math.cos(a), 0.0, radius * math.sin(a)))
    ped_lines = [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in top]
    ped_lines.append("f " + " ".join(str(-SIDES + k) for k in range(SIDES)))
    bottom = [(x, -height, z) for x, _, z in top]
    ped_lines += [f"v {x:.6f} {y:.6f} {z:.6f}" for x, y, z in bottom]
    ped_lines += ["usemtl stone"]
    for k in range(SIDES):
        # top k, top k+1 are the first SIDES vertices, bottom the next; all relative to the end
        tk, tk1 = -2 * SIDES + k, -2 * SIDES + (k + 1) % SIDES
        bk, bk1 = -SIDES + k, -SIDES + (k + 1) % SIDES
        ped_lines.append(f"f {tk} {bk} {bk1} {tk1}")

    with open(os.path.join(out_dir, "knot.obj"), "w") as f:
        f.write("# (2,3) torus knot on a pedestal, made by scenes/tools/torus_knot_obj.py\n")
        f.write("mtllib knot.mtl\n")
        for x, y, z in v:
            f.write(f"v {x:.6f} {y:.6f} {z:.6f}\n")
        for x, y, z in vn:
            f.write(f"vn {x:.5f} {y:.5f} {z:.5f}\n")
        f.write("\n".join(lines) + "\n")
        f.write("\n".join(ped_lines) + "\n")
    with open(os.path.join(out_dir, "knot.mtl"), "w") as f:
        f.write("""# materials of knot.obj
newmtl coral
Ka 0.9 0.35 0.25
Kd 0.85 0.3 0.22
Ks 0.6 0.6 0.6
Ns 80
illum 2

newmtl mirror
Ka 0 0 0
Kd 0.05 0.05 0.05
Ks 0.85 0.85 0.9
Ns 200
illum 3

newmtl stone
Ka 0.5 0.5 0.52
Kd 0.55 0.55 0.58
Ks 0.1 0.1 0.1
Ns 10
illum 2
""")
    print("wrote", os.path.join(out_dir, "knot.obj"), "and knot.mtl")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else ".")
