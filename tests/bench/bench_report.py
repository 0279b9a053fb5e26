"""bench.py's report: the Markdown tables and totals of the results (build/bench/bench.md)."""
from bench_common import CULL_MODES


def fmt_s(x, digits=3):
    return "n/a" if x is None else f"{x:.{digits}f}"


def fmt_mb(b):
    if b is None:
        return "n/a"
    return f"{b / 2**20:.1f}" if b < 100 * 2**20 else f"{b / 2**20:.0f}"


def table(header, rows, align):
    widths = [max(len(str(r[i])) for r in [header] + rows) for i in range(len(header))]

    def line(cells):
        out = []
        for c, w, al in zip(cells, widths, align):
            out.append(str(c).rjust(w) if al == "r" else str(c).ljust(w))
        return "| " + " | ".join(out) + " |"

    sep = "| " + " | ".join(("-" * (w - 1) + ":") if al == "r" else "-" * w for w, al in zip(widths, align)) + " |"
    return "\n".join([line(header), sep] + [line(r) for r in rows])


def label(r):
    """A result's scene name with its culling setting when that is not the default."""
    return r["name"] + ("" if r["cull"] == "cull" else " no-cull")


def render_ratio(r):
    """Our render phase over refrender's (medians), or None."""
    p, rp = r["phases"] or {}, r["ref_phases"] or {}
    ren, rren = p.get("render"), rp.get("render")
    return ren / rren if ren is not None and rren else None


def fmt_ratio(x):
    return "n/a" if x is None else f"{x:.2f}"


def report(results, meta):
    out = []
    m = meta["machine"]
    modes = [c for c in CULL_MODES if any(r["cull"] == c for r in results)]
    out.append("# raytracer benchmark")
    out.append("")
    out.append(f"- date: {meta['date']} (took {meta['elapsed'] / 60:.1f} min)")
    out.append(f"- machine: {m['cpu']}, {m['cores']} cores ({m['usable_cores']} usable), "
               f"{(m['memory_bytes'] or 0) / 2**30:.1f} GiB; load average {meta['loadavg_start']} at start, "
               f"{meta['loadavg_end']} at end")
    out.append(f"- threads: {m['threads']} for both; runs: {meta['runs']} timed runs each after one warm-up, "
               f"alternating (heavy scenes, marked *: at most {meta['heavy_runs']})")
    out.append("- culling: every scene with " + " and with ".join(f"`--{c}`" for c in modes)
               + " on both sides (rows marked no-cull are the latter)")
    out.append(f"- ours: {meta['raytracer']} --precision {meta['precision']} (git {meta['git']}, "
               f"sha256 {meta['raytracer_sha256'][:12]})")
    if meta["refrender_problem"]:
        out.append(f"- **refrender could not run: {meta['refrender_problem']}; our times only**")
    else:
        out.append(f"- yardstick: {meta['refrender']}")
    out.append("")
    header = ["scene", "triangles", "ours s", "ref s", "ours/ref", "load", "bvh", "render", "write",
              "ours MiB", "ref MiB"]
    align = ["l", "r", "r", "r", "r", "r", "r", "r", "r", "r", "r"]
    rows = []
    for r in results:
        p = r["phases"] or {}
        name = label(r) + (" *" if r.get("heavy") else "")
        ours = fmt_s(r["ours_median"]) if r["ours_ok"] else "FAILED"
        ref = fmt_s(r["ref_median"]) if r["ref_ok"] else ("FAILED" if r["ref_cmd"] else "n/a")
        ratio = "n/a" if r["ratio"] is None else f"{r['ratio']:.2f}" + (" !" if r["ratio"] > 1.5 else "")
        rows.append([name, p.get("triangles", "?"), ours, ref, ratio, fmt_s(p.get("load")), fmt_s(p.get("bvh")),
                     fmt_s(p.get("render")), fmt_s(p.get("write")), fmt_mb(r["ours_maxrss"]),
                     fmt_mb(r["ref_maxrss"])])
    out.append(table(header, rows, align))
    out.append("")
    out.append("Times are medians of whole-process wall time (seconds); load/bvh/render/write is our "
               "own phase split (median of non-quiet runs); MiB is peak RSS (max over runs; readings "
               f"include a floor of {meta['rss_floor'] / 2**20:.1f} MiB, the process launcher's). "
               "`!` marks ours slower than 1.5x refrender; `*` a heavy scene.")

    for mode in modes:
        both = [r for r in results if r["cull"] == mode and r["ours_median"] is not None
                and r["ref_median"] is not None]
        mine = [r for r in results if r["cull"] == mode]
        out.append("")
        out.append(f"### `--{mode}`")
        out.append("")
        s_ours = sum(r["ours_median"] for r in both)
        s_ref = sum(r["ref_median"] for r in both)
        if both:
            out.append(f"**Total** over the {len(both)} scenes both finished: ours {s_ours:.2f} s, "
                       f"refrender {s_ref:.2f} s, ratio {s_ours / s_ref:.2f}.")
        else:
            s_all = sum(r["ours_median"] for r in mine if r["ours_median"] is not None)
            out.append(f"**Total** (ours only): {s_all:.2f} s.")
        official = [r for r in both if r["kind"] != "large"]
        if official and len(official) < len(both):
            o_ours = sum(r["ours_median"] for r in official)
            o_ref = sum(r["ref_median"] for r in official)
            out.append("")
            out.append(f"**Official scenes** ({len(official)} files): ours {o_ours:.3f} s, refrender {o_ref:.3f} s, "
                       f"ratio {o_ours / o_ref:.2f}.")
        slow = [r["name"] for r in both if r["ratio"] > 1.5]
        out.append("")
        out.append(f"**Ours slower than 1.5x refrender on {len(slow)} of {len(both)} scenes**"
                   + (": " + ", ".join(slow) if slow else "."))
        rr = [(r["name"], render_ratio(r)) for r in mine if render_ratio(r) is not None]
        if rr:
            over = [f"{n} {x:.2f}" for n, x in rr if x > 1.0]
            out.append("")
            out.append(f"**Render phase at most refrender's on {len(rr) - len(over)} of {len(rr)} scenes**"
                       + (" (over: " + ", ".join(over) + ")" if over else "."))

    failed = [r for r in results if not r["ours_ok"]]
    if failed:
        out.append("")
        out.append(f"**raytracer failed on {len(failed)} run(s):**")
        for r in failed:
            out.append(f"- {label(r)}: {r.get('ours_error', '?')} (`{r['ours_cmd']}`)")
    ref_failed = [r for r in results if r["ref_cmd"] and not r["ref_ok"]]
    if ref_failed:
        out.append("")
        out.append("refrender failed on: " + ", ".join(f"{label(r)} ({r.get('ref_error', '?')})" for r in ref_failed))

    # Render phase side by side, both culling settings, one row per scene.
    names = list(dict.fromkeys(r["name"] for r in results))
    by = {(r["name"], r["cull"]): r for r in results}
    if names:
        out.append("")
        out.append("## Render phase: ours / refrender, both culling settings")
        out.append("")
        header = ["scene", "triangles"]
        for mode in modes:
            header += [f"ours {mode} s", f"ref {mode} s", f"{mode} ratio"]
        rows = []
        for n in names:
            rs = [by.get((n, mode)) for mode in modes]
            tris = next(((x["phases"] or {}).get("triangles") for x in rs if x and x["phases"]), None)
            row = [n, tris or "?"]
            for x in rs:
                p, rp = ((x or {}).get("phases") or {}), ((x or {}).get("ref_phases") or {})
                rat = render_ratio(x) if x else None
                row += [fmt_s(p.get("render")), fmt_s(rp.get("render")),
                        fmt_ratio(rat) + (" >" if rat is not None and rat > 1.0 else "")]
            rows.append(row)
        out.append(table(header, rows, ["l"] + ["r"] * (len(header) - 1)))
        out.append("")
        out.append("Render: the render phase alone, summed over a scene's images (ours: median of our phase "
                   "split; refrender: median of its own render= figures). `>` marks ours slower than refrender.")

    large = [r for r in results if r["kind"] == "large"]
    if large:
        out.append("")
        out.append("## Large scenes: build cost and memory")
        out.append("")
        header = ["scene", "triangles", "ours load+bvh s", "ref parse+bvh s", "ours render s", "ref render s",
                  "render ratio", "ours B/tri", "ref B/tri"]
        rows = []
        for r in large:
            p = r["phases"] or {}
            rp = r["ref_phases"] or {}
            tris = p.get("triangles")
            lb = p["load"] + p["bvh"] if p else None
            rlb = rp["parse"] + rp["bvh"] if rp else None
            bpt = lambda rss: "n/a" if rss is None or not tris else f"{rss / tris:.0f}"
            rows.append([label(r), tris or "?", fmt_s(lb, 2), fmt_s(rlb, 2), fmt_s(p.get("render")),
                         fmt_s(rp.get("render")), fmt_ratio(render_ratio(r)), bpt(r["ours_maxrss"]),
                         bpt(r["ref_maxrss"])])
        out.append(table(header, rows, ["l", "r", "r", "r", "r", "r", "r", "r", "r"]))
        out.append("")
        out.append("Render: the render phase alone (ours: median of our phase split; refrender: median of "
                   "its own render= figures). B/tri: peak RSS of the whole process over the scene's "
                   "triangle count (ours' count, which includes the 2 ground triangles).")
    notes = {}
    for r in results:
        for n in r["notes"]:
            notes.setdefault(n, []).append(label(r))
    if notes:
        out.append("")
        for n, names_ in notes.items():
            out.append(f"- {n}: {', '.join(names_)}")
    return "\n".join(out) + "\n"
