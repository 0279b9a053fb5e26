"""bench.py's shared settings: the repository, the generated shapes and their sizes, the
culling settings, and the messages on stderr."""
import os
import sys


REPO = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
DEFAULT_SIZES = ["1M", "4M", "16M"]
# Generated shapes (gen_mesh --shape) and their scene variants; the knot runs at --sizes,
# the others at --shape-sizes.
SHAPES = {"knot": ["plain", "glass", "gold"], "blob": ["plain", "glass"], "terrain": ["plain"],
          "city": ["plain"], "soup": ["plain"]}
DEFAULT_SHAPE_SIZES = ["1M"]
CULL_MODES = ["cull", "no-cull"]  # the flag passed to both programs


def log(msg):
    print(msg, file=sys.stderr, flush=True)


def loud(msg):
    bar = "!" * 78
    log(f"\n{bar}\n!! {msg}\n{bar}\n")
