#!/usr/bin/env python3
"""cairo (through pycairo) filling a path with ANTIALIAS_NONE, as a subject
of `rasterlab check`.

cairo's convention is the screen's: pixel (i, j) covers [i, i+1) x [j, j+1),
its centre at (i + 0.5, j + 0.5), y down; vertices are passed as given.
"""

import cairo
import numpy

from protocol import run


def draw(width, height, tri):
    surface = cairo.ImageSurface(cairo.FORMAT_A8, width, height)
    ctx = cairo.Context(surface)
    ctx.set_antialias(cairo.ANTIALIAS_NONE)
    ctx.move_to(*tri[0])
    ctx.line_to(*tri[1])
    ctx.line_to(*tri[2])
    ctx.close_path()
    ctx.fill()
    surface.flush()
    stride = surface.get_stride()
    data = numpy.frombuffer(surface.get_data(), numpy.uint8).reshape(height, stride)
    return data[:, :width]


run(draw)
