"""report.py's write-up: the comparisons of the renders (imgdiff), every table, the chart
and the gallery, written to --out as index.md, index.html, chart.svg and report.json."""
import json
import os
import shutil
import time

from report_chart import svg_chart
from report_common import log
from report_doc import Doc
from report_machine import machine
from report_runner import MAX_REPEATS
from report_timing import Timing, fs, mean, pct, pct_s, ratio_text, worst


class Writeup:
    """The report of one run of every study: built section by section (the order of the
    page), then written by write(), which returns the exit status."""

    def __init__(self, a, R, D, runs, repeat, configs, official, main_set, far, big, depths, depth_set, bvh_set,
                 bvh_configs, t_start):
        self.a, self.R, self.D, self.runs, self.repeat, self.configs = a, R, D, runs, repeat, configs
        self.official, self.main_set, self.far, self.big = official, main_set, far, big
        self.depths, self.depth_set, self.bvh_set, self.bvh_configs = depths, depth_set, bvh_set, bvh_configs
        self.t_start = t_start
        self.doc = self.data = None
        self.gallery = []  # culling()'s rows of images, shown by write()
        shutil.rmtree(os.path.join(a.out, "img"), ignore_errors=True)
        self.img_dir = os.path.join(a.out, "img")
        os.makedirs(self.img_dir, exist_ok=True)

    # Comparisons and totals the sections share.

    def ref_of(self, scene, image):
        return scene.refs.get(image) or scene.refs.get(os.path.basename(image))

    def vs_ref(self, cfg, scene, image):
        ref = self.ref_of(scene, image)
        if not ref or not self.R.ok(cfg, scene):
            return None
        d = self.D(self.R.png(cfg, scene, image), ref)
        return None if "error" in d else d

    def vs_cfg(self, cfg, base, scene, image, diff_png=None):
        if not self.R.ok(cfg, scene) or not self.R.ok(base, scene):
            return None
        d = self.D(self.R.png(cfg, scene, image), self.R.png(base, scene, image), diff_png)
        return None if "error" in d else d

    def errors(self, cfg, scenes, base="double"):
        """(mean %, worst %) off by >1 vs reference over official images; the same vs `base` for ours."""
        ref_p, own_p, n_ref, n_own = [], [], 0, 0
        for s in scenes:
            if not self.R.ok(cfg, s):
                continue
            for im in self.R.images(cfg, s):
                rec = self.R.record(cfg, s, im)
                px = rec["width"] * rec["height"]
                if s.kind == "official":
                    d = self.vs_ref(cfg, s, im)
                    if d:
                        ref_p.append(100.0 * d["over1"] / px)
                        n_ref += 1
                else:
                    d = self.vs_cfg(cfg, base, s, im)
                    if d:
                        own_p.append(100.0 * d["over1"] / px)
                        n_own += 1
        return mean(ref_p), worst(ref_p), mean(own_p), worst(own_p), n_ref, n_own

    def total_timing(self, cfg, scenes, fields=("render",)):
        parts = []
        for s in scenes:
            if not self.R.ok(cfg, s):
                return None
            for i, im in enumerate(self.R.images(cfg, s)):
                for fld in fields:
                    if fld == "bvh" and i > 0:
                        continue  # one build per scene file
                    parts.append(self.R.timing(cfg, s, im, fld))
        return Timing.total(parts)

    def total_time(self, cfg, scenes, fields=("render",)):
        t = self.total_timing(cfg, scenes, fields)
        return t.median if t else None

    # The sections, in the page's order.

    def intro(self):
        """The title and the paragraph on the machine and the method; starts doc and data."""
        R, a, runs, repeat, configs = self.R, self.a, self.runs, self.repeat, self.configs
        n_runs = sum(len(v) for v in R.runs.values())
        still_disturbed = sum(1 for v in R.runs.values() for r in v if r.get("disturbed"))
        data = {"repeated_runs": R.repeated, "disturbed_runs": still_disturbed,
                "machine": machine(a.threads, {k: v[0] for k, v in configs.items()}), "runs": runs, "repeat": repeat,
                "quick": a.quick, "images": []}
        doc = Doc()
        m = data["machine"]
        doc.h(1, "Ray tracer report: culling, timings and the speed/accuracy trade")
        doc.p(f"Machine: {m['cpu']}, {m['hardware_threads']} hardware threads, rendering with {a.threads} threads "
              f"(`-j {a.threads}`); {m['compiler']}; commit {m['commit']}; {m['date']}. Times are medians of "
              f"{runs} process{'es' if runs > 1 else ''} of each configuration, each rendering every image "
              f"{repeat} time{'s' if repeat > 1 else ''} (`--repeat {repeat}`; the raytracer's `--stats` figures: "
              f"render = tracing only, BVH build separately), processes interleaved across configurations. "
              f"A ratio is marked *within noise* where the fastest and slowest renders of the two "
              f"configurations overlap, *one run* where there is one render of each. "
              f"Made by `make report{'-quick' if a.quick else ''}` (tests/report/report.py). "
              f"A run during which other processes used more than a quarter of a core was repeated "
              f"(twice at most, {MAX_REPEATS} times in all): {R.repeated} repeats; {still_disturbed} of "
              f"{n_runs} runs kept were still disturbed.")
        self.doc, self.data = doc, data

    def culling(self):
        """The blog table: culling off and on, one row per image, and the chart."""
        R, a, doc, data, runs = self.R, self.a, self.doc, self.data, self.runs
        repeat, main_set, img_dir = self.repeat, self.main_set, self.img_dir
        doc.h(2, "Back-face culling off and on")
        doc.p("One row per image. Time: render seconds (tracing only; parsing, BVH build and PNG writing "
              "excluded). Pixels changed: pixels whose colour differs at all between the two renders. "
              "Off by >1 vs reference: pixels with a channel more than one level away from the course's "
              "reference image, with culling on (as the references were made).")
        rows, chart_rows = [], []
        all_off, all_on = [], []
        gallery = []
        for s in main_set:
            if not (R.ok("double", s) and R.ok("nocull", s)):
                continue
            for im in R.images("double", s):
                rec = R.record("double", s, im)
                tm_on = R.timing("double", s, im, "render")
                tm_off = R.timing("nocull", s, im, "render")
                t_on, t_off = tm_on.median, tm_off.median
                all_on.append(tm_on)
                all_off.append(tm_off)
                stem = f"{s.key}__{os.path.splitext(os.path.basename(im))[0]}"
                diff_png = os.path.join(img_dir, stem + "__culling_diff.png")
                ch = self.vs_cfg("nocull", "double", s, im, diff_png)
                rd = self.vs_ref("double", s, im)
                pixels = rec["width"] * rec["height"]
                prim = rec["primitives"]
                shutil.copy2(R.png("double", s, im), os.path.join(img_dir, stem + "__cull.png"))
                shutil.copy2(R.png("nocull", s, im), os.path.join(img_dir, stem + "__nocull.png"))
                ref = self.ref_of(s, im)
                if ref:
                    shutil.copy2(ref, os.path.join(img_dir, stem + "__reference.png"))
                rows.append([f"`{s.label}`", os.path.basename(im), f"{rec['width']}x{rec['height']}",
                             str(prim["triangles"]) + (f" + {prim['spheres']} sph" if prim["spheres"] else ""),
                             fs(t_off), fs(t_on), ratio_text(tm_off, tm_on),
                             f"{ch['changed']} ({pct(ch['changed'], pixels)})" if ch else "—",
                             pct(rd["over1"], pixels, 3) if rd else "no reference"])
                chart_rows.append((os.path.basename(im), t_off, t_on))
                gallery.append((f"`{s.label}` {os.path.basename(im)}",
                                [(f"img/{stem}__cull.png", "ours, culling on"),
                                 (f"img/{stem}__nocull.png", "ours, culling off"),
                                 (f"img/{stem}__reference.png" if ref else None, "reference"),
                                 (f"img/{stem}__culling_diff.png",
                                  f"changed by culling: {ch['changed'] if ch else '?'} px")]))
                data["images"].append({"scene": s.label, "image": im, "kind": s.kind, "width": rec["width"],
                                       "height": rec["height"], "primitives": prim, "render_nocull": t_off,
                                       "render_cull": t_on, "culling_diff": ch, "vs_reference": rd,
                                       "rays_cull": rec["rays"],
                                       "rays_nocull": R.record("nocull", s, im)["rays"]})
        sum_off, sum_on = Timing.total(all_off), Timing.total(all_on)
        rows.append(["**all**", "", "", "", fs(sum_off.median if sum_off else None),
                     fs(sum_on.median if sum_on else None), ratio_text(sum_off, sum_on), "", ""])
        doc.table(["scene", "image", "resolution", "triangles", "no culling (s)", "culling (s)", "speed-up",
                   "pixels changed by culling", "off by >1 vs reference"], rows,
                  ["l", "l", "r", "r", "r", "r", "r", "r", "r"])
        with open(os.path.join(a.out, "chart.svg"), "w", encoding="utf-8") as f:
            f.write(svg_chart(chart_rows, f"Render time per image, median of {runs * repeat} "
                                          f"render{'s' if runs * repeat > 1 else ''}, {a.threads} threads"))
        doc.image("chart.svg", "render time per image, culling off and on")
        self.gallery = gallery

    def trade(self):
        """The speed/accuracy trade, one row per option of every study."""
        R, doc, data, main_set, big = self.R, self.doc, self.data, self.main_set, self.big
        depths, depth_set, bvh_set, bvh_configs = self.depths, self.depth_set, self.bvh_set, self.bvh_configs
        summary = []

        def add_row(study, option, cfg, scenes, base_cfg="double", fields=("render",), err_base="double"):
            t = self.total_timing(cfg, scenes, fields)
            t0 = self.total_timing(base_cfg, scenes, fields)
            rm, rw, om, ow, nr, no = self.errors(cfg, scenes, err_base)
            summary.append([study, option, f"{sum(len(R.images(cfg, s)) for s in scenes)}", fs(t.median if t else None),
                            ratio_text(t, t0) if cfg != base_cfg else "1.00x",
                            f"{pct_s(rm)} / {pct_s(rw)}" if nr else "—",
                            f"{pct_s(om)} / {pct_s(ow)}" if no else "—"])

        add_row("precision", "double (default)", "double_prec", main_set, "double_prec")
        add_row("precision", "float (`--precision float`)", "float", main_set, "double_prec")
        add_row("precision", "float, culling off (`--precision float --no-cull`)", "float_nocull", main_set,
                "double_prec")
        add_row("culling", "on (default)", "double", main_set)
        add_row("culling", "off (`--no-cull`)", "nocull", main_set)
        add_row("ShadowRayEpsilon", "x0.1 (`--epsilon-scale 0.1`)", "eps0.1", main_set, "eps1")
        add_row("ShadowRayEpsilon", "x1 (default)", "eps1", main_set, "eps1")
        add_row("ShadowRayEpsilon", "x10 (`--epsilon-scale 10`)", "eps10", main_set, "eps1")
        add_row("weak rays", "not traced below weight 1e-4 (default)", "minw_default", main_set, "minw_default",
                err_base="minw_default")
        add_row("weak rays", "all traced to MaxRecursionDepth (`--min-weight 0`)", "minw0", main_set, "minw_default",
                err_base="minw_default")
        for d in depths:
            add_row("MaxRecursionDepth", f"{d} (`--max-depth {d}`)", f"depth{d}", depth_set, "depth_default")
        add_row("MaxRecursionDepth", "the scene's own (default)", "depth_default", depth_set, "depth_default")
        for name, cfg in bvh_configs:
            add_row("BVH", name, cfg, bvh_set, "bvh_default", fields=("bvh", "render"), err_base="bvh_default")
        doc.h(2, "The speed/accuracy trade, one row per option")
        doc.p("Time: the sum over the study's images of the median render time (for BVH rows: BVH build + "
              "render), and its ratio to the default. Error, official scenes: the percentage of pixels more than "
              "one level off the course's reference image, mean / worst over the images. Error, our scenes (no "
              "reference): the same against our default double-precision render. Studies: precision, culling, "
              f"epsilon and weak rays over all {sum(len(R.images('double', s)) for s in main_set)} images; "
              "depth over the "
              f"{len(depth_set)} scenes with mirrors, conductors or glass; BVH over the {len(bvh_set)} scenes of "
              "5000+ triangles" + (" (including a generated 1M-triangle mesh)" if big else "") + ".")
        doc.table(["study", "option", "images", "time (s)", "vs default", "official: % off vs reference (mean / worst)",
                   "ours: % changed vs double (mean / worst)"], summary, ["l", "l", "r", "r", "r", "r", "r"])
        data["summary"] = summary

    def far_from_origin(self):
        """Precision far from the origin (official simple.json and spheres.json moved)."""
        R, doc, data, official, far = self.R, self.doc, self.data, self.official, self.far
        if far:
            doc.h(3, "Precision far from the origin")
            doc.p("The official simple.json and spheres.json with every position (vertices, camera, gaze point, "
                  "lights) moved by (d, d, d); ShadowRayEpsilon stays 1e-3. Compared with the unmoved scene's "
                  "reference image: pixels more than one level off, and the largest channel difference.")
            frows = []
            bases = [s for s in official if s.label in ("simple.json", "spheres.json")]
            for s in bases + far:
                cells = [s.label]
                for cfg in ("double", "float"):
                    ims = R.images(cfg, s)
                    if not ims:
                        cells += ["failed", ""]
                        continue
                    im = ims[0]
                    d = self.vs_ref(cfg, s, im)
                    rec = R.record(cfg, s, im)
                    px = rec["width"] * rec["height"]
                    cells += [pct(d["over1"], px, 3) if d else "—", str(d["max"]) if d else "—"]
                frows.append(cells)
            doc.table(["scene", "double: off by >1", "double: max", "float: off by >1", "float: max"], frows)
            data["far"] = frows

    def epsilon(self):
        """ShadowRayEpsilon: pixels darker (acne) and brighter (leaks)."""
        R, doc, data, main_set = self.R, self.doc, self.data, self.main_set
        doc.h(3, "ShadowRayEpsilon: acne against light leaking")
        doc.p("Pixels more than one level away from the default (x1) render, split by whether they got darker "
              "(surfaces shadowing themselves: acne) or brighter (shadow rays starting beyond a thin occluder: "
              "leaks), summed over all images.")
        erows = []
        for cfg, name in (("eps0.1", "x0.1"), ("eps10", "x10")):
            dark = bright = total_px = 0
            worst_im = ("", 0.0)
            for s in main_set:
                if not R.ok(cfg, s):
                    continue
                for im in R.images(cfg, s):
                    d = self.vs_cfg(cfg, "double", s, im)
                    if not d:
                        continue
                    dark += d["darker"]
                    bright += d["brighter"]
                    total_px += d["pixels"]
                    share = 100.0 * d["over1"] / d["pixels"]
                    if share > worst_im[1]:
                        worst_im = (os.path.basename(im), share)
            erows.append([name, f"{dark} ({pct(dark, total_px, 3)})", f"{bright} ({pct(bright, total_px, 3)})",
                          f"{worst_im[0]} ({worst_im[1]:.2f}%)" if worst_im[0] else "—"])
        doc.table(["ShadowRayEpsilon", "darker pixels (acne)", "brighter pixels (leaks)", "most changed image"], erows)
        data["epsilon"] = erows

    def depth(self):
        """MaxRecursionDepth: time against the pixels still changing."""
        R, doc, data, depths, depth_set = self.R, self.doc, self.data, self.depths, self.depth_set
        doc.h(3, "MaxRecursionDepth: time against pixels still changing")
        doc.p(f"Over the {len(depth_set)} scenes with mirrors, conductors or glass: "
              + ", ".join(f"`{s.label}`" for s in depth_set) + ". Pixels changed: pixels whose colour differs "
              "at all from the render one level shallower.")
        drows = []
        prev = None
        for d in depths:
            cfg = f"depth{d}"
            t = self.total_time(cfg, depth_set)
            rays = sum(R.record(cfg, s, im)["rays"]["total"] for s in depth_set if R.ok(cfg, s)
                       for im in R.images(cfg, s))
            changed = total_px = 0
            if prev:
                for s in depth_set:
                    for im in R.images(cfg, s):
                        dd = self.vs_cfg(cfg, prev, s, im)
                        if dd:
                            changed += dd["changed"]
                            total_px += dd["pixels"]
            rm, rw, om, ow, nr, no = self.errors(cfg, depth_set)
            drows.append([str(d), fs(t), f"{rays / 1e6:.2f} M",
                          f"{changed} ({pct(changed, total_px, 3)})" if prev else "—",
                          f"{pct_s(rm)} / {pct_s(rw)}" if nr else "—"])
            prev = cfg
        doc.table(["depth", "render (s)", "rays", "pixels changed from depth - 1", "official: % off vs reference"],
                  drows)
        data["depth"] = drows

    def bvh(self):
        """BVH variants: build time against render time."""
        R, doc, data, bvh_set, bvh_configs = self.R, self.doc, self.data, self.bvh_set, self.bvh_configs
        doc.h(3, "BVH leaf size and build quality: build time against render time")
        doc.p("Over " + ", ".join(f"`{s.label}`" for s in bvh_set) + ". Build and render: sums of medians. "
              "Nodes and depth: of the largest scene. Identical: every image equal, pixel for pixel, to the "
              "default build's (the traversal's answer never depends on the tree).")
        brows = []
        largest = max(bvh_set, key=lambda s: max((R.record("bvh_default", s, im)["primitives"]["triangles"]
                                                  for im in R.images("bvh_default", s)),
                                                 default=0)) if bvh_set else None
        for name, cfg in bvh_configs:
            tb = self.total_time(cfg, bvh_set, ("bvh",))
            tr = self.total_time(cfg, bvh_set, ("render",))
            same = all((self.vs_cfg(cfg, "bvh_default", s, im) or {"changed": 1})["changed"] == 0
                       for s in bvh_set for im in R.images(cfg, s))
            nodes = depth = "—"
            if largest and R.ok(cfg, largest):
                rec = R.record(cfg, largest, R.images(cfg, largest)[0])
                nodes, depth = str(rec["bvh"]["nodes"]), str(rec["bvh"]["depth"])
            brows.append([name, fs(tb), fs(tr), fs(tb + tr if tb is not None and tr is not None else None),
                          nodes, depth, "yes" if same else "NO"])
        doc.table(["BVH", "build (s)", "render (s)", "build + render (s)", "nodes", "depth", "identical"], brows)
        data["bvh"] = brows

    def write(self):
        """The gallery and the failures; writes the files; the exit status."""
        R, D, a, doc, data = self.R, self.D, self.a, self.doc, self.data
        t_start = self.t_start
        doc.h(2, "Images")
        doc.p("Our render with culling on and off, the course's reference, and what culling changes (grey: "
              "unchanged; red: darker with culling off; green: brighter).")
        doc.gallery(["image", "culling on", "culling off", "reference", "culling changes"], self.gallery)

        failures = [f"{c} {k}: {msg}" for (c, k), msg in R.failed.items()]
        if failures:
            doc.h(2, "Failures")
            for f in failures:
                doc.p(f)
        data["failures"] = failures
        elapsed = time.perf_counter() - t_start
        doc.p(f"Report made in {elapsed:.0f} s.")
        D.close()

        with open(os.path.join(a.out, "index.md"), "w", encoding="utf-8") as f:
            f.write(doc.markdown())
        with open(os.path.join(a.out, "index.html"), "w", encoding="utf-8") as f:
            f.write(doc.html("Ray tracer report"))
        data["runs_raw"] = {f"{c}|{k}": v for (c, k), v in R.runs.items()}
        with open(os.path.join(a.out, "report.json"), "w", encoding="utf-8") as f:
            json.dump(data, f, indent=1)
        print(doc.markdown().split("## Images")[0])
        log(f"report: {os.path.relpath(os.path.join(a.out, 'index.md'))} (and index.html, chart.svg, report.json) "
            f"in {elapsed:.0f} s" + (f"; {len(failures)} failed runs" if failures else ""))
        return 1 if failures else 0

