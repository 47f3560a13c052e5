"""The small valid chain the mutation test mutates (tests/mutation/test_mutation.py).

A 10 km x 10 km synthetic field in EPSG:32632 with one pool, its aquifer, one dipping fault, three
units between constant surfaces and a one-year monthly pressure schedule: every tool runs on it in
about a second, so that a few hundred mutated runs fit in the test's time budget.
"""

import json
import math
import os
import shutil

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


ENSEMBLE = """# mutation-test ensemble (tests/mutation/fixtures.py)
[design]
method = "sobol"
members = 12
seed = 3

[[parameter]]
path = "material.pool_x.c_R"
distribution = "uniform"
lower = 2.0
upper = 6.0

[[parameter]]
paths = ["material.pool_x.K_m_per_s[0]", "material.pool_x.K_m_per_s[1]"]
distribution = "lognormal"
median = 2e-7
sigma_log = 0.5

[[parameter]]
path = "fault.f1.friction_deg"
distribution = "normal"
mean = 30.0
std = 3.0
lower = 20.0
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
    with open(os.path.join(d, "ensemble.toml"), "w") as fh:
        fh.write(ENSEMBLE)
    write_horizons(d)
    with open(os.path.join(d, "pressure_pool_x.csv"), "w") as fh:
        fh.write("date,p_norm,p_MPa\n")
        p = [15.0, 14.6, 14.2, 13.8, 13.5, 13.3, 13.2, 13.4, 13.8, 14.2, 14.5, 14.7, 14.8]
        for m, v in enumerate(p):
            y, mo = 1950 + (m // 12), m % 12 + 1
            fh.write(f"{y:04d}-{mo:02d}-01,{v / 15.0:.5f},{v:.4f}\n")
    # ugs-seismicity: a per-pair CSV of fault F as ugs-solve writes it (3 pairs, 4 monthly dates), a
    # one-patch dCFS table, and a case with the [seismicity] section.
    with open(os.path.join(d, "pairs_fault_F.csv"), "w") as fh:
        fh.write("# ugs-solve fault F: one row per node pair and output date; units m, MPa, mm; tension positive\n")
        fh.write("date,node,x_m,y_m,z_m,along_strike_m,down_dip_m,area_m2,state,tau_MPa,sigma_n_eff_MPa,chi,slip_mm,"
                 "opening_mm,cfs_change_MPa,p_fault_MPa,interpolated\n")
        for m in range(4):
            for q in range(3):
                fh.write(f"1950-{m + 1:02d}-01,{101 + q},{X0 + 100 * q},{Y0 + 5000},-1000,{100 * q},0,{5000 + 1000 * q},stick,"
                         f"1.5,-20,0.1,0,0,{0.01 * m * (q - 1):.3f},10,{1 if q == 2 else 0}\n")
    with open(os.path.join(d, "dcfs.csv"), "w") as fh:
        fh.write("date,dcfs_MPa\n1950-01-01,0\n1950-07-01,0.05\n1951-01-01,-0.02\n")
    with open(os.path.join(d, "seismicity.toml"), "w") as fh:
        fh.write("[[fault]]\nname = \"F\"\n\n[seismicity]\nA_sigma_MPa = 0.05\nstressing_rate_MPa_per_yr = 1e-3\n"
                 "background_rate_per_yr_km2 = 0.2\nM_c = 1.5\nmagnitudes = [2.0, 3.0]\n\n[seismicity.fault.F]\nb_value = 0.9\n")
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


# ---- horizons as modelling packages export them (issue 40): ugs-meshgen's grid surfaces ----------
STRATA_GRIDS = """# mutation-test stratigraphy with horizon grids (tests/mutation/fixtures.py)
crs = "EPSG:32632"

[[surface]]
name = "top"
constant = 50.0

[[surface]]
name = "reservoir top"
grid = "res_top.irap"

[[surface]]
name = "reservoir base"
grid = "res_base.ts"

[[surface]]
name = "deep"
grid = "deep.zmap"

[[surface]]
name = "bottom"
grid = "bottom.cps"
crs = "EPSG:32632"

[[unit]]
name = "cover"
layers = 1

[[unit]]
name = "reservoir"
layers = 1

[[unit]]
name = "under"
layers = 1

[[unit]]
name = "base"
layers = 1

[[material]]
name = "rock"
units = ["cover", "reservoir", "under", "base"]
"""


def _res_top(x, y):
    return -1400.0 + 0.004 * (x - X0) - 0.002 * (y - Y0) + 15.0 * math.sin((x - X0) / 1500.0)


def write_horizons(d):
    """The horizons of STRATA_GRIDS: an IRAP grid turned by 10 degrees, a TSurf, a ZMAP+ and a CPS-3
    grid, each covering the 10 km square of the chain."""
    # IRAP: 16 x 16 nodes at 1 km, origin 2.5 km south-west of the square, turned 10 degrees.
    a = math.radians(10.0)
    nx = ny = 16
    ox, oy = X0 - 2500.0, Y0 - 2500.0
    vals = []
    for j in range(ny):
        for i in range(nx):
            x = ox + math.cos(a) * 1000.0 * i - math.sin(a) * 1000.0 * j
            y = oy + math.sin(a) * 1000.0 * i + math.cos(a) * 1000.0 * j
            vals.append(_res_top(x, y))
    with open(os.path.join(d, "res_top.irap"), "w") as fh:
        fh.write(f"-996 {ny} 1000.000000 1000.000000\n{ox:.6f} {ox + 15000:.6f} {oy:.6f} {oy + 15000:.6f}\n"
                 f"{nx} 10.000000 {ox:.6f} {oy:.6f}\n0  0  0  0  0  0  0\n")
        for k in range(0, len(vals), 6):
            fh.write(" ".join(f"{v:.4f}" for v in vals[k:k + 6]) + "\n")
    # TSurf: 11 x 11 nodes at 1 km on the square, 100 m below the reservoir top, as depth.
    n = 11
    lines = ["GOCAD TSurf 1", "HEADER {", "name:reservoir_base", "}", "GOCAD_ORIGINAL_COORDINATE_SYSTEM",
             "NAME Default", 'AXIS_NAME "X" "Y" "Z"', 'AXIS_UNIT "m" "m" "m"', "ZPOSITIVE Depth",
             "END_ORIGINAL_COORDINATE_SYSTEM", "TFACE"]
    for j in range(n):
        for i in range(n):
            x, y = X0 + 1000.0 * i, Y0 + 1000.0 * j
            lines.append(f"VRTX {j * n + i + 1} {x:.2f} {y:.2f} {-(_res_top(x, y) - 100.0):.4f}")
    for j in range(n - 1):
        for i in range(n - 1):
            p = j * n + i + 1
            lines += [f"TRGL {p} {p + 1} {p + n + 1}", f"TRGL {p} {p + n + 1} {p + n}"]
    lines.append("END")
    with open(os.path.join(d, "res_base.ts"), "w") as fh:
        fh.write("\n".join(lines) + "\n")
    # ZMAP+: 13 x 13 nodes at 1 km from 1 km south-west of the square, columns from the west, each from the north.
    n, x0, y0 = 13, X0 - 1000.0, Y0 - 1000.0
    out = ["! deep horizon", "@deep, GRID, 5", "     20, -99999.0, , 4, 1",
           f"{n}, {n}, {x0:.1f}, {x0 + 12000:.1f}, {y0:.1f}, {y0 + 12000:.1f}", "0.0, 0.0, 0.0", "@"]
    for i in range(n):
        col = [-2200.0 + 0.003 * 1000.0 * i - 0.001 * 1000.0 * j for j in range(n - 1, -1, -1)]
        for k in range(0, n, 5):
            out.append("".join(f"{v:20.4f}" for v in col[k:k + 5]))
    with open(os.path.join(d, "deep.zmap"), "w") as fh:
        fh.write("\n".join(out) + "\n")
    # CPS-3: the same nodes, columns from the west, each from the north.
    vals = [-3000.0 + 2.0 * i - 1.0 * j for i in range(n) for j in range(n - 1, -1, -1)]
    with open(os.path.join(d, "bottom.cps"), "w") as fh:
        fh.write(f"FSASCI 0 1 COMPUTED 0 1.0000000E+30\nFSATTR 0 0\n"
                 f"FSLIMI {x0:.4f} {x0 + 12000:.4f} {y0:.4f} {y0 + 12000:.4f} {min(vals):.4f} {max(vals):.4f}\n"
                 f"FSNROW {n} {n}\nFSXINC 1000.0000 1000.0000\n->bottom\n")
        for k in range(0, len(vals), 5):
            fh.write(" ".join(f"{v:.4f}" for v in vals[k:k + 5]) + "\n")
    with open(os.path.join(d, "strata_grids.toml"), "w") as fh:
        fh.write(STRATA_GRIDS)


# ---- a reservoir simulator's output (ugs-import-eclipse) ------------------------------------------
DECK = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "eclipse", "make_deck.py")


def write_eclipse(d, flow):
    """TINY.EGRID and TINY.UNRST of OPM Flow on the import test's tiny deck (tests/eclipse/make_deck.py:
    8 x 6 x 4 corner-point cells about (600000, 5000000), 1000-1080 m deep, MAPAXES, a faulted pillar,
    an inactive cell; 5 report steps), and deck_mesh.msh: a box of tetrahedra over it."""
    import subprocess
    import sys
    run = os.path.join(d, "deck-run")
    os.makedirs(run, exist_ok=True)
    for cmd in ([sys.executable, DECK, "TINY.DATA"], [flow, "TINY.DATA", "--output-dir=."]):
        r = subprocess.run(cmd, cwd=run, capture_output=True, text=True, timeout=600)
        if r.returncode != 0:
            raise SystemExit(f"FAIL: {' '.join(cmd)} (exit {r.returncode}): {r.stdout[-2000:]}{r.stderr[-2000:]}")
    for f in ("TINY.EGRID", "TINY.UNRST"):
        shutil.move(os.path.join(run, f), os.path.join(d, f))
    shutil.rmtree(run)
    write_box_msh(os.path.join(d, "deck_mesh.msh"), (599400.0, 4999900.0, -1120.0), (601000.0, 5001100.0, -980.0),
                  (12, 10, 4))


def write_box_msh(path, lo, hi, n):
    """An ASCII MSH 4.1 box of n[0] x n[1] x n[2] cubes, 6 tetrahedra each, one volume "rock"."""
    nodes, coords, tets = {}, [], []

    def node(i, j, k):
        if (i, j, k) not in nodes:
            nodes[(i, j, k)] = len(coords) + 1
            coords.append(tuple(lo[a] + (hi[a] - lo[a]) * (i, j, k)[a] / n[a] for a in range(3)))
        return nodes[(i, j, k)]

    for i in range(n[0]):
        for j in range(n[1]):
            for k in range(n[2]):
                c = [node(i + a, j + b, k + e) for e in (0, 1) for b in (0, 1) for a in (0, 1)]
                for t in ((0, 1, 3, 7), (0, 3, 2, 7), (0, 2, 6, 7), (0, 6, 4, 7), (0, 4, 5, 7), (0, 5, 1, 7)):
                    tets.append([c[q] for q in t])
    with open(path, "w") as f:
        f.write('$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 "rock"\n$EndPhysicalNames\n')
        f.write("$Entities\n0 0 0 1\n1 %r %r %r %r %r %r 1 1 0\n$EndEntities\n" % (*lo, *hi))
        f.write("$Nodes\n1 %d 1 %d\n3 1 0 %d\n" % (len(coords), len(coords), len(coords)))
        f.write("".join("%d\n" % (q + 1) for q in range(len(coords))))
        f.write("".join("%r %r %r\n" % c for c in coords))
        f.write("$EndNodes\n$Elements\n1 %d 1 %d\n3 1 4 %d\n" % (len(tets), len(tets), len(tets)))
        f.write("".join("%d %d %d %d %d\n" % (e + 1, *t) for e, t in enumerate(tets)))
        f.write("$EndElements\n")
