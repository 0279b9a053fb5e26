#!/usr/bin/env python3
"""The folder-level include graph of include/rt/* and src/*: an arrow A -> B when a file of
folder A (include/rt/A/... or src/A/...) includes "rt/B/...". Prints the arrows and fails
(exit 1) on any cycle, naming the files that make each arrow of it.

  tests/tools/include_graph.py [--quiet]     (make check-includes)
"""
import os
import re
import sys

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
INCLUDE = re.compile(r'^\s*#\s*include\s+"rt/([^/"]+)/[^"]+"', re.M)


def folder_of(path):
    """The folder a repository file belongs to: include/rt/X/... and src/X/... are X;
    a file directly under src/ (main.cpp) is "main"."""
    parts = path.split("/")
    if parts[0] == "include":
        return parts[2] if len(parts) > 3 else None
    return parts[1] if len(parts) > 2 else "main"


def graph():
    """{folder: {included folder: [including files]}}, self-arrows left out."""
    arrows = {}
    for top in ("include/rt", "src"):
        for root, _, files in os.walk(os.path.join(REPO, top)):
            for name in sorted(files):
                if not name.endswith((".h", ".cpp")):
                    continue
                rel = os.path.relpath(os.path.join(root, name), REPO)
                src = folder_of(rel)
                if src is None:
                    continue
                arrows.setdefault(src, {})
                with open(os.path.join(REPO, rel), encoding="utf-8") as f:
                    for dst in INCLUDE.findall(f.read()):
                        if dst != src:
                            arrows[src].setdefault(dst, []).append(rel)
    return arrows


def components(arrows):
    """The strongly connected components of more than one folder (Tarjan's)."""
    index, low, stack, on, out = {}, {}, [], set(), []

    def visit(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on.add(v)
        for w in sorted(arrows.get(v, {})):
            if w not in index:
                visit(w)
                low[v] = min(low[v], low[w])
            elif w in on:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            comp = []
            while True:
                w = stack.pop()
                on.discard(w)
                comp.append(w)
                if w == v:
                    break
            if len(comp) > 1:
                out.append(sorted(comp))

    for v in sorted(arrows):
        if v not in index:
            visit(v)
    return out


def main():
    arrows = graph()
    if "--quiet" not in sys.argv:
        for src in sorted(arrows):
            print(f"{src} -> {' '.join(sorted(arrows[src])) or '(none)'}")
    comps = components(arrows)
    for comp in comps:
        print("cycle among: " + " ".join(comp))
        pairs = [f"{a} <-> {b}" for a in comp for b in sorted(arrows[a]) if a < b and a in arrows.get(b, {})]
        if pairs:
            print("  folders that include each other: " + ", ".join(pairs))
        for a in comp:
            for b in sorted(arrows[a]):
                if b in comp:
                    print(f"  {a} -> {b}: {', '.join(sorted(set(arrows[a][b])))}")
    if comps:
        print(f"include_graph: {len(comps)} cycle(s) of folders")
        return 1
    print("include_graph: no cycle of folders")
    return 0


if __name__ == "__main__":
    sys.exit(main())
