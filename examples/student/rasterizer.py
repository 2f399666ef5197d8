#!/usr/bin/env python3
"""A rasterizer as a student might write it for an assignment.

For every pixel of the triangle's bounding box it computes the barycentric
coordinates of the pixel centre in floating point and draws the pixel when
all three are >= 0. The protocol (reading cases, printing `x y id`) is the
Python starter's helper, `examples/starters/python/rasterlab_check.py`:

    rasterlab check --rule watertight --persistent --exec "python3 examples/student/rasterizer.py"

finds what is wrong with it (`--exec "python3 examples/student/rasterizer.py
{input} {width} {height}"` starts it once per case instead).
"""

import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "starters", "python"))
from rasterlab_check import run  # noqa: E402


def edge(a, b, p):
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


def rasterize_triangle(a, b, c, width, height):
    area = edge(a, b, c)
    if area == 0:
        return []
    xmin = max(0, math.floor(min(a[0], b[0], c[0])))
    xmax = min(width - 1, math.ceil(max(a[0], b[0], c[0])))
    ymin = max(0, math.floor(min(a[1], b[1], c[1])))
    ymax = min(height - 1, math.ceil(max(a[1], b[1], c[1])))
    fragments = []
    for y in range(ymin, ymax + 1):
        for x in range(xmin, xmax + 1):
            p = (x + 0.5, y + 0.5)
            w0 = edge(b, c, p) / area
            w1 = edge(c, a, p) / area
            w2 = edge(a, b, p) / area
            if w0 >= 0 and w1 >= 0 and w2 >= 0:
                fragments.append((x, y))
    return fragments


if __name__ == "__main__":
    run(rasterize_triangle)
