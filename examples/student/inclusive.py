#!/usr/bin/env python3
"""A rasterizer of the inclusive rule, as CS184 and CS248 ask for it: a
pixel is drawn when its centre lies inside the triangle or on any of its
edges.

It works as the rules do: the vertices snapped to 1/256 px (Python's
`round` rounds a value exactly halfway to even, as `check` does), then
three edge functions in integers, so that a centre on an edge is decided
exactly. It passes

    rasterlab check --rule inclusive --persistent --exec "python3 examples/student/inclusive.py"

and fails `--rule top-left` (the default), with the inclusive rule named.
"""

import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "starters", "python"))
from rasterlab_check import run  # noqa: E402


def snap(v):
    """A coordinate in 1/256 px units, halfway values rounded to even."""
    return round(v * 256)


def edge(a, b, p):
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


def rasterize_triangle(a, b, c, width, height):
    a, b, c = [(snap(x), snap(y)) for x, y in (a, b, c)]
    area = edge(a, b, c)
    if area == 0:
        return []
    sign = 1 if area > 0 else -1
    xs, ys = [a[0], b[0], c[0]], [a[1], b[1], c[1]]
    fragments = []
    for y in range(max(0, min(ys) // 256 - 1), min(height, max(ys) // 256 + 1)):
        for x in range(max(0, min(xs) // 256 - 1), min(width, max(xs) // 256 + 1)):
            p = (x * 256 + 128, y * 256 + 128)
            if all(sign * edge(u, v, p) >= 0 for u, v in ((a, b), (b, c), (c, a))):
                fragments.append((x, y))
    return fragments


if __name__ == "__main__":
    run(rasterize_triangle)
