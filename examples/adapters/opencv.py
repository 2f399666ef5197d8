#!/usr/bin/env python3
"""OpenCV's `cv2.fillPoly`, as a subject of `rasterlab check`.

    python3 examples/adapters/opencv.py {input} {width} {height}          # shift=8
    python3 examples/adapters/opencv.py {input} {width} {height} noshift  # whole pixels

OpenCV's convention: integer coordinates are pixel centres; vertices are
integers, with `shift` fractional bits. So the screen point (x, y) is
OpenCV's (x - 0.5, y - 0.5), given as round((x - 0.5) * 256) with shift=8,
or rounded to whole pixels without it. Drawn with `lineType=cv2.LINE_8`
(aliased).
"""

import sys

import cv2
import numpy

from protocol import run

SHIFT = 0 if "noshift" in sys.argv else 8
sys.argv = [a for a in sys.argv if a != "noshift"]


def draw(width, height, tri):
    mask = numpy.zeros((height, width), numpy.uint8)
    scale = 1 << SHIFT
    points = numpy.array(
        [[round((x - 0.5) * scale), round((y - 0.5) * scale)] for x, y in tri],
        numpy.int32,
    )
    cv2.fillPoly(mask, [points], 1, lineType=cv2.LINE_8, shift=SHIFT)
    return mask


run(draw)
