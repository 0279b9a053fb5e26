"""The assignment 3 section's tables and its log-log plot (report_convergence.py)."""
import html
import json
import math
import os

from report_doc import Doc


def f2(v):
    return f"{v:.2f}"


def section(doc, results, converged_factor):
    doc.h(2, "Assignment 3: samples, time and error")
    doc.p(f"Every complete hw3 scene. Errors against a converged image (the sobol sampler at {converged_factor}x "
          f"the scene's NumSamples) and against the course's reference: RMSE in output levels, and the % of "
          f"16x16 blocks whose mean is off by more than 3 levels (`rtdiff --mc`). Time: CPU seconds of the "
          f"raytracer process (all threads). Made by `tests/report/report_convergence.py` (`make report`).")
    doc.image("convergence.svg", "error against time, log-log, per scene")
    doc.h(3, "Convergence (default sampler)")
    rows = []
    for r in results:
        for x in r["spp"]:
            ref = x["vs_reference"]
            rows.append([r["scene"] if x is r["spp"][0] else "", str(x["n"]) + (" (own)" if x["n"] == r["samples"]
                                                                              else ""),
                         f2(x["cpu"]), f2(x["vs_converged"]["rmse"]), f2(x["vs_converged"]["blocks"]),
                         f2(ref["rmse"]) if ref else "", f2(ref["blocks"]) if ref else ""])
    doc.table(["scene", "samples", "CPU s", "RMSE vs converged", "% blocks vs converged", "RMSE vs reference",
               "% blocks vs reference"], rows)

    doc.h(3, "Samplers at the scene's samples")
    doc.p("At equal samples the samplers cost the same to within noise; `RMSE at equal time` scales each "
          "sampler's RMSE to the default's CPU time by 1/sqrt(time) (the Monte Carlo rate, which favours "
          "none of them).")
    rows = []
    for r in results:
        base = r["samplers"]["sobol"]
        for i, (name, x) in enumerate(r["samplers"].items()):
            eq = x["vs_converged"]["rmse"] * math.sqrt(x["cpu"] / base["cpu"]) if base["cpu"] > 0 else 0
            ref = x["vs_reference"]
            rows.append([r["scene"] if i == 0 else "", name, f2(x["cpu"]), f2(x["vs_converged"]["rmse"]),
                         f2(eq), f2(ref["blocks"]) if ref else ""])
    doc.table(["scene", "sampler", "CPU s", "RMSE vs converged", "RMSE at equal time", "% blocks vs reference"],
              rows)

    doc.h(3, "Adaptive sampling")
    doc.p("`--sampler sobol --noise-target E` (the default cap), E from the loosest down until its error "
          "against the converged image is no more than the default sampler's at the scene's samples.")
    rows = []
    for r in results:
        base = r["samplers"]["sobol"]
        rows.append([r["scene"], "uniform, sobol", str(r["samples"]), f2(base["cpu"]),
                     f2(base["vs_converged"]["rmse"]), "1.00"])
        for x in r["adaptive"]:
            rows.append(["", f"E = {x['target']:g}", f"{x['spp']:.1f}", f2(x["cpu"]), f2(x["vs_converged"]["rmse"]),
                         f2(x["cpu"] / base["cpu"]) if base["cpu"] > 0 else ""])
    doc.table(["scene", "sampling", "mean samples", "CPU s", "RMSE vs converged", "time / uniform's"], rows)

    doc.h(3, "What each feature costs at equal samples")
    rows = [[r["scene"], x["feature"], f2(x["on"]), f2(x["off"]), f2(x["on"] / x["off"]) if x["off"] > 0 else ""]
            for r in results for x in r["features"]]
    doc.table(["scene", "feature", "CPU s with", "CPU s without", "ratio"], rows)


def svg_plot(results):
    """Small multiples: per scene, RMSE against the converged image over CPU time, log-log;
    the default sampler's counts joined, the other samplers and adaptive sampling as marks,
    and the 1/sqrt(N) slope through the 1-sample point, dashed."""
    e = html.escape
    pw, ph, cols = 380, 250, 2
    rows_n = (len(results) + cols - 1) // cols
    width, height = cols * pw, rows_n * ph + 30
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" font-family="sans-serif" '
           f'font-size="10">', f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="10" y="{height - 10}">RMSE against the converged image (levels) over CPU seconds, log-log. '
           f'Line: default sampler at 1..256 and own samples; dashed: slope 1/sqrt(N); '
           f'triangle: stratified, square: sobol, diamond: adaptive.</text>']
    for i, r in enumerate(results):
        ox, oy = (i % cols) * pw, (i // cols) * ph
        pts = [(x["cpu"], x["vs_converged"]["rmse"]) for x in r["spp"]]
        marks = [("tri", r["samplers"][s]["cpu"], r["samplers"][s]["vs_converged"]["rmse"])
                 for s in ("stratified",) if s in r["samplers"]]
        marks += [("dia", x["cpu"], x["vs_converged"]["rmse"]) for x in r["adaptive"]]
        allp = [p for p in pts + [(m[1], m[2]) for m in marks] if p[0] > 0 and p[1] > 0]
        if not allp:
            continue
        lx = [math.log10(p[0]) for p in allp]
        ly = [math.log10(p[1]) for p in allp]
        x0, x1 = math.floor(min(lx)), math.ceil(max(lx))
        y0, y1 = math.floor(min(ly) - 0.05), math.ceil(max(ly) + 0.05)
        x1, y1 = max(x1, x0 + 1), max(y1, y0 + 1)
        L, T, W, H = ox + 50, oy + 25, pw - 70, ph - 60

        def X(t):
            return L + (math.log10(t) - x0) / (x1 - x0) * W

        def Y(v):
            return T + H - (math.log10(v) - y0) / (y1 - y0) * H

        out.append(f'<text x="{ox + pw / 2}" y="{oy + 15}" text-anchor="middle" font-size="12">'
                   f'{e(r["scene"])}</text>')
        out.append(f'<rect x="{L}" y="{T}" width="{W}" height="{H}" fill="none" stroke="#888"/>')
        for d in range(x0, x1 + 1):
            out.append(f'<text x="{X(10 ** d):.1f}" y="{T + H + 14}" text-anchor="middle">{10 ** d:g} s</text>')
        for d in range(y0, y1 + 1):
            out.append(f'<text x="{L - 4}" y="{Y(10 ** d) + 3:.1f}" text-anchor="end">{10 ** d:g}</text>')
        good = [p for p in pts if p[0] > 0 and p[1] > 0]
        if good:
            t1, e1 = good[0]
            ta, tb = 10 ** x0, 10 ** x1
            ya, yb = e1 * math.sqrt(t1 / ta), e1 * math.sqrt(t1 / tb)
            out.append(f'<line x1="{X(ta):.1f}" y1="{Y(ya):.1f}" x2="{X(tb):.1f}" y2="{Y(yb):.1f}" '
                       f'stroke="#aaa" stroke-dasharray="4 3" clip-path="inset(0)"/>')
            out.append('<polyline fill="none" stroke="#1f5fa8" stroke-width="1.5" points="' +
                       " ".join(f"{X(t):.1f},{Y(v):.1f}" for t, v in good) + '"/>')
            for (t, v), x in zip(good, r["spp"]):
                out.append(f'<circle cx="{X(t):.1f}" cy="{Y(v):.1f}" r="2.5" fill="#1f5fa8"/>'
                           f'<text x="{X(t) + 4:.1f}" y="{Y(v) - 4:.1f}" font-size="8">{x["n"]}</text>')
        for kind, t, v in marks:
            if t <= 0 or v <= 0:
                continue
            cx, cy = X(t), Y(v)
            if kind == "tri":
                out.append(f'<polygon points="{cx},{cy - 4} {cx - 4},{cy + 3} {cx + 4},{cy + 3}" fill="#e07b39"/>')
            else:
                out.append(f'<polygon points="{cx},{cy - 4} {cx + 4},{cy} {cx},{cy + 4} {cx - 4},{cy}" '
                           f'fill="#3a9a50"/>')
        # sobol as a square, drawn over the triangles
        if "sobol" in r["samplers"]:
            s = r["samplers"]["sobol"]
            if s["cpu"] > 0 and s["vs_converged"]["rmse"] > 0:
                out.append(f'<rect x="{X(s["cpu"]) - 3:.1f}" y="{Y(s["vs_converged"]["rmse"]) - 3:.1f}" '
                           f'width="6" height="6" fill="#8a3fb0"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"


def write(a, results):
    doc = Doc()
    section(doc, results, a.converged)
    with open(os.path.join(a.out, "convergence.svg"), "w", encoding="utf-8") as f:
        f.write(svg_plot(results))
    with open(os.path.join(a.out, "convergence.md"), "w", encoding="utf-8") as f:
        f.write(doc.markdown())
    with open(os.path.join(a.out, "convergence.json"), "w", encoding="utf-8") as f:
        json.dump(results, f, indent=1)
    print(doc.markdown())
    return doc
