#!/usr/bin/env python3
"""scikit-image's `skimage.draw.polygon`, given whole polygons, as a
subject of `rasterlab check --kind polygons`.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/skimage_polygon.py {rule}"

scikit-image's convention: (row, column) with integer coordinates at pixel
centres, so the screen point (x, y) is row y - 0.5, column x - 0.5.
`polygon` takes one ring and has no fill rule to choose: a polygon's holes
are joined to its outer ring by an edge there and back
(`protocol.bridged`), and `{rule}` is ignored.
"""

from skimage.draw import polygon

from protocol import bridged, run_polygons


def draw(width, height, rings, fill):
    ring = bridged(rings)
    rr, cc = polygon([y - 0.5 for _, y in ring], [x - 0.5 for x, _ in ring], shape=(height, width))
    return zip(cc.tolist(), rr.tolist())


run_polygons(draw)
