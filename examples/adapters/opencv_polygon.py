#!/usr/bin/env python3
"""OpenCV's `cv2.fillPoly`, given whole polygons (every ring a contour), as
a subject of `rasterlab check --kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/opencv_polygon.py {rule}"

OpenCV's convention: integer coordinates are pixel centres, vertices are
integers with `shift` fractional bits; the screen point (x, y) is given as
round((x - 0.5) * 256) with shift=8, drawn with `lineType=cv2.LINE_8`.
`fillPoly` has no fill rule to choose: `{rule}` is ignored.
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
