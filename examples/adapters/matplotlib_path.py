#!/usr/bin/env python3
"""matplotlib's `Path.contains_points`, as a subject of `rasterlab check`.

matplotlib tests points against a path in whatever coordinates the path is
given in; the pixel centres (i + 0.5, j + 0.5) of the box around the
triangle are tested against the triangle in screen coordinates, as given.
"""

import math

import numpy
from matplotlib.path import Path

from protocol import run


def draw(width, height, tri):
    xs = [x for x, _ in tri]
    ys = [y for _, y in tri]
    x0, x1 = max(0, math.floor(min(xs))), min(width - 1, math.ceil(max(xs)))
    y0, y1 = max(0, math.floor(min(ys))), min(height - 1, math.ceil(max(ys)))
    if x0 > x1 or y0 > y1:
        return []
    gx, gy = numpy.meshgrid(numpy.arange(x0, x1 + 1), numpy.arange(y0, y1 + 1))
    centres = numpy.column_stack([gx.ravel() + 0.5, gy.ravel() + 0.5])
    inside = Path(tri + [tri[0]], closed=True).contains_points(centres)
    return zip(gx.ravel()[inside].tolist(), gy.ravel()[inside].tolist())


run(draw)
