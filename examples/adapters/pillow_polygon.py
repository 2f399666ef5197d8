#!/usr/bin/env python3
"""Pillow's `ImageDraw.polygon`, filled, no outline, given whole polygons,
as a subject of `rasterlab check --kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/pillow_polygon.py {rule}"

Pillow's convention: integer coordinates are pixel centres (pixel (i, j) is
centred on (i, j)), so the screen point (x, y) is Pillow's (x - 0.5,
y - 0.5). `polygon` takes one ring and has no fill rule to choose: a
polygon's holes are joined to its outer ring by an edge there and back
(`protocol.bridged`), and `{rule}` is ignored.

What Pillow 13 does, measured on hand-made rings (screen coordinates):

- it draws on whole pixels only: its C layer casts each coordinate to
  `int`, truncating toward zero, so a ring passed in floats moves up and
  left by up to a pixel (the square 1.2..5.8, passed as 0.7..5.3, fills
  columns and rows 0 to 5, as the square 0..5 does; the reference fills
  1 to 5). This adapter therefore rounds each vertex to the nearest pixel
  centre itself (Python's `round`, half to even), as a caller with screen
  coordinates would; the square then fills 1 to 5;
- `fill` alone draws no outline (`outline=None`): asked for one in
  another colour, 391 of 500 random whole-pixel triangles on 14x14 gain
  pixels, so the pixels below are the fill's own;
- it fills each pixel row y (through the pixel centres) from the left
  edge's x rounded half up to the right edge's x rounded half down: a
  pixel whose centre lies up to half a pixel outside a slanted edge is
  filled, so the closed polygon of the rounded vertices (every centre on
  an edge inside) is filled and more (the triangle 0.5 0.5, 7.5 2.5,
  2.5 7.5 on 9x9 fills 30 pixels, where the closed polygon holds 27 and
  the reference 20, the 3 beyond the closed polygon beside its slanted
  edges). On whole-pixel triangles that model (pixel i of row y filled
  when the span [left x, right x] of the row meets the open interval
  (i - 0.5, i + 0.5)) gives exactly Pillow's pixels on 446 of 491 random
  ones on 14x14; on the others Pillow adds a few pixels on a vertex's
  row (it joins the two edges meeting there). A horizontal edge is drawn
  whole, and a zero-width sliver (such as the bridge to a hole) draws
  the pixel nearest to it on each row. No sampling convention of the
  reference draws that, so `check` names no cause for it.
"""

import numpy
from PIL import Image, ImageDraw

from protocol import bridged, run_polygons


def draw(width, height, rings, fill):
    image = Image.new("L", (width, height), 0)
    ring = [(round(x - 0.5), round(y - 0.5)) for x, y in bridged(rings)]
    ImageDraw.Draw(image).polygon(ring, fill=1)
    return numpy.asarray(image)


run_polygons(draw)
