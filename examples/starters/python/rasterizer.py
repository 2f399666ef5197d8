#!/usr/bin/env python3
"""Your rasterizer: write `rasterize_triangle` (and `rasterize_segment`).

Check it, from the folder of this file:

    rasterlab check --persistent --exec "python3 rasterizer.py"
    rasterlab check --kind lines --convention pixel-index-left-to-right \
        --persistent --exec "python3 rasterizer.py"

As shipped, `rasterize_triangle` is the course's rasterisation
pseudocode: every pixel of the target, drawn when the barycentric
coordinates of its centre are all between 0 and 1; `rasterize_segment`
is the direct evaluation of y = m x + b. Run the check: it says what the
rules want instead, and why this is not it.
"""

import math

from rasterlab_check import run


def implicit_line(a, b, p):
    """The implicit line equation of the line through a and b, at p:
    zero on the line, positive on one side, negative on the other."""
    return (a[1] - b[1]) * p[0] + (b[0] - a[0]) * p[1] + a[0] * b[1] - b[0] * a[1]


def rasterize_triangle(a, b, c, width, height):
    """The pixels (x, y) of the target whose centre is inside triangle abc.

    How check judges it: it snaps every vertex to 1/256 px first (a
    coordinate exactly halfway between two steps rounded to even, as
    Python's round(v * 256) / 256 does), then decides each pixel centre
    with integer edge functions, and a centre exactly on an edge by the
    fill rule (--rule, top-left by default). To agree bit for bit, snap the
    same way and compute in integers; floating point on the vertices as
    given differs on a few cases (the ties family, whose vertices lie
    exactly halfway). Under --snap none check snaps nothing and judges the
    vertices as given, exactly; its coordinates are then multiples of
    1/256 px, where floats are exact."""
    f_bc_a = implicit_line(b, c, a)
    f_ca_b = implicit_line(c, a, b)
    f_ab_c = implicit_line(a, b, c)
    if f_bc_a == 0:  # no area: no barycentric coordinates
        return []
    fragments = []
    for y in range(height):
        for x in range(width):
            p = (x + 0.5, y + 0.5)
            alpha = implicit_line(b, c, p) / f_bc_a
            beta = implicit_line(c, a, p) / f_ca_b
            gamma = implicit_line(a, b, p) / f_ab_c
            if 0 <= alpha <= 1 and 0 <= beta <= 1 and 0 <= gamma <= 1:
                fragments.append((x, y))
    return fragments


def rasterize_segment(p0, p1, width, height):
    """The pixels (x, y) of the line from pixel p0 to pixel p1 (whole
    numbers naming pixels): direct evaluation of y = m x + b in every
    column from the left end to the right end, the row nearest the line,
    a row exactly halfway going to the left end's side."""
    (x0, y0), (x1, y1) = sorted([(round(p0[0]), round(p0[1])), (round(p1[0]), round(p1[1]))])
    if x0 == x1:  # vertical: no slope, every row between the ends
        return [(x0, y) for y in range(y0, y1 + 1) if 0 <= x0 < width and 0 <= y < height]
    m = (y1 - y0) / (x1 - x0)
    b = y0 - m * x0
    fragments = []
    for x in range(x0, x1 + 1):
        y = m * x + b
        row = math.ceil(y - 0.5) if m >= 0 else math.floor(y + 0.5)
        if 0 <= x < width and 0 <= row < height:
            fragments.append((x, row))
    return fragments


if __name__ == "__main__":
    run(rasterize_triangle, rasterize_segment)
