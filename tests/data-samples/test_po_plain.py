#!/usr/bin/python3
"""Checks of the po-plain synthetic twin (data-samples/po-plain, issue 3).

Runs the generator for the small twin (twice, to check determinism) and for the full twin (to check
that the committed files are exactly what the generator produces), then checks both the committed
full twin and the generated small twin:

  * every raster read back through GDAL: CRS EPSG:32632, extent = domain + one cell, Table 4.1
    value at A016VJP (bilinear, +-0.5 m), surfaces never cross (equality only in pinching units);
  * strata.toml: surfaces, 41 sub-layers, the seven materials and their polygon filters;
  * pressure CSVs: monotone monthly dates 1950-01 .. 2033-12 without gaps, 35 % and 52 % drops of
    Pool C in 1960 and 1964 (+-2 %), identical forecast cycles spanning 37 % (+-2 %), Pool A phases;
  * every GeoJSON opens with OGR, has the CRS and the required attributes and a sound geometry;
  * InSAR CSVs: EGMS L3 layout, the six points, date columns monthly then weekly 2003-10 .. 2021-10;
  * case.toml: the sections and the parameters of Tables 4.2 and 4.3.

usage: test_po_plain.py [--sample DIR] [--workdir DIR] [--keep]
Exit status 0 when every check passes, 1 otherwise. Prints one line per check.
"""

import sys

sys.dont_write_bytecode = True

import argparse  # noqa: E402
import csv  # noqa: E402
import datetime as dt  # noqa: E402
import hashlib  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402
import subprocess  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import tomllib  # noqa: E402

import numpy as np  # noqa: E402
from osgeo import gdal, ogr, osr  # noqa: E402

gdal.UseExceptions()
ogr.UseExceptions()
osr.UseExceptions()
gdal.SetConfigOption("GDAL_PAM_ENABLED", "NO")   # reading must not leave .aux.xml files behind

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_SAMPLE = os.path.normpath(os.path.join(HERE, "..", "..", "data-samples", "po-plain"))

# Thesis Table 4.1, typed in independently of the generator: surface, elevation at A016VJP, layers
TABLE_4_1 = [
    ("DEM", 50.0, 2), ("Alluvial base", -346.0, 2), ("Santerno top (Asti base)", -1024.0, 2),
    ("Upper Pliocene sands base", -1152.0, 3), ("Pool A top (Pliocene base)", -1410.0, 5),
    ("Pool A base", -1476.0, 3), ("Pool C top", -1498.0, 8), ("Pool C base", -1515.0, 2),
    ("Miocene clays top (Miocene sands base)", -1543.0, 2), ("Marls top", -1543.0, 10),
    ("Limestones top", -8655.0, 2), ("Model bottom", -10000.0, None),
]
MATERIALS = {"surrounding_rock", "aquifer_pool_a", "aquifer_interlayer", "aquifer_pool_c",
             "pool_a", "interlayer", "pool_c"}
PINCHING = {"Pool C", "Miocene clays"}
PIDS_IN = ["A00LFZ4", "A016VJP", "A016VNW"]
PIDS_OUT = ["A00LFOB", "A016VQ9", "A016VUG"]
EGMS_STATIC = ["pid", "easting", "northing", "height", "rmse", "mean_velocity", "mean_velocity_std",
               "acceleration", "acceleration_std", "seasonality", "seasonality_std"]


class Checks:
    def __init__(self):
        self.n_ok = 0
        self.failed = []

    def __call__(self, cond, what):
        if cond:
            self.n_ok += 1
            print(f"ok    {what}")
        else:
            self.failed.append(what)
            print(f"FAIL  {what}")
        return cond


check = Checks()


# ------------------------------------------------------------------------------------------ helpers
def bilinear(arr, gt, x, y):
    fx = (x - gt[0]) / gt[1] - 0.5
    fy = (y - gt[3]) / gt[5] - 0.5
    j0, i0 = int(math.floor(fx)), int(math.floor(fy))
    tx, ty = fx - j0, fy - i0
    a = arr[i0:i0 + 2, j0:j0 + 2].astype(float)
    return float((1 - ty) * ((1 - tx) * a[0, 0] + tx * a[0, 1]) + ty * ((1 - tx) * a[1, 0] + tx * a[1, 1]))


def epsg_of(srs):
    if srs is None:
        return None
    s = srs.Clone()
    s.AutoIdentifyEPSG()
    return s.GetAuthorityCode(None)


def layer_features(path):
    ds = ogr.Open(path)
    lyr = ds.GetLayer(0)
    names = [lyr.GetLayerDefn().GetFieldDefn(i).GetName() for i in range(lyr.GetLayerDefn().GetFieldCount())]
    feats = []
    for f in lyr:
        attrs = {n: f.GetField(n) for n in names}
        feats.append((attrs, f.GetGeometryRef().Clone()))
    return ds, lyr, names, feats


def bearing(p, q):
    return math.degrees(math.atan2(q[0] - p[0], q[1] - p[1])) % 360.0


def file_digests(root):
    out = {}
    for d, _, fs in os.walk(root):
        for f in fs:
            p = os.path.join(d, f)
            with open(p, "rb") as fh:
                out[os.path.relpath(p, root)] = hashlib.sha256(fh.read()).hexdigest()
    return out


def run_generator(sample, out, *extra):
    t0 = time.time()
    env = dict(os.environ, PYTHONDONTWRITEBYTECODE="1")
    r = subprocess.run(["/usr/bin/python3", os.path.join(sample, "generate.py"), "--out", out, "-q", *extra],
                       capture_output=True, text=True, env=env)
    check(r.returncode == 0, f"generate.py --out {os.path.basename(out)} {' '.join(extra)} exits 0 "
          f"({time.time() - t0:.1f} s){': ' + r.stderr.strip() if r.returncode else ''}")
    return r.returncode == 0


# ------------------------------------------------------------------------------------------ checks
def check_strata(d, tag):
    with open(os.path.join(d, "strata.toml"), "rb") as fh:
        st = tomllib.load(fh)
    check(st.get("crs") == "EPSG:32632", f"[{tag}] strata.toml crs = EPSG:32632")
    check(isinstance(st.get("min_thickness"), float) and st["min_thickness"] > 0,
          f"[{tag}] strata.toml min_thickness = {st.get('min_thickness')} m")
    surf = st.get("surface", [])
    check([s.get("name") for s in surf] == [t[0] for t in TABLE_4_1],
          f"[{tag}] strata.toml lists the 12 surfaces of Table 4.1 top to bottom")
    check(surf and surf[-1].get("constant") == -10000.0, f"[{tag}] model bottom constant -10,000 m")
    units = st.get("unit", [])
    layers = [u.get("layers") for u in units]
    check(layers == [t[2] for t in TABLE_4_1[:-1]] and sum(layers) == 41,
          f"[{tag}] sub-layers {layers} = Table 4.1, total {sum(l or 0 for l in layers)}")
    unit_names = [u.get("name") for u in units]
    mats = st.get("material", [])
    check({m.get("name") for m in mats} == MATERIALS and len(mats) == 7,
          f"[{tag}] seven material rules: {', '.join(m.get('name', '?') for m in mats)}")
    check(mats and "polygon" not in mats[-1], f"[{tag}] last material rule has no polygon (default)")
    for m in mats:
        ok = all(u in unit_names for u in m.get("units", [])) and m.get("units")
        if "polygon" in m:
            ds = ogr.Open(os.path.join(d, m["polygon"]))
            lyr = ds.GetLayer(0)
            lyr.SetAttributeFilter(m["where"])
            ok = ok and lyr.GetFeatureCount() == 1
        check(ok, f"[{tag}] material {m.get('name')}: units exist, polygon filter selects one feature")
    # the faulted model's stratigraphy (Makefile FAULT_STRATA): strata_coarse.toml's surfaces and materials,
    # finer down dip in the units the faults cross (docs/fault-convergence.md)
    with open(os.path.join(d, "strata_coarse.toml"), "rb") as fh:
        co = tomllib.load(fh)
    with open(os.path.join(d, "strata_faulted.toml"), "rb") as fh:
        fa = tomllib.load(fh)
    cl = {u["name"]: u["layers"] for u in co["unit"]}
    fl = {u["name"]: u["layers"] for u in fa["unit"]}
    finer = {u: (cl[u], fl[u]) for u in cl if fl.get(u) != cl[u]}
    check(fa["surface"] == co["surface"] and fa["material"] == co["material"] and list(fl) == list(cl)
          and finer == {"Santerno clays": (1, 3), "Marls": (4, 8)} and sum(fl.values()) == 22,
          f"[{tag}] strata_faulted.toml = strata_coarse.toml with finer units {finer}, {sum(fl.values())} sub-layers")
    return st


def check_rasters(d, tag, st, domain_env, pref):
    arrays = []
    for s, (name, z, _) in zip(st["surface"], TABLE_4_1):
        if "constant" in s:
            continue
        path = os.path.join(d, s["raster"])
        ds = gdal.Open(path)
        gt = ds.GetGeoTransform()
        arr = ds.GetRasterBand(1).ReadAsArray().astype(float)
        code = epsg_of(ds.GetSpatialRef())
        xmin, xmax = gt[0], gt[0] + gt[1] * ds.RasterXSize
        ymax, ymin = gt[3], gt[3] + gt[5] * ds.RasterYSize
        cell = gt[1]
        ext_ok = (abs(gt[1] + gt[5]) < 1e-9 and gt[2] == 0 and gt[4] == 0 and
                  abs(xmin - (domain_env[0] - cell)) < 1e-6 and abs(xmax - (domain_env[1] + cell)) < 1e-6 and
                  abs(ymin - (domain_env[2] - cell)) < 1e-6 and abs(ymax - (domain_env[3] + cell)) < 1e-6)
        v = bilinear(arr, gt, *pref)
        check(code == "32632" and ext_ok and np.isfinite(arr).all() and abs(v - z) <= 0.5,
              f"[{tag}] {s['raster']}: EPSG:{code}, {ds.RasterXSize}x{ds.RasterYSize} cells of {cell:g} m "
              f"= domain + 1 cell, {v:.3f} m at A016VJP (Table 4.1: {z:g})")
        arrays.append((name, arr))
        ds = None
    bottom = np.full_like(arrays[0][1], -10000.0)
    arrays.append(("Model bottom", bottom))
    for (un, upper), (ln, lower), u in zip(arrays[:-1], arrays[1:], st["unit"]):
        t = upper - lower
        unit = u["name"]
        zero = float((t == 0).mean())
        if unit in PINCHING:
            check(t.min() >= 0 and 0 < zero < 0.9 and t.max() > 0,
                  f"[{tag}] {unit}: min {t.min():.2f} m (never negative), pinched out on {100 * zero:.1f} % "
                  f"of the cells, max {t.max():.1f} m")
        else:
            check(t.min() > 0, f"[{tag}] {unit}: thickness {t.min():.2f} .. {t.max():.2f} m (> 0 everywhere)")
    return dict(arrays)


def check_pinchouts(tag, arrays, gt_cell, pref, domain_env):
    pc = arrays["Pool C top"] - arrays["Pool C base"]
    ny, nx = pc.shape
    x0, y0 = domain_env[0] - gt_cell, domain_env[3] + gt_cell
    xs = x0 + (np.arange(nx) + 0.5) * gt_cell
    ys = y0 - (np.arange(ny) + 0.5) * gt_cell
    X, Y = np.meshgrid(xs, ys)
    zx, zy = X[pc == 0] - pref[0], Y[pc == 0] - pref[1]
    b = math.degrees(math.atan2(zx.mean(), zy.mean())) % 360.0 if zx.size else -1
    near = np.hypot(X - pref[0], Y - pref[1]) < 3000.0
    pz = (pc == 0) & near
    bnear = math.degrees(math.atan2((X[pz] - pref[0]).mean(), (Y[pz] - pref[1]).mean())) % 360.0 if pz.any() else -1
    check(22.5 <= bnear <= 112.5, f"[{tag}] Pool C pinches out towards E-NE of A016VJP "
          f"(zero-thickness cells within 3 km lie at mean bearing {bnear:.0f} deg; all: {b:.0f} deg)")
    mc = arrays["Miocene clays top (Miocene sands base)"] - arrays["Marls top"]
    gt = (x0, gt_cell, 0, y0, 0, -gt_cell)
    check(bilinear(mc, gt, *pref) == 0.0 and mc.max() > 50.0,
          f"[{tag}] Miocene clays: zero at A016VJP, up to {mc.max():.0f} m elsewhere")


def read_pressure(path):
    with open(path, newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def check_pressures(d, tag):
    out = {}
    for pool, fname in (("Pool A", "pressure_pool_a.csv"), ("Pool C", "pressure_pool_c.csv")):
        header, rows = read_pressure(os.path.join(d, fname))
        check(header == ["date", "p_norm", "p_MPa"], f"[{tag}] {fname}: header date,p_norm,p_MPa")
        dates = [dt.date.fromisoformat(r[0]) for r in rows]
        p = np.array([float(r[1]) for r in rows])
        pm = np.array([float(r[2]) for r in rows])
        monthly = all(d2 == (dt.date(d1.year + (d1.month == 12), d1.month % 12 + 1, 1))
                      for d1, d2 in zip(dates[:-1], dates[1:]))
        check(dates[0] == dt.date(1950, 1, 1) and dates[-1] == dt.date(2033, 12, 1) and monthly
              and all(d.day == 1 for d in dates) and len(dates) == 1008,
              f"[{tag}] {fname}: {len(dates)} monthly dates {dates[0]} .. {dates[-1]}, increasing, no gaps")
        ratio = pm / p
        check(np.ptp(ratio) < 1e-3 and abs(ratio.mean() - 15.2055) < 1e-3 and np.isfinite(p).all() and (p > 0).all(),
              f"[{tag}] {fname}: p_MPa = p_norm x {ratio.mean():.4f} MPa (Pool C initial pressure)")
        out[pool] = (dates, p)
    dates, pc = out["Pool C"]
    idx = {d: i for i, d in enumerate(dates)}
    check(abs(pc[0] - 1.0) < 1e-9, f"[{tag}] Pool C starts at p_norm = {pc[0]}")
    for year, drop in ((1960, 0.35), (1964, 0.52)):
        got = 1.0 - pc[idx[dt.date(year, 1, 1)]]
        check(abs(got - drop) <= 0.02, f"[{tag}] Pool C drop by {year}-01: {100 * got:.1f} % (thesis {100 * drop:.0f} % +-2)")
    spans, shapes = [], []
    for year in range(2022, 2034):
        yv = np.array([pc[idx[dt.date(year, m, 1)]] for m in range(1, 13)])
        spans.append(yv.max() - yv.min())
        shapes.append(yv)
        if year == 2022:
            amin, amax = int(np.argmin(yv)) + 1, int(np.argmax(yv)) + 1
    check(all(abs(s - 0.37) <= 0.02 for s in spans),
          f"[{tag}] forecast cycles 2022-2033 span {min(spans) * 100:.1f} .. {max(spans) * 100:.1f} % (37 % +-2)")
    check(all(np.array_equal(shapes[1], s) for s in shapes[1:]) and np.array_equal(shapes[0][3:], shapes[1][3:]),
          f"[{tag}] forecast cycles identical from the April 2022 injection to 2033-12")
    check(amin == 4 and amax in (10, 11), f"[{tag}] cycle minimum in month {amin} (April), maximum in month {amax}")
    recent = []
    for year in range(2010, 2022):
        yv = [pc[idx[dt.date(year, m, 1)]] for m in range(1, 13)]
        recent.append(max(yv) - min(yv))
    check(all(0.20 <= s <= 0.30 for s in recent),
          f"[{tag}] recent cycles 2010-2021 span {min(recent) * 100:.1f} .. {max(recent) * 100:.1f} % (~25 %)")
    i64 = idx[dt.date(1964, 4, 1)]
    check(all(np.diff(pc[:i64 + 1]) <= 0), f"[{tag}] Pool C declines monotonically in primary production 1950-1964")
    _, pa = out["Pool A"]
    i71, i91, i02 = idx[dt.date(1971, 1, 1)], idx[dt.date(1991, 4, 1)], idx[dt.date(2002, 4, 1)]
    span_storage = [max(pa[idx[dt.date(y, m, 1)]] for m in range(1, 13)) -
                    min(pa[idx[dt.date(y, m, 1)]] for m in range(1, 13)) for y in range(1992, 2002)]
    check(all(np.diff(pa[:i91 + 1]) <= 0) and pa[i71] < pa[0] - 0.3 and min(span_storage) > 0.05
          and all(np.diff(pa[i02:]) >= 0) and pa[-1] > pa[i02] + 0.1,
          f"[{tag}] Pool A: production 1950-1971 ({pa[0]:.3f} -> {pa[i71]:.3f}), tail to 1991 ({pa[i91]:.3f}), "
          f"storage cycles 1991-2002 (spans >= {min(span_storage):.3f}), re-pressurization to {pa[-1]:.3f} in 2033")
    return out


def check_vectors(d, tag, variant):
    res = {}
    # domain
    ds, lyr, names, feats = layer_features(os.path.join(d, "domain.geojson"))
    env = feats[0][1].GetEnvelope() if feats else (0, 0, 0, 0)
    size = (env[1] - env[0], env[3] - env[2])
    want = (42000.0, 30000.0) if variant == "full" else None
    check(epsg_of(lyr.GetSpatialRef()) == "32632" and len(feats) == 1 and
          (want is None or size == want) and "size_m" in names,
          f"[{tag}] domain.geojson: EPSG:32632, {size[0] / 1000:g} x {size[1] / 1000:g} km, size_m")
    res["domain"] = env
    dom = feats[0][1]
    # traces
    ds, lyr, names, feats = layer_features(os.path.join(d, "reservoir_traces.geojson"))
    tr = {a["name"]: g for a, g in feats}
    check(epsg_of(lyr.GetSpatialRef()) == "32632" and set(tr) == {"Pool A", "Pool C"} and
          all(g.GetGeometryType() == ogr.wkbPolygon and g.IsValid() and dom.Contains(g) for g in tr.values()),
          f"[{tag}] reservoir_traces.geojson: valid polygons Pool A ({tr['Pool A'].GetArea() / 1e6:.1f} km2), "
          f"Pool C ({tr['Pool C'].GetArea() / 1e6:.1f} km2) inside the domain")
    ea, ec = tr["Pool A"].GetEnvelope(), tr["Pool C"].GetEnvelope()
    check(3000 < max(ea[1] - ea[0], ea[3] - ea[2]) < 10000 and (ea[1] - ea[0]) > (ea[3] - ea[2]),
          f"[{tag}] Pool A trace a few km long, elongated E-W ({(ea[1] - ea[0]) / 1000:.1f} x {(ea[3] - ea[2]) / 1000:.1f} km)")
    res["traces"] = tr
    # aquifers
    ds, lyr, names, feats = layer_features(os.path.join(d, "aquifers.geojson"))
    aq = {a["name"]: g for a, g in feats}
    check(set(aq) == {"Pool A", "Interlayer", "Pool C"} and all(g.IsValid() for g in aq.values())
          and aq["Pool A"].Buffer(1.0).Contains(tr["Pool A"]) and aq["Pool C"].Buffer(1.0).Contains(tr["Pool C"]),
          f"[{tag}] aquifers.geojson: Pool A / Interlayer / Pool C aquifers, each around its trace")
    # faults
    ds, lyr, names, feats = layer_features(os.path.join(d, "faults.geojson"))
    req = ["name", "kind", "top_m", "bottom_m", "dip_deg", "dip_dir_deg"]
    check(all(n in names for n in req) and epsg_of(lyr.GetSpatialRef()) == "32632",
          f"[{tag}] faults.geojson: attributes {', '.join(req)}")
    regional = [(a, g) for a, g in feats if a["kind"].startswith("regional")]
    local = [(a, g) for a, g in feats if a["kind"] == "local_extensional"]
    ok = len(regional) == 2 and 3 <= len(local) <= 4
    for a, g in regional:
        pts = g.GetPoints()
        strike = bearing(pts[0], pts[-1]) % 180.0
        ok = ok and a["top_m"] == -500.0 and a["bottom_m"] == -5000.0 and 90.0 <= strike <= 135.0
        south = 90.0 < a["dip_dir_deg"] < 270.0
        ok = ok and (south if a["kind"] == "regional_overthrust" else not south)
    for a, g in local:
        pts = g.GetPoints()
        strike = bearing(pts[0], pts[-1]) % 180.0
        ok = ok and a["dip_deg"] >= 75.0 and 40.0 <= strike <= 105.0 and a["top_m"] > a["bottom_m"] \
            and -2000.0 < a["bottom_m"] and a["top_m"] < -1000.0 and tr["Pool A"].Buffer(500.0).Intersects(g)
    check(ok, f"[{tag}] faults: overthrust (dips S, N vergence) + back-thrust (dips N), E-W..NW-SE, -500..-5,000 m; "
          f"{len(local)} sub-vertical local faults NE-SW..E-W over the trap")
    # the regional faults lie outside the depleted volume (thesis 4.3.4): at every elevation of the
    # pools' sands (-1,400 .. -1,850 m on the flanks) the fault surface (the trace moved down-dip) is at
    # least 1.8 km from every aquifer polygon (it bounded them, and crossed their deep flanks, before)
    gap = math.inf
    for a, g in regional:
        b = math.radians(a["dip_dir_deg"])
        for z in np.linspace(-1400.0, -1850.0, 10):
            shift = (a["trace_z_m"] - z) / math.tan(math.radians(a["dip_deg"]))
            moved = ogr.Geometry(ogr.wkbLineString)
            for x, y in g.GetPoints():
                moved.AddPoint_2D(x + shift * math.sin(b), y + shift * math.cos(b))
            gap = min([gap] + [moved.Distance(p) for p in aq.values()])
    check(gap >= 1800.0, f"[{tag}] regional faults at least 1.8 km from the aquifers over the sands' depths ({gap:.0f} m)")
    # sections
    ds, lyr, names, feats = layer_features(os.path.join(d, "sections.geojson"))
    check({a["name"] for a, g in feats} == {"A-A", "B-B"} and
          all(g.GetGeometryType() == ogr.wkbLineString and g.Intersects(tr["Pool A"]) for a, g in feats),
          f"[{tag}] sections.geojson: A-A and B-B cross the reservoir")
    # PS points
    ds, lyr, names, feats = layer_features(os.path.join(d, "ps_points.geojson"))
    pts = {a["pid"]: g for a, g in feats}
    ok = set(pts) == set(PIDS_IN + PIDS_OUT)
    ok = ok and all(tr["Pool A"].Contains(pts[p]) and tr["Pool C"].Contains(pts[p]) for p in PIDS_IN)
    ok = ok and all(not tr["Pool A"].Contains(pts[p]) and not tr["Pool C"].Contains(pts[p]) for p in PIDS_OUT)
    check(ok, f"[{tag}] ps_points.geojson: {', '.join(PIDS_IN)} inside both traces; {', '.join(PIDS_OUT)} outside")
    res["points"] = {p: (g.GetX(), g.GetY()) for p, g in pts.items()}
    # refinement
    ds, lyr, names, feats = layer_features(os.path.join(d, "refinement.geojson"))
    check(len(feats) == 1 and "size_m" in names and feats[0][1].Contains(tr["Pool A"]) and feats[0][1].Contains(tr["Pool C"]),
          f"[{tag}] refinement.geojson: one polygon around both traces, size_m = {feats[0][0]['size_m'] if feats else '?'}")
    return res


def check_insar(d, tag, points, pressures):
    src, dst = osr.SpatialReference(), osr.SpatialReference()
    src.ImportFromEPSG(3035)
    dst.ImportFromEPSG(32632)
    src.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    dst.SetAxisMappingStrategy(osr.OAMS_TRADITIONAL_GIS_ORDER)
    to32632 = osr.CoordinateTransformation(src, dst)
    series = {}
    for comp, fname in (("U", "insar_vertical.csv"), ("E", "insar_east.csv")):
        with open(os.path.join(d, fname), newline="") as fh:
            rows = list(csv.reader(fh))
        head = rows[0]
        dcols = head[len(EGMS_STATIC):]
        dates = [dt.datetime.strptime(c, "%Y%m%d").date() for c in dcols]
        gaps = [(b - a).days for a, b in zip(dates[:-1], dates[1:])]
        before = [g for a, g in zip(dates[:-1], gaps) if a < dt.date(2015, 2, 1)]
        after = [g for a, g in zip(dates[:-1], gaps) if a >= dt.date(2015, 3, 1)]
        check(head[:len(EGMS_STATIC)] == EGMS_STATIC and all(len(c) == 8 for c in dcols),
              f"[{tag}] {fname}: EGMS L3 columns {','.join(EGMS_STATIC)}, then YYYYMMDD")
        check((dates[0].year, dates[0].month) == (2003, 10) and (dates[-1].year, dates[-1].month) == (2021, 10)
              and all(g > 0 for g in gaps) and all(27 <= g <= 32 for g in before) and all(g == 7 for g in after),
              f"[{tag}] {fname}: {len(dates)} dates {dates[0]} .. {dates[-1]}, monthly to 2015-02 "
              f"({len(before) + 1}), weekly from 2015-03 ({len(after)})")
        body = {r[0]: r for r in rows[1:]}
        ok = set(body) == set(PIDS_IN + PIDS_OUT) and all(len(r) == len(head) for r in rows[1:])
        maxdev = 0.0
        for pid, r in body.items():
            x, y, _ = to32632.TransformPoint(float(r[1]), float(r[2]))
            px, py = points[pid]
            maxdev = max(maxdev, math.hypot(x - px, y - py))
            vals = np.array([float(v) for v in r[len(EGMS_STATIC):]])
            ok = ok and vals[0] == 0.0 and np.isfinite(vals).all() and np.abs(vals).max() < 100.0
            series[(comp, pid)] = (dates, vals)
        check(ok and maxdev < 0.05, f"[{tag}] {fname}: six PS rows, first epoch 0 mm, |u| < 100 mm, "
              f"EPSG:3035 easting/northing = ps_points.geojson (max {maxdev:.3f} m)")
    # physics: storage-phase uplift 2015 at the culmination, correlation with Pool C inside only
    dates, uz = series[("U", "A016VJP")]
    dd = np.array([x.toordinal() for x in dates], dtype=float)

    def mean_between(v, a, b):
        m = (dd >= a.toordinal()) & (dd <= b.toordinal())
        return v[m].mean()
    up = mean_between(uz, dt.date(2015, 10, 15), dt.date(2015, 11, 30)) - mean_between(uz, dt.date(2015, 4, 1), dt.date(2015, 5, 15))
    check(2.0 <= up <= 6.0, f"[{tag}] A016VJP storage uplift May -> Nov 2015: {up:.1f} mm (thesis: up to ~4 mm)")
    pdates, pc = pressures["Pool C"]
    pp = np.interp(dd, [x.toordinal() for x in pdates], pc)
    w = dd >= dt.date(2015, 3, 1).toordinal()
    corr = {}
    for pid in PIDS_IN + PIDS_OUT:
        v = series[("U", pid)][1]
        corr[pid] = float(np.corrcoef(v[w] - np.polyval(np.polyfit(dd[w], v[w], 1), dd[w]), pp[w])[0, 1])
    check(min(corr[p] for p in PIDS_IN[1:]) > 0.5 and max(corr[p] for p in PIDS_OUT) < 0.4,
          f"[{tag}] detrended vertical series vs Pool C pressure 2015-2021: correlation " +
          ", ".join(f"{p} {corr[p]:.2f}" for p in PIDS_IN + PIDS_OUT))


def check_case(d, tag):
    with open(os.path.join(d, "case.toml"), "rb") as fh:
        case = tomllib.load(fh)
    check(all(k in case for k in ("model", "initial_stress", "material", "pool", "boundary", "output")),
          f"[{tag}] case.toml: sections model, initial_stress, material, pool, boundary, output")
    mats = {m["name"]: m for m in case.get("material", [])}
    ok = set(mats) == MATERIALS and case.get("crs") == "EPSG:32632"
    ok = ok and mats["pool_c"].get("c_R") == 3.0 and mats["pool_a"].get("c_R") == 5.0 \
        and mats["interlayer"].get("c_R") == 5.0 and mats["surrounding_rock"].get("law") == "elastic"
    ok = ok and all(m.get("nu_z") == 0.3 and m.get("cm_a") == 1.0044e-2 and m.get("cm_b") == 1.1347 for m in mats.values())
    ok = ok and all(mats[n].get("K_m_per_s") == [2.04e-7, 2.04e-7, 2.04e-8] and mats[n].get("porosity") == 0.2
                    for n in ("pool_a", "pool_c", "aquifer_pool_a", "aquifer_pool_c"))
    ok = ok and mats["pool_c"].get("Eh_over_Ez") == 3.0 and mats["pool_c"].get("nuh_over_nuz") == 0.2
    check(ok, f"[{tag}] case.toml: seven materials with Tables 4.2 / 4.3 values, c_M law a=1.0044e-2 b=1.1347")
    ist = case.get("initial_stress", {})
    check(all(k in ist for k in ("lithostatic_gradient_MPa_per_m", "hydrostatic_gradient_MPa_per_m", "k0")),
          f"[{tag}] case.toml initial stress: lithostatic {ist.get('lithostatic_gradient_MPa_per_m')} MPa/m, "
          f"hydrostatic {ist.get('hydrostatic_gradient_MPa_per_m')} MPa/m, k0 {ist.get('k0')}")
    pools = case.get("pool", [])
    check(len(pools) == 2 and all(os.path.isfile(os.path.join(d, p["schedule"])) for p in pools)
          and all(m.get("biot") == 1.0 for m in mats.values())
          and case.get("water", {}).get("unit_weight_N_per_m3") == 9810.0,
          f"[{tag}] case.toml: two pools with existing schedules, alpha = 1, water unit weight 9810 N/m3")


def check_kernel(sample):
    """The InSAR generator's nucleus-of-strain sum reproduces Geertsma's closed form for a disk."""
    sys.path.insert(0, sample)
    import po_insar
    for radius, depth in ((1800.0, 1550.0), (3000.0, 1500.0)):
        cm = po_insar.c_m(19.9) / 3.0
        exact = po_insar.geertsma_disk_centre(cm, 3.8, 17.0, radius, depth)
        summed = po_insar.nuclei_disk_centre(cm, 3.8, 17.0, radius, depth)
        check(abs(summed / exact - 1.0) < 0.02,
              f"InSAR generator kernel: disk R={radius:g} m at {depth:g} m, dp=3.8 MPa, h=17 m, c_M/3: "
              f"{1000 * summed:.3f} mm vs Geertsma {1000 * exact:.3f} mm")


def check_twin(d, tag, variant):
    print(f"--- {tag}: {d}")
    for dirpath, dirnames, files in os.walk(d):
        bad = [f for f in files if f.endswith(".aux.xml")] + [x for x in dirnames if x.startswith(".generate.") or x == "__pycache__"]
        check(not bad, f"[{tag}] no side files in {os.path.relpath(dirpath, d)} {bad if bad else ''}")
    st = check_strata(d, tag)
    vec = check_vectors(d, tag, variant)
    e = vec["domain"]
    pref = vec["points"]["A016VJP"]
    arrays = check_rasters(d, tag, st, e, pref)
    ds = gdal.Open(os.path.join(d, st["surface"][0]["raster"]))
    cell = ds.GetGeoTransform()[1]
    ds = None
    check_pinchouts(tag, arrays, cell, pref, e)
    pr = check_pressures(d, tag)
    check_insar(d, tag, vec["points"], pr)
    check_case(d, tag)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sample", default=DEFAULT_SAMPLE, help="the committed sample folder")
    ap.add_argument("--workdir", default=None, help="scratch folder (default: a temporary one)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch folder")
    args = ap.parse_args()
    t0 = time.time()
    sample = os.path.abspath(args.sample)
    if args.workdir:
        os.makedirs(args.workdir, exist_ok=True)
    work = tempfile.mkdtemp(prefix="po-plain-test.", dir=args.workdir)
    try:
        small1, small2, full = (os.path.join(work, n) for n in ("small1", "small2", "full"))
        other = os.path.join(work, "small_seed7")
        if not all([run_generator(sample, small1, "--small"), run_generator(sample, small2, "--small"),
                    run_generator(sample, full), run_generator(sample, other, "--small", "--seed", "7")]):
            raise SystemExit(1)
        h1, h2 = file_digests(small1), file_digests(small2)
        check(h1 == h2 and len(h1) == 27, f"determinism: two runs with the same seed give identical bytes ({len(h1)} files)")
        hs = file_digests(other)
        diff = sorted(k for k in h1 if h1[k] != hs.get(k))
        check("insar_vertical.csv" in diff and "pressure_pool_c.csv" in diff,
              f"another seed changes the data ({len(diff)} files differ)")
        hf, hc = file_digests(full), file_digests(sample)
        stale = sorted(k for k in hf if hf[k] != hc.get(k))
        check(not stale, "committed full twin = generator output, bit for bit"
              + (f" (differs: {', '.join(stale)})" if stale else f" ({len(hf)} files)"))
        check_kernel(sample)
        check_twin(sample, "full", "full")
        check_twin(small1, "small", "small")
    finally:
        if not args.keep:
            shutil.rmtree(work, ignore_errors=True)
    n_fail = len(check.failed)
    print(f"--- {check.n_ok} checks passed, {n_fail} failed ({time.time() - t0:.1f} s)")
    for f in check.failed:
        print(f"failed: {f}")
    return 1 if n_fail else 0


if __name__ == "__main__":
    sys.exit(main())
