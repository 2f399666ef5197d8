#!/usr/bin/env python3
"""scikit-image's `skimage.draw.line`, as a subject of `rasterlab check
--kind lines --convention pixel-index`.

    python3 examples/adapters/skimage_line.py {input} {width} {height}

scikit-image's convention: whole-number endpoints naming pixels, given as
(row, column) = (y, x). The input's numbers are pixel indices (whole, under
`--convention pixel-index`), so `x0 y0 x1 y1` is `line(y0, x0, y1, x1)`.

What it draws (measured: every endpoint pair in -1..9 on 12x12, and 25,000
long lines partly off a 16x16 target, all agree): one pixel per step of
the major axis (x when |dx| >= |dy|), both endpoints included, a
zero-length line one pixel; the minor coordinate nearest the line through
the two pixels' centres, a tie going toward the END's minor coordinate
(integer Bresenham walked from the first endpoint, stepping on `d >= 0`).
So `(0,0)-(2,1)` draws (1,1) and `(2,1)-(0,0)` draws (1,0).

`line` does not clip: it returns every pixel, negative ones too (which would
wrap round if used to index an array). The adapter keeps those on the
target, so the drawn pixels are exactly the unclipped line's on the target.
"""

from skimage.draw import line

from protocol import pixel_index, run_lines


def draw(width, height, seg):
    (x0, y0), (x1, y1) = [(pixel_index(x), pixel_index(y)) for x, y in seg]
    rr, cc = line(y0, x0, y1, x1)
    return [(c, r) for r, c in zip(rr.tolist(), cc.tolist())
            if 0 <= c < width and 0 <= r < height]


run_lines(draw)
