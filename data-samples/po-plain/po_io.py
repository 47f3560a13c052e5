"""GDAL/OGR writers with deterministic output (no timestamps, no .aux.xml side files)."""

import math
import os

import numpy as np
from osgeo import gdal, ogr, osr

gdal.UseExceptions()
ogr.UseExceptions()
osr.UseExceptions()
gdal.SetConfigOption("GDAL_PAM_ENABLED", "NO")       # never write .aux.xml files


def srs_of(epsg):
    s = osr.SpatialReference()
    s.ImportFromEPSG(epsg)
    s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    return s


class Grid:
    """North-up raster grid: x0, y0 = top-left corner, nx x ny square cells of size `cell`."""

    def __init__(self, domain, cell, margin_cells=1):
        xmin, ymin, xmax, ymax = domain
        self.cell = float(cell)
        self.x0 = xmin - margin_cells * cell
        self.y0 = ymax + margin_cells * cell
        self.nx = int(round((xmax - xmin) / cell)) + 2 * margin_cells
        self.ny = int(round((ymax - ymin) / cell)) + 2 * margin_cells

    def centres(self):
        xs = self.x0 + (np.arange(self.nx) + 0.5) * self.cell
        ys = self.y0 - (np.arange(self.ny) + 0.5) * self.cell
        return np.meshgrid(xs, ys)

    def geotransform(self):
        return (self.x0, self.cell, 0.0, self.y0, 0.0, -self.cell)


def bilinear(arr, gt, x, y):
    """GDAL-convention bilinear interpolation (pixel centres at (i + 0.5) cells)."""
    fx = (x - gt[0]) / gt[1] - 0.5
    fy = (y - gt[3]) / gt[5] - 0.5
    j0 = int(math.floor(fx))
    i0 = int(math.floor(fy))
    tx, ty = fx - j0, fy - i0
    a = arr[i0:i0 + 2, j0:j0 + 2].astype(float)
    return float((1 - ty) * ((1 - tx) * a[0, 0] + tx * a[0, 1]) + ty * ((1 - tx) * a[1, 0] + tx * a[1, 1]))


def bilinear_cells(gt, x, y):
    """The four (row, col) cells that bilinear interpolation at (x, y) uses."""
    fx = (x - gt[0]) / gt[1] - 0.5
    fy = (y - gt[3]) / gt[5] - 0.5
    j0 = int(math.floor(fx))
    i0 = int(math.floor(fy))
    return [(i0, j0), (i0, j0 + 1), (i0 + 1, j0), (i0 + 1, j0 + 1)]


def write_geotiff(path, arr, grid, epsg, description, metadata):
    drv = gdal.GetDriverByName("GTiff")
    opts = ["COMPRESS=DEFLATE", "PREDICTOR=3", "ZLEVEL=9", "INTERLEAVE=BAND"]
    ds = drv.Create(path, grid.nx, grid.ny, 1, gdal.GDT_Float32, options=opts)
    ds.SetGeoTransform(grid.geotransform())
    ds.SetProjection(srs_of(epsg).ExportToWkt())
    ds.SetMetadata({k: str(v) for k, v in sorted(metadata.items())})
    band = ds.GetRasterBand(1)
    band.SetDescription(description)
    band.SetUnitType("m")
    band.WriteArray(np.asarray(arr, dtype=np.float32))
    band.FlushCache()
    ds.FlushCache()
    band = None
    ds = None


_OFT = {"str": ogr.OFTString, "int": ogr.OFTInteger, "real": ogr.OFTReal}


def write_geojson(path, layer_name, epsg, geom_type, fields, features):
    """fields: [(name, 'str'|'int'|'real')]; features: [(attrs dict, ogr.Geometry)]."""
    if os.path.exists(path):
        os.remove(path)
    drv = ogr.GetDriverByName("GeoJSON")
    ds = drv.CreateDataSource(path)
    lyr = ds.CreateLayer(layer_name, srs=srs_of(epsg), geom_type=geom_type,
                         options=["RFC7946=NO", "COORDINATE_PRECISION=2", "WRITE_BBOX=NO"])
    for name, kind in fields:
        fd = ogr.FieldDefn(name, _OFT[kind])
        lyr.CreateField(fd)
    defn = lyr.GetLayerDefn()
    for attrs, geom in features:
        feat = ogr.Feature(defn)
        for name, kind in fields:
            v = attrs[name]
            if kind == "real":
                v = float(v)
            elif kind == "int":
                v = int(v)
            feat.SetField(name, v)
        feat.SetGeometry(geom)
        lyr.CreateFeature(feat)
        feat = None
    ds = None
