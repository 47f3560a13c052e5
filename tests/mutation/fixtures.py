"""The small valid chain the mutation test mutates (tests/mutation/test_mutation.py).

A 10 km x 10 km synthetic field in EPSG:32632 with one pool, its aquifer, one dipping fault, three
units between constant surfaces and a one-year monthly pressure schedule: every tool runs on it in
about a second, so that a few hundred mutated runs fit in the test's time budget.
"""

import json
import os

X0, Y0 = 680000.0, 4950000.0
CRS = {"type": "name", "properties": {"name": "urn:ogc:def:crs:EPSG::32632"}}


def square(x0, y0, x1, y1):
    return [[[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]]]


def geojson(path, name, features):
    with open(path, "w") as fh:
        json.dump({"type": "FeatureCollection", "name": name, "crs": CRS, "features": features}, fh, indent=1)


def feature(props, geom_type, coords):
    return {"type": "Feature", "properties": props, "geometry": {"type": geom_type, "coordinates": coords}}


CASE = """# mutation-test case (tests/mutation/fixtures.py)
crs = "EPSG:32632"

[model]
name = "mutation"
start = "1950-01-01"
end = "1951-01-01"

[water]
unit_weight_N_per_m3 = 9810.0
compressibility_per_MPa = 4.4e-4

[initial_stress]
surface_elevation_m = 50.0
lithostatic_gradient_MPa_per_m = 0.0226
hydrostatic_gradient_MPa_per_m = 0.00981
k0 = 0.9

[[material]]
name = "rock"
law = "elastic"
biot = 1.0
nu_z = 0.3
cm_a = 1.0044e-2
cm_b = 1.1347

[[material]]
name = "pool_x"
law = "hypoplastic"
biot = 1.0
nu_z = 0.3
Eh_over_Ez = 3.0
nuh_over_nuz = 0.2
cm_a = 1.0044e-2
cm_b = 1.1347
c_R = 3.0
K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]
porosity = 0.20

[[material]]
name = "aquifer_x"
law = "hypoplastic"
biot = 1.0
nu_z = 0.3
cm_a = 1.0044e-2
cm_b = 1.1347
c_R = 3.0
K_m_per_s = [2.04e-7, 2.04e-7, 2.04e-8]
porosity = 0.20

[[pool]]
name = "Pool X"
materials = ["pool_x"]
aquifer_materials = ["aquifer_x"]
schedule = "pressure_pool_x.csv"
column = "p_MPa"

[boundary]
fixed = ["bottom", "west", "east", "south", "north"]

[[fault]]
name = "f1"
cohesion_MPa = 0.0
friction_deg = 30.0

[output]
dates = ["1950-07-01", "1951-01-01"]
"""

STRATA = """# mutation-test stratigraphy (tests/mutation/fixtures.py)
crs = "EPSG:32632"
min_thickness = 0.5
faults = "faults.geojson"

[[surface]]
name = "top"
constant = 50.0

[[surface]]
name = "reservoir top"
constant = -1400.0

[[surface]]
name = "reservoir base"
constant = -1500.0

[[surface]]
name = "bottom"
constant = -3000.0

[[unit]]
name = "cover"
layers = 1

[[unit]]
name = "reservoir"
layers = 1

[[unit]]
name = "base"
layers = 1

[[material]]
name = "pool_x"
units = ["reservoir"]
polygon = "traces.geojson"
where = "name = 'Pool X'"

[[material]]
name = "aquifer_x"
units = ["reservoir"]
polygon = "aquifers.geojson"

[[material]]
name = "rock"
units = ["cover", "reservoir", "base"]
"""


def write_inputs(d):
    """The hand-written inputs of the chain, in folder d."""
    geojson(os.path.join(d, "domain.geojson"), "domain",
            [feature({"name": "domain"}, "Polygon", square(X0, Y0, X0 + 10000, Y0 + 10000))])
    geojson(os.path.join(d, "traces.geojson"), "traces",
            [feature({"name": "Pool X", "size_m": 1500.0}, "Polygon", square(X0 + 3000, Y0 + 3000, X0 + 7000, Y0 + 7000))])
    geojson(os.path.join(d, "aquifers.geojson"), "aquifers",
            [feature({"name": "Pool X"}, "Polygon", square(X0 + 1500, Y0 + 1500, X0 + 8500, Y0 + 8500))])
    geojson(os.path.join(d, "faults.geojson"), "faults",
            [feature({"name": "f1", "top_m": -500.0, "bottom_m": -2000.0, "dip_deg": 70.0, "dip_dir_deg": 180.0,
                      "trace_z_m": -500.0},
                     "LineString", [[X0 + 2000, Y0 + 5200], [X0 + 8000, Y0 + 5800]])])
    geojson(os.path.join(d, "sections.geojson"), "sections",
            [feature({"name": "AA", "from_label": "W", "to_label": "E"}, "LineString",
                     [[X0 + 500, Y0 + 5000], [X0 + 9500, Y0 + 5000]])])
    geojson(os.path.join(d, "ps_points.geojson"), "ps_points",
            [feature({"pid": f"P{i}", "height": 50.0}, "Point", [X0 + 2000 + 1500 * i, Y0 + 4000 + 500 * i])
             for i in range(5)])
    with open(os.path.join(d, "case.toml"), "w") as fh:
        fh.write(CASE)
    with open(os.path.join(d, "strata.toml"), "w") as fh:
        fh.write(STRATA)
    with open(os.path.join(d, "pressure_pool_x.csv"), "w") as fh:
        fh.write("date,p_norm,p_MPa\n")
        p = [15.0, 14.6, 14.2, 13.8, 13.5, 13.3, 13.2, 13.4, 13.8, 14.2, 14.5, 14.7, 14.8]
        for m, v in enumerate(p):
            y, mo = 1950 + (m // 12), m % 12 + 1
            fh.write(f"{y:04d}-{mo:02d}-01,{v / 15.0:.5f},{v:.4f}\n")
    # Measured vertical series in the EGMS layout (EPSG:3035), monthly in the second half of 1950,
    # at the PS points.
    from osgeo import osr
    utm, laea = osr.SpatialReference(), osr.SpatialReference()
    utm.ImportFromEPSG(32632)
    laea.ImportFromEPSG(3035)
    for s in (utm, laea):
        s.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to_laea = osr.CoordinateTransformation(utm, laea)
    dates = ["19500701", "19500801", "19500901", "19501001", "19501101", "19501201"]
    with open(os.path.join(d, "measured.csv"), "w") as fh:
        fh.write("pid,easting,northing,height," + ",".join(dates) + "\n")
        for i in range(5):
            e, n, _ = to_laea.TransformPoint(X0 + 2000 + 1500 * i, Y0 + 4000 + 500 * i)
            vals = ",".join(f"{-0.5 * k * (1 + 0.1 * i):.2f}" for k in range(len(dates)))
            fh.write(f"P{i},{e:.2f},{n:.2f},50.0,{vals}\n")
