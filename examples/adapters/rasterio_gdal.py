#!/usr/bin/env python3
"""GDAL's rasterizer through `rasterio.features.rasterize`, as a subject of
`rasterlab check`.

With the identity transform, GDAL's pixel (column i, row j) covers
[i, i+1) x [j, j+1) in the geometry's coordinates, rows going down: the
screen's convention, so vertices are passed as given. Without
`all_touched`, a pixel is burnt when its centre is inside the polygon.
"""

import numpy
from affine import Affine
from rasterio.features import rasterize

from protocol import run


def draw(width, height, tri):
    polygon = {"type": "Polygon", "coordinates": [tri + [tri[0]]]}
    return rasterize(
        [(polygon, 1)],
        out_shape=(height, width),
        transform=Affine.identity(),
        fill=0,
        dtype=numpy.uint8,
    )


run(draw)
