#!/usr/bin/env python3
"""cairo (through pycairo) filling whole polygons with ANTIALIAS_NONE, by
the fill rule asked for, as a subject of `rasterlab check --kind
polygons`.

    rasterlab check --kind polygons --fill nonzero --persistent --exec "python3 examples/adapters/cairo_polygon.py {rule}"

cairo's convention is the screen's: pixel (i, j) covers [i, i+1) x
[j, j+1), y down; vertices are passed as given, every ring a closed
sub-path, filled with `FILL_RULE_EVEN_ODD` or `FILL_RULE_WINDING` as
`{rule}` says.
"""

import cairo
import numpy

from protocol import run_polygons


def draw(width, height, rings, fill):
    surface = cairo.ImageSurface(cairo.FORMAT_A8, width, height)
    ctx = cairo.Context(surface)
    ctx.set_antialias(cairo.ANTIALIAS_NONE)
    ctx.set_fill_rule(cairo.FILL_RULE_EVEN_ODD if fill == "even-odd" else cairo.FILL_RULE_WINDING)
    for ring in rings:
        ctx.move_to(*ring[0])
        for p in ring[1:]:
            ctx.line_to(*p)
        ctx.close_path()
    ctx.fill()
    surface.flush()
    data = numpy.frombuffer(surface.get_data(), numpy.uint8).reshape(height, surface.get_stride())
    return data[:, :width]


run_polygons(draw)
