"""report.py's chart: render time per image, culling off and on, as an SVG bar chart."""
import html
import math


def svg_chart(rows, title):
    """rows: [(label, t_nocull, t_cull)] -> a grouped horizontal bar chart."""
    e = html.escape
    label_w, bar_w, right = 260, 560, 90
    bar_h, gap, top = 11, 9, 58
    width = label_w + bar_w + right
    height = top + len(rows) * (2 * bar_h + gap) + 40
    tmax = max([0.001] + [max(a or 0, b or 0) for _, a, b in rows])
    # a round step giving 4 to 8 ticks
    raw = tmax / 6
    mag = 10 ** math.floor(math.log10(raw))
    step = next(m * mag for m in (1, 2, 2.5, 5, 10) if raw <= m * mag)
    n = math.ceil(tmax / step - 1e-9)
    ticks = [round(i * step, 10) for i in range(n + 1)]
    axis_max = ticks[-1]
    sx = bar_w / axis_max
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="11">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{width / 2}" y="18" text-anchor="middle" font-size="14">{e(title)}</text>',
           f'<rect x="{label_w}" y="30" width="12" height="10" fill="#8aa1c1"/>'
           f'<text x="{label_w + 16}" y="39">culling off</text>',
           f'<rect x="{label_w + 110}" y="30" width="12" height="10" fill="#e07b39"/>'
           f'<text x="{label_w + 126}" y="39">culling on</text>']
    for t in ticks:
        x = label_w + t * sx
        out.append(f'<line x1="{x:.1f}" y1="{top - 6}" x2="{x:.1f}" y2="{height - 30}" stroke="#e4e4e4"/>')
        out.append(f'<text x="{x:.1f}" y="{height - 16}" text-anchor="middle">{t:g} s</text>')
    y = top
    for label, a, b in rows:
        out.append(f'<text x="{label_w - 6}" y="{y + bar_h + 4}" text-anchor="end">{e(label)}</text>')
        for val, colour, dy in ((a, "#8aa1c1", 0), (b, "#e07b39", bar_h)):
            if val is None:
                continue
            w = max(1.0, val * sx)
            out.append(f'<rect x="{label_w}" y="{y + dy}" width="{w:.1f}" height="{bar_h - 1}" fill="{colour}"/>')
            out.append(f'<text x="{label_w + w + 4:.1f}" y="{y + dy + bar_h - 2}" font-size="9">{val:.3f}</text>')
        y += 2 * bar_h + gap
    out.append(f'<line x1="{label_w}" y1="{top - 6}" x2="{label_w}" y2="{height - 30}" stroke="#444"/>')
    out.append("</svg>")
    return "\n".join(out) + "\n"
