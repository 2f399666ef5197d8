"""The `rasterlab check --exec` protocol, shared by the adapters here.

An adapter is started once per case as

    python3 examples/adapters/LIBRARY.py {input} {width} {height}

`{input}` holds `# size WxH`, then one triangle per line, `x0 y0 x1 y1 x2 y2`
in screen coordinates: pixels, x right, y down, pixel (i, j) covering
[i, i+1) x [j, j+1) with its centre at (i + 0.5, j + 0.5). The adapter prints
one fragment per line, `x y id`, id the triangle's 0-based index.

Each adapter draws one triangle at a time into a mask of the target's size,
so that every fragment is known by its triangle, and maps the library's own
pixel convention to the one above (said at the top of each adapter).

Line adapters (`check --kind lines`, the `*_line.py` here) are the same but
for the input: one segment per line, `x0 y0 x1 y1`, read by `read_lines`
and drawn by `run_lines`, one segment alone at a time. Under `--convention
pixel-index` the numbers are whole and name pixels (`pixel_index` turns
them into ints and refuses any that is not whole); otherwise they are
screen coordinates as above.
"""

import math
import sys


def read_case():
    """(width, height, triangles) from the command line and the input file."""
    path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    triangles = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                v = [float(t) for t in line.split()]
                if len(v) != 6:
                    sys.exit(f"expected six numbers a line, got {len(v)}")
                triangles.append([(v[0], v[1]), (v[2], v[3]), (v[4], v[5])])
    return width, height, triangles


def run(draw):
    """Reads the case, calls `draw(width, height, triangle)` for each
    triangle (it returns the drawn pixels as (x, y) pairs, or a 2D array
    indexed [y][x] that is non-zero where drawn) and prints the fragments."""
    width, height, triangles = read_case()
    out = []
    for t, tri in enumerate(triangles):
        pixels = draw(width, height, tri)
        if hasattr(pixels, "nonzero"):
            ys, xs = pixels.nonzero()
            pixels = zip(xs.tolist(), ys.tolist())
        out.extend(f"{x} {y} {t}" for x, y in pixels)
    sys.stdout.write("\n".join(out) + ("\n" if out else ""))


def read_lines():
    """(width, height, segments) from the command line and the input file,
    each segment ((x0, y0), (x1, y1)) in floats."""
    path, width, height = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
    segments = []
    with open(path) as f:
        for line in f:
            line = line.split("#")[0].strip()
            if line:
                v = [float(t) for t in line.split()]
                if len(v) != 4:
                    sys.exit(f"expected four numbers a line, got {len(v)}")
                segments.append(((v[0], v[1]), (v[2], v[3])))
    return width, height, segments


def pixel_index(v):
    """The pixel index a number names, as an int: the number itself when it
    is whole (the cases of the whole-pixel conventions), else rounded half
    up (`--convention any` also gives screen cases to every subject, which
    a whole-pixel drawer then draws at the nearest pixel indices)."""
    return math.floor(v + 0.5)


def run_lines(draw):
    """Reads the case, calls `draw(width, height, segment)` for each segment
    (it returns the drawn pixels as (x, y) pairs, or a 2D array indexed
    [y][x] that is non-zero where drawn) and prints the fragments, id the
    segment's 0-based index."""
    width, height, segments = read_lines()
    out = []
    for t, seg in enumerate(segments):
        pixels = draw(width, height, seg)
        if hasattr(pixels, "nonzero"):
            ys, xs = pixels.nonzero()
            pixels = zip(xs.tolist(), ys.tolist())
        out.extend(f"{x} {y} {t}" for x, y in pixels)
    sys.stdout.write("\n".join(out) + ("\n" if out else ""))
