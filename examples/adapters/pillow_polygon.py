#!/usr/bin/env python3
"""Pillow's `ImageDraw.polygon`, filled, no outline, given whole polygons,
as a subject of `rasterlab check --kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/pillow_polygon.py {rule}"

Pillow's convention: integer coordinates are pixel centres (pixel (i, j) is
centred on (i, j)), so the screen point (x, y) is Pillow's (x - 0.5,
y - 0.5). `polygon` takes one ring and has no fill rule to choose: a
polygon's holes are joined to its outer ring by an edge there and back
(`protocol.bridged`), and `{rule}` is ignored.
"""

import numpy
from PIL import Image, ImageDraw

from protocol import bridged, run_polygons


def draw(width, height, rings, fill):
    image = Image.new("L", (width, height), 0)
    ring = [(x - 0.5, y - 0.5) for x, y in bridged(rings)]
    ImageDraw.Draw(image).polygon(ring, fill=1)
    return numpy.asarray(image)


run_polygons(draw)
