#!/usr/bin/env python3
"""scikit-image's `skimage.draw.polygon`, as a subject of `rasterlab check`.

scikit-image's convention: (row, column) with integer coordinates at pixel
centres. So the screen point (x, y) is row y - 0.5, column x - 0.5.
"""

from skimage.draw import polygon

from protocol import run


def draw(width, height, tri):
    rows = [y - 0.5 for _, y in tri]
    cols = [x - 0.5 for x, _ in tri]
    rr, cc = polygon(rows, cols, shape=(height, width))
    return zip(cc.tolist(), rr.tolist())


run(draw)
