#!/usr/bin/env python3
"""GDAL's rasterizer given whole polygons, as a subject of `rasterlab
check --kind polygons`: `gdal.RasterizeLayer` on an in-memory layer when
GDAL's own Python bindings (`osgeo`) are installed, else the same
rasterizer (`GDALRasterizeGeometries`) through
`rasterio.features.rasterize`; the first line it writes on standard error
says which.

    rasterlab check --kind polygons --fill even-odd --persistent --exec "python3 examples/adapters/gdal_polygon.py {rule}"

With the identity transform (y down), GDAL's pixel (column i, row j) covers
[i, i+1) x [j, j+1) in the geometry's coordinates: the screen's, so
vertices are passed as given, a polygon's outer ring and its holes as
the polygon's rings. Without `ALL_TOUCHED`, a pixel is burnt when its
centre is inside. GDAL has no fill rule to choose: `{rule}` is ignored.
"""

import sys

import numpy

from protocol import run_polygons

try:
    from osgeo import gdal, ogr

    def draw(width, height, rings, fill):
        ds = gdal.GetDriverByName("MEM").Create("", width, height, 1, gdal.GDT_Byte)
        ds.SetGeoTransform([0, 1, 0, 0, 0, 1])
        source = ogr.GetDriverByName("Memory").CreateDataSource("")
        layer = source.CreateLayer("polygon", geom_type=ogr.wkbPolygon)
        geometry = ogr.Geometry(ogr.wkbPolygon)
        for ring in rings:
            r = ogr.Geometry(ogr.wkbLinearRing)
            for x, y in list(ring) + [ring[0]]:
                r.AddPoint_2D(x, y)
            geometry.AddGeometry(r)
        feature = ogr.Feature(layer.GetLayerDefn())
        feature.SetGeometry(geometry)
        layer.CreateFeature(feature)
        gdal.RasterizeLayer(ds, [1], layer, burn_values=[1])
        return ds.GetRasterBand(1).ReadAsArray()

    sys.stderr.write(f"gdal_polygon: osgeo.gdal.RasterizeLayer, GDAL {gdal.__version__}\n")
except ImportError:
    from affine import Affine
    from rasterio.features import rasterize
    import rasterio

    def draw(width, height, rings, fill):
        polygon = {"type": "Polygon", "coordinates": [list(r) + [r[0]] for r in rings]}
        return rasterize(
            [(polygon, 1)],
            out_shape=(height, width),
            transform=Affine.identity(),
            fill=0,
            dtype=numpy.uint8,
        )

    sys.stderr.write(f"gdal_polygon: rasterio.features.rasterize, GDAL {rasterio.__gdal_version__}\n")

run_polygons(draw)
