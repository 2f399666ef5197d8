#!/usr/bin/env python3
"""OpenCV's `cv2.line` (thickness 1, aliased), as a subject of `rasterlab
check --kind lines`.

    python3 examples/adapters/opencv_line.py {input} {width} {height} [--line-type 8|4] [--shift N]

`--line-type` is `cv2.LINE_8` (default) or `cv2.LINE_4`; `--shift N` gives
the endpoints N fractional bits (default 0: whole pixels).

OpenCV's convention: integer coordinates are pixel centres (pixel (i, j) is
centred on (i, j)), with `shift` fractional bits when it is given.

- No shift (`--convention pixel-index`): the input's numbers are pixel
  indices, given to OpenCV as they are.
- `--shift N`: the input's numbers are screen coordinates, and the screen
  point (x, y) is OpenCV's (x - 0.5, y - 0.5), given as round((x - 0.5) * 2^N).

What OpenCV 5.1.0 draws (measured against ports of `drawing.cpp`, all
cases agreeing, on every pair of endpoints in -1..9 on a 12x12 image and on
25,000 long lines partly off a 16x16 one):

- Whole pixels, both line types: if an endpoint lies off the image,
  `clipLine` first moves it onto the image's edge (the new coordinate
  truncated toward zero), and the line is drawn between the moved
  endpoints: the visible pixels are not always the unclipped line's (they
  differed on 30% of long random lines partly off a 16x16 target). Then
  the walk goes from the endpoint with the smaller x (left to right, for
  y-major lines too), major axis x when |dx| >= |dy|, both endpoints
  drawn, a zero-length line one pixel.
  - LINE_8: one pixel per major step, the minor coordinate nearest the
    line through the pixels' centres, a tie keeping the minor coordinate
    of the left endpoint (so a y-major tie takes the smaller x):
    `(0,0)-(2,1)` and `(2,1)-(0,0)` both draw (1,0).
  - LINE_4: 4-connected, dx + dy + 1 pixels; err = 0, then per step: if
    err >= 0, a major step and err -= 2|d_minor|, else a minor step and
    err += 2|d_major|. A diagonal move takes the major-axis neighbour first
    (x-major: (x+1, y) then (x+1, y+1)). `(0,0)-(2,1)` draws (0,0) (1,0)
    (1,1) (2,1).
- With shift, LINE_8: each endpoint rounded to the nearest whole pixel
  (half up: the pixel containing the snapped screen point), then the
  whole-pixel LINE_8 above, clipping included.
- With shift, LINE_4: OpenCV's `Line2`, a 16.16 fixed-point DDA, and it is
  8-connected (5.1.0 routes LINE_8 to the whole-pixel line and LINE_4 to
  `Line2`): after a clip to OpenCV's [0, W) x [0, H) (screen
  [0.5, W + 0.5)), the major axis is x when |dx| > |dy| (a diagonal is
  y-major), the walk goes toward increasing major coordinate, and for
  k = 0 .. floor(|d_major|) the pixel containing the point start + k *
  (1, slope) is drawn (slope truncated to 1/65536 px), then the pixel
  containing the end point: samples at whole steps from the start, not at
  pixel centres, and in 13% of lines two pixels in the last column.
"""

import argparse
import sys

import cv2
import numpy

from protocol import pixel_index, run_lines

parser = argparse.ArgumentParser()
parser.add_argument("case", nargs="*", help="{input} {width} {height}; none: --persistent")
parser.add_argument("--line-type", type=int, choices=[8, 4], default=8)
parser.add_argument("--shift", type=int, default=0, choices=range(0, 17), metavar="N")
args = parser.parse_args()
sys.argv[1:] = args.case
LINE_TYPE = cv2.LINE_8 if args.line_type == 8 else cv2.LINE_4
SHIFT = args.shift


def point(x, y):
    if SHIFT == 0:
        return pixel_index(x), pixel_index(y)
    scale = 1 << SHIFT
    return round((x - 0.5) * scale), round((y - 0.5) * scale)


def draw(width, height, seg):
    mask = numpy.zeros((height, width), numpy.uint8)
    (p0, p1) = [point(x, y) for x, y in seg]
    cv2.line(mask, p0, p1, 1, thickness=1, lineType=LINE_TYPE, shift=SHIFT)
    return mask


run_lines(draw)
