#!/usr/bin/env python3
"""Pillow's `ImageDraw.polygon`, filled, no outline, as a subject of
`rasterlab check`.

Pillow's convention: integer coordinates are pixel centres (pixel (i, j) is
centred on (i, j)). So the screen point (x, y) is Pillow's (x - 0.5, y - 0.5).
"""

import numpy
from PIL import Image, ImageDraw

from protocol import run


def draw(width, height, tri):
    image = Image.new("L", (width, height), 0)
    ImageDraw.Draw(image).polygon([(x - 0.5, y - 0.5) for x, y in tri], fill=1)
    return numpy.asarray(image)


run(draw)
