#!/usr/bin/env python3
"""Skia (through skia-python) filling a path without anti-aliasing, as a
subject of `rasterlab check`.

Skia's convention is the screen's: pixel (i, j) covers [i, i+1) x [j, j+1),
its centre at (i + 0.5, j + 0.5), y down; vertices are passed as given.
"""

import numpy
import skia

from protocol import run


def draw(width, height, tri):
    surface = skia.Surface(width, height)
    canvas = surface.getCanvas()
    canvas.clear(skia.ColorTRANSPARENT)
    path = skia.Path()
    path.moveTo(*tri[0])
    path.lineTo(*tri[1])
    path.lineTo(*tri[2])
    path.close()
    canvas.drawPath(path, skia.Paint(Color=skia.ColorWHITE, AntiAlias=False))
    pixels = surface.makeImageSnapshot().toarray()
    return numpy.asarray(pixels)[:, :, 3]


run(draw)
