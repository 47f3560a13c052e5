"""Distance of fault node pairs from the depleted volume's corners (bench/fault-convergence).

Where a fault cuts the top or base of a depleted layer, the stress change on the fault is singular
(Jansen et al. 2019; docs/fault-convergence.md, VERIFICATION V8): the largest chi AT such a corner line
does not converge under mesh refinement. The bench therefore reports, beside the raw maximum, the
largest chi over the pairs at least CORNER_M from every corner line.

The depleted volume of the po-plain twin is the three layers Pool A, Interlayer and Pool C inside
their aquifer polygons (aquifers.geojson: the pools' traces lie inside them; gas pools and aquifers
are both under a pressure change). A corner line is where a fault meets the top or base surface of
one of those layers. A pair's distance from the corners is the vertical distance from its elevation
to the nearest top or base of a depleted layer at its (x, y), for pairs whose plan position lies in
that layer's polygon grown by CORNER_M (so the lateral edges count too); pairs elsewhere are
infinitely far. The surfaces are sub-horizontal and the local faults dip 80-82 degrees, so the
vertical distance is the distance along the fault to within 2 %.
"""
import glob
import json
import math
import os

from osgeo import gdal, ogr

gdal.UseExceptions()

# depleted layers: (aquifers.geojson name, top surface raster, base surface raster)
LAYERS = [("Pool A", "05_pool_a_top", "06_pool_a_base"),
          ("Interlayer", "06_pool_a_base", "07_pool_c_top"),
          ("Pool C", "07_pool_c_top", "08_pool_c_base")]


class Corners:
    def __init__(self, sample, grow_m):
        self.rasters = {}
        for _, top, base in LAYERS:
            for name in (top, base):
                if name not in self.rasters:
                    ds = gdal.Open(glob.glob(os.path.join(sample, "surfaces", name + "*.tif"))[0])
                    self.rasters[name] = (ds.GetGeoTransform(), ds.ReadAsArray().astype(float))
        polys = {}
        with open(os.path.join(sample, "aquifers.geojson")) as fh:
            for f in json.load(fh)["features"]:
                polys[f["properties"]["name"]] = ogr.CreateGeometryFromJson(json.dumps(f["geometry"])).Buffer(grow_m)
        self.polys = [polys[name] for name, _, _ in LAYERS]

    def _z(self, name, x, y):
        gt, a = self.rasters[name]
        c = (x - gt[0]) / gt[1] - 0.5
        r = (y - gt[3]) / gt[5] - 0.5
        i, j = int(math.floor(r)), int(math.floor(c))
        fr, fc = r - i, c - j
        return (a[i, j] * (1 - fr) * (1 - fc) + a[i, j + 1] * (1 - fr) * fc
                + a[i + 1, j] * fr * (1 - fc) + a[i + 1, j + 1] * fr * fc)

    def distance(self, x, y, z):
        pt = ogr.Geometry(ogr.wkbPoint)
        pt.AddPoint(x, y)
        d = math.inf
        for (name, top, base), poly in zip(LAYERS, self.polys):
            if poly.Contains(pt):
                d = min(d, abs(z - self._z(top, x, y)), abs(z - self._z(base, x, y)))
        return d
