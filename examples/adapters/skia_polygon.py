#!/usr/bin/env python3
"""Skia (through skia-python) filling whole polygons without
anti-aliasing, by the fill rule asked for, as a subject of `rasterlab
check --kind polygons`.

    rasterlab check --kind polygons --fill nonzero --persistent --exec "python3 examples/adapters/skia_polygon.py {rule}"

Skia's convention is the screen's: pixel (i, j) covers [i, i+1) x
[j, j+1), y down; vertices are passed as given, every ring a closed
contour, the path's fill type `kEvenOdd` or `kWinding` as `{rule}` says.
"""

import numpy
import skia

from protocol import run_polygons


def draw(width, height, rings, fill):
    surface = skia.Surface(width, height)
    canvas = surface.getCanvas()
    canvas.clear(skia.ColorTRANSPARENT)
    path = skia.Path()
    path.setFillType(skia.PathFillType.kEvenOdd if fill == "even-odd" else skia.PathFillType.kWinding)
    for ring in rings:
        path.moveTo(*ring[0])
        for p in ring[1:]:
            path.lineTo(*p)
        path.close()
    canvas.drawPath(path, skia.Paint(Color=skia.ColorWHITE, AntiAlias=False))
    return numpy.asarray(surface.makeImageSnapshot().toarray())[:, :, 3]


run_polygons(draw)
