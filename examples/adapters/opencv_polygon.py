#!/usr/bin/env python3
"""OpenCV's `cv2.fillPoly`, given whole polygons (every ring a contour), as
a subject of `rasterlab check --kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/opencv_polygon.py {rule}"

OpenCV's convention: integer coordinates are pixel centres, vertices are
integers with `shift` fractional bits; the screen point (x, y) is given as
round((x - 0.5) * 256) with shift=8, drawn with `lineType=cv2.LINE_8`.
`fillPoly` has no fill rule to choose: `{rule}` is ignored.

What OpenCV 5.1 does with `shift=8`, measured on hand-made rings (screen
coordinates; the adapter passes the fractional bits, as it should):

- each vertex's y is rounded to a whole pixel row whatever `shift` is
  (the rectangle 1.2..5.8 across and 1.4..5.6, or 1.6..5.4, down fills
  rows 1 to 5 alike; 1.0..6.0 down fills rows 1 to 6, a bottom edge
  through row 6's centres drawn), only the x of the edges between rows
  keeping the fractional bits; so the square 1.2..5.8 fills exactly the
  reference's 25 pixels;
- it draws the outline too, each edge an 8-connected line between the
  vertices rounded to whole pixels in x and y (`CollectPolyEdges` in
  `drawing.cpp`): the triangle 0.8 0.3, 7.9 2.6, 2.2 7.7 on 9x9 fills 33
  pixels where the reference fills 26, the 7 extra all on that outline
  (the corner (0, 0) comes from the vertex 0.8 0.3 rounded to pixel
  (0, 0)).

The fill with y rounded and x kept, plus an outline between vertices
rounded in both, is no change of the reference's vertices or sampling
alone, so `check` names no cause for it.
"""

import cv2
import numpy

from protocol import run_polygons


def draw(width, height, rings, fill):
    mask = numpy.zeros((height, width), numpy.uint8)
    contours = [
        numpy.array([[round((x - 0.5) * 256), round((y - 0.5) * 256)] for x, y in ring], numpy.int32)
        for ring in rings
    ]
    cv2.fillPoly(mask, contours, 1, lineType=cv2.LINE_8, shift=8)
    return mask


run_polygons(draw)
