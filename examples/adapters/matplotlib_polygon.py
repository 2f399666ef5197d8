#!/usr/bin/env python3
"""matplotlib's `Path.contains_points` at pixel centres, given whole
polygons (every ring a closed sub-path), as a subject of `rasterlab check
--kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/matplotlib_polygon.py {rule}"

The pixel centres (i + 0.5, j + 0.5) are tested against the path in
screen coordinates, as given. `contains_points` has no fill rule to
choose: `{rule}` is ignored.
"""

import numpy
from matplotlib.path import Path

from protocol import run_polygons


def draw(width, height, rings, fill):
    vertices, codes = [], []
    for ring in rings:
        vertices += list(ring) + [ring[0]]
        codes += [Path.MOVETO] + [Path.LINETO] * (len(ring) - 1) + [Path.CLOSEPOLY]
    gx, gy = numpy.meshgrid(numpy.arange(width), numpy.arange(height))
    centres = numpy.column_stack([gx.ravel() + 0.5, gy.ravel() + 0.5])
    inside = Path(vertices, codes).contains_points(centres)
    return zip(gx.ravel()[inside].tolist(), gy.ravel()[inside].tolist())


run_polygons(draw)
