"""report.py's document: sections kept once and written both as Markdown (index.md) and as
HTML (index.html)."""
import html
import re


class Doc:
    """Sections rendered both as Markdown and as HTML."""

    def __init__(self):
        self.parts = []

    def h(self, level, text):
        self.parts.append(("h", level, text))

    def p(self, text):
        self.parts.append(("p", text))

    def table(self, header, rows, align=None):
        self.parts.append(("table", header, rows, align or ["l"] + ["r"] * (len(header) - 1)))

    def image(self, src, alt):
        self.parts.append(("img", src, alt))

    def gallery(self, header, rows):
        """rows: [(label, [(src or None, caption)])]"""
        self.parts.append(("gallery", header, rows))

    def markdown(self):
        out = []
        for part in self.parts:
            if part[0] == "h":
                out.append("#" * part[1] + " " + part[2] + "\n")
            elif part[0] == "p":
                out.append(part[1] + "\n")
            elif part[0] == "table":
                _, header, rows, align = part
                out.append("| " + " | ".join(header) + " |")
                out.append("| " + " | ".join("---:" if a == "r" else "---" for a in align) + " |")
                for r in rows:
                    out.append("| " + " | ".join(str(c) for c in r) + " |")
                out.append("")
            elif part[0] == "img":
                out.append(f"![{part[2]}]({part[1]})\n")
            elif part[0] == "gallery":
                _, header, rows = part
                out.append("| " + " | ".join(header) + " |")
                out.append("| " + " | ".join("---" for _ in header) + " |")
                for label, cells in rows:
                    cs = []
                    for src, cap in cells:
                        cs.append(f'<img src="{src}" width="240" alt="{cap}"><br>{cap}' if src else "—")
                    out.append("| " + " | ".join([label] + cs) + " |")
                out.append("")
        return "\n".join(out) + "\n"

    def html(self, title):
        return html_page(title, self.parts)


def html_inline(t):
    """Markdown's `code` and **bold** spans as HTML; everything else escaped."""
    parts = t.split("`")
    return "".join(re.sub(r"\*\*(.+?)\*\*", r"<strong>\1</strong>", html.escape(x)) if i % 2 == 0
                   else "<code>" + html.escape(x) + "</code>" for i, x in enumerate(parts))


def html_page(title, parts):
    """Doc's parts as one HTML page."""
    e = html.escape
    inline = html_inline
    out = [f"<!doctype html><html><head><meta charset='utf-8'><title>{e(title)}</title><style>"
           "body{font-family:sans-serif;margin:2em;max-width:1400px} table{border-collapse:collapse;margin:1em 0}"
           "td,th{border:1px solid #ccc;padding:3px 8px} td.r{text-align:right} img{max-width:100%}"
           "code{background:#f4f4f4}</style></head><body>"]
    for part in parts:
        if part[0] == "h":
            out.append(f"<h{part[1]}>{inline(part[2])}</h{part[1]}>")
        elif part[0] == "p":
            out.append("<p>" + inline(part[1]) + "</p>")
        elif part[0] == "table":
            _, header, rows, align = part
            out.append("<table><tr>" + "".join("<th>" + inline(h) + "</th>" for h in header) + "</tr>")
            for r in rows:
                out.append("<tr>" + "".join(
                    f"<td class='{'r' if a == 'r' else 'l'}'>" + inline(str(c)) + "</td>" for c, a in zip(r, align))
                    + "</tr>")
            out.append("</table>")
        elif part[0] == "img":
            out.append(f"<p><img src='{e(part[1])}' alt='{e(part[2])}'></p>")
        elif part[0] == "gallery":
            _, header, rows = part
            out.append("<table><tr>" + "".join("<th>" + e(h) + "</th>" for h in header) + "</tr>")
            for label, cells in rows:
                cs = "".join(
                    (f"<td><a href='{e(src)}'><img src='{e(src)}' width='320'></a><br>{e(cap)}</td>" if src
                     else "<td>—</td>") for src, cap in cells)
                out.append(f"<tr><td>{inline(label)}</td>{cs}</tr>")
            out.append("</table>")
    out.append("</body></html>")
    return "\n".join(out) + "\n"
