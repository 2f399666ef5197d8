#!/usr/bin/env python3
"""Pillow's `ImageDraw.line` (width 1), as a subject of `rasterlab check
--kind lines --convention pixel-index`.

    python3 examples/adapters/pillow_line.py {input} {width} {height}

Pillow's convention: integer coordinates are pixel centres, so a whole
number names a pixel (non-whole ones Pillow truncates toward zero). The
input's numbers are pixel indices (whole, under `--convention
pixel-index`), given to Pillow as they are: `line([(x0, y0), (x1, y1)])`.

What it draws (measured: every endpoint pair in -1..9 on 12x12, and 25,000
long lines partly off a 16x16 target, modes "L" and "1" alike, all agree):
one pixel per step of the major axis (x when |dx| >= |dy|), both endpoints
included, a zero-length line one pixel; the minor coordinate nearest the
line through the two pixels' centres, a tie going toward the END's minor
coordinate (`Draw.c`'s `line8`: Bresenham walked from the first endpoint,
stepping on `e >= 0`, the last pixel left out and drawn after it as a
point). So `(0,0)-(2,1)` draws (1,1) and `(2,1)-(0,0)` draws (1,0), the same
pixels as scikit-image's `line`.

Clipping is per pixel (each pixel is tested against the image), so the
drawn pixels are exactly the unclipped line's on the target.
"""

import numpy
from PIL import Image, ImageDraw

from protocol import pixel_index, run_lines


def draw(width, height, seg):
    ends = [(pixel_index(x), pixel_index(y)) for x, y in seg]
    image = Image.new("L", (width, height), 0)
    ImageDraw.Draw(image).line(ends, fill=1, width=1)
    return numpy.asarray(image)


run_lines(draw)
