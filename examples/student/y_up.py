#!/usr/bin/env python3
"""A rasterizer whose y grows up, as in Scotty3D and OpenGL's window
coordinates: the origin at the lower left corner, row 0 at the bottom.

It follows the top-left rule as its own picture shows it: a centre on an
edge is drawn when the edge is a top edge (horizontal, the triangle below
it, so at smaller y) or a left edge (the triangle on its right). The
vertices are snapped to 1/256 px (halfway to even), the edge functions
are integers. Checked with its y direction said, it passes:

    rasterlab check --origin bottom-left --persistent --exec "python3 examples/student/y_up.py"

Without `--origin bottom-left` it is read as y down, so what it calls
top is the bottom of the picture: the check names the y flip.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "starters", "python"))
from rasterlab_check import run  # noqa: E402


def snap(v):
    """A coordinate in 1/256 px units, halfway values rounded to even."""
    return round(v * 256)


def edge(a, b, p):
    """Positive when p lies to the left of a -> b (y up)."""
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


def owns_ties(a, b):
    """Whether edge a -> b of a counter-clockwise triangle (y up) is a top
    edge (horizontal, going left: the triangle below it) or a left edge
    (going down: the triangle on its right)."""
    if a[1] == b[1]:
        return b[0] < a[0]
    return b[1] < a[1]


def rasterize_triangle(a, b, c, width, height):
    a, b, c = [(snap(x), snap(y)) for x, y in (a, b, c)]
    area = edge(a, b, c)
    if area == 0:
        return []
    if area < 0:  # made counter-clockwise
        b, c = c, b
    xs, ys = [a[0], b[0], c[0]], [a[1], b[1], c[1]]
    edges = [(a, b), (b, c), (c, a)]
    fragments = []
    for y in range(max(0, min(ys) // 256 - 1), min(height, max(ys) // 256 + 1)):
        for x in range(max(0, min(xs) // 256 - 1), min(width, max(xs) // 256 + 1)):
            p = (x * 256 + 128, y * 256 + 128)
            values = [edge(u, v, p) for u, v in edges]
            if all(e > 0 or (e == 0 and owns_ties(u, v)) for e, (u, v) in zip(values, edges)):
                fragments.append((x, y))
    return fragments


if __name__ == "__main__":
    run(rasterize_triangle)
