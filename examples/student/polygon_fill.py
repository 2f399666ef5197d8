#!/usr/bin/env python3
"""A polygon filler as the polygon back-ends fill: a pixel is filled when
the winding number of its centre, moved right by an infinitesimal and down
by a smaller one, is one the fill rule fills (a centre on a left or top
edge inside, on a right or bottom edge outside).

It works as the rules do: the vertices snapped to 1/256 px (Python's
`round` rounds a value exactly halfway to even, as `check` does), then, for
each pixel centre, the rings' crossings of the ray to its left, each
decided by one cross product in integers. It passes

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/student/polygon_fill.py {rule}"

and, asked to fill by a rule of its own (`nonzero` in place of `{rule}`),
fails the other with the other fill rule named. Two classic mistakes can
be asked for too: `inclusive` (a centre on any edge filled) and `no-holes`
(the holes ignored).
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "adapters"))
from protocol import run_polygons  # noqa: E402

INCLUSIVE = "inclusive" in sys.argv
NO_HOLES = "no-holes" in sys.argv
sys.argv = [a for a in sys.argv if a not in ("inclusive", "no-holes")]


def snap(v):
    """A coordinate in 1/256 px units, halfway values rounded to even."""
    return round(v * 256)


def winding(rings, px, py):
    """The winding number of (px, py) moved right by e and down by d << e."""
    w = 0
    for ring in rings:
        for a, b in zip(ring, ring[1:] + ring[:1]):
            if (a[1] <= py) == (b[1] <= py):
                continue
            down = b[1] > a[1]
            side = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])
            if (side <= 0) if down else (side >= 0):
                w += 1 if down else -1
    return w


def on_a_ring(rings, px, py):
    for ring in rings:
        for a, b in zip(ring, ring[1:] + ring[:1]):
            cross = (b[0] - a[0]) * (py - a[1]) - (b[1] - a[1]) * (px - a[0])
            if cross == 0 and min(a[0], b[0]) <= px <= max(a[0], b[0]) and min(a[1], b[1]) <= py <= max(a[1], b[1]):
                return True
    return False


def draw(width, height, rings, fill):
    if NO_HOLES:
        rings = rings[:1]
    rings = [[(snap(x), snap(y)) for x, y in ring] for ring in rings]
    xs = [p[0] for r in rings for p in r]
    ys = [p[1] for r in rings for p in r]
    x0, x1 = max(0, (min(xs) - 128) // 256), min(width - 1, (max(xs) - 128) // 256)
    y0, y1 = max(0, (min(ys) - 128) // 256), min(height - 1, (max(ys) - 128) // 256)
    out = []
    for j in range(y0, y1 + 1):
        for i in range(x0, x1 + 1):
            px, py = 256 * i + 128, 256 * j + 128
            if INCLUSIVE and on_a_ring(rings, px, py):
                out.append((i, j))
                continue
            w = winding(rings, px, py)
            if (w % 2 != 0) if fill == "even-odd" else (w != 0):
                out.append((i, j))
    return out


run_polygons(draw)
