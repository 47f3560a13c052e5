#!/usr/bin/python3
"""Generate the po-plain synthetic twin (data-samples/po-plain/README.md documents every file).

usage: generate.py [--out DIR] [--seed N] [--small | --variant {full,small}] [-q]

  --out DIR     output directory (default: the folder of this script, i.e. the committed sample)
  --seed N      seed of every random choice (default 1948); same seed, same bytes
  --small       the small twin (14 x 12 km, 250 m cells) used by fast tests
  -q            quiet

Example:
  /usr/bin/python3 data-samples/po-plain/generate.py --out /tmp/po-small --small

Outputs are written to a hidden temporary folder inside DIR and moved into place only when all of
them are complete.
"""

import sys

sys.dont_write_bytecode = True      # keep the source folder free of __pycache__

import argparse  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402
import tempfile  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
if HERE not in sys.path:
    sys.path.insert(0, HERE)

import numpy as np  # noqa: E402
from osgeo import ogr, osr  # noqa: E402

import po_field as F  # noqa: E402
import po_insar as I  # noqa: E402
import po_io as IO  # noqa: E402
import po_pressure as PP  # noqa: E402
import po_toml as T  # noqa: E402
import po_vectors as V  # noqa: E402

VARIANTS = {
    # domain, raster cell, far-field mesh size, reservoir mesh size (m)
    "full": (F.DOMAIN_FULL, F.CELL_FULL, 2000.0, 50.0),
    "small": (F.DOMAIN_SMALL, F.CELL_SMALL, 500.0, 100.0),
}

OUTPUTS = [
    "domain.geojson", "refinement.geojson", "reservoir_traces.geojson", "aquifers.geojson",
    "faults.geojson", "fault_footprints.geojson", "sections.geojson", "ps_points.geojson",
] + ["surfaces/" + s[1] for s in F.SURFACES] + [
    "strata.toml", "strata_coarse.toml", "strata_faulted.toml", "case.toml", "pressure_pool_a.csv", "pressure_pool_c.csv",
    "insar_vertical.csv", "insar_east.csv",
]


def log(args, msg):
    if not args.quiet:
        print(f"generate: {msg}", file=sys.stderr)


# --------------------------------------------------------------------------------------------------
def build_surfaces(field, grid):
    """Rasters of the 11 surfaces; bilinear value at A016VJP equals Table 4.1; never crossing."""
    X, Y = grid.centres()
    gt = grid.geotransform()
    xP, yP = F.P_REF
    t = {s[0]: s[3] for s in F.SURFACES}
    S = {}
    for key in ("dem", "alluvial_base", "santerno_top", "up_sands_base", "pool_a_top", "limestones_top"):
        a = field.surface_indep(key, t[key], X, Y)
        S[key] = a + (t[key] - IO.bilinear(a, gt, xP, yP))     # exact under bilinear sampling

    def thick(unit, target):
        a = field.thickness(unit, target, X, Y)
        if target == 0.0:
            for c in IO.bilinear_cells(gt, xP, yP):
                if a[c] != 0.0:
                    raise RuntimeError(f"{unit}: not pinched out around A016VJP")
            return a
        return a * (target / IO.bilinear(a, gt, xP, yP))

    S["pool_a_base"] = S["pool_a_top"] - thick("Pool A", t["pool_a_top"] - t["pool_a_base"])
    S["pool_c_top"] = S["pool_a_base"] - thick("Interlayer", t["pool_a_base"] - t["pool_c_top"])
    S["pool_c_base"] = S["pool_c_top"] - thick("Pool C", t["pool_c_top"] - t["pool_c_base"])
    S["miocene_clays_top"] = S["pool_c_base"] - thick("Miocene sands", t["pool_c_base"] - t["miocene_clays_top"])
    S["marls_top"] = S["miocene_clays_top"] - thick("Miocene clays", 0.0)
    out = {k: np.round(v, 3).astype(np.float32) for k, v in S.items()}   # mm; rounding is monotone

    keys = [s[0] for s in F.SURFACES]
    for a, b in zip(keys[:-1], keys[1:]):
        if not (out[a] >= out[b]).all():
            raise RuntimeError(f"surface {a} below {b}")
    if not (out["limestones_top"] > F.MODEL_BOTTOM).all():
        raise RuntimeError("limestones top below the model bottom")
    for k in keys:
        v = IO.bilinear(out[k], gt, xP, yP)
        if abs(v - t[k]) > 0.01:
            raise RuntimeError(f"{k}: {v} at A016VJP, expected {t[k]}")
    return out


# --------------------------------------------------------------------------------------------------
def clip(geom, domain_geom):
    if domain_geom.Contains(geom):
        return geom
    g = geom.Intersection(domain_geom)
    if g is None or g.IsEmpty():
        return None
    return g


def shrink(domain, d):
    xmin, ymin, xmax, ymax = domain
    return (xmin + d, ymin + d, xmax - d, ymax - d)


def rect(domain):
    xmin, ymin, xmax, ymax = domain
    return V.polygon_geom([(xmin, ymin), (xmax, ymin), (xmax, ymax), (xmin, ymax), (xmin, ymin)])


def write_vectors(tmp, field, variant, domain, size_far, size_res, seed):
    epsg = F.EPSG
    dom = rect(domain)
    inner = rect(shrink(domain, VARIANTS[variant][1]))

    IO.write_geojson(os.path.join(tmp, "domain.geojson"), "domain", epsg, ogr.wkbPolygon,
                     [("name", "str"), ("variant", "str"), ("size_m", "real")],
                     [({"name": "domain", "variant": variant, "size_m": size_far}, dom)])

    traces = {p: V.trace(field, p) for p in ("Pool A", "Pool C")}
    feats = []
    for p in ("Pool A", "Pool C"):
        g = V.polygon_geom(traces[p])
        if not dom.Contains(g):
            raise RuntimeError(f"trace of {p} leaves the domain")
        feats.append(({"name": p, "gwc_m": V.GWC[p], "area_km2": round(g.GetArea() / 1e6, 3),
                       "note": "contour of the pool top at the gas-water contact" +
                       ("; closed towards E-NE by the pinch-out" if p == "Pool C" else "")}, g))
    IO.write_geojson(os.path.join(tmp, "reservoir_traces.geojson"), "reservoir_traces", epsg, ogr.wkbPolygon,
                     [("name", "str"), ("gwc_m", "real"), ("area_km2", "real"), ("note", "str")], feats)

    union = V.polygon_geom(traces["Pool A"]).Union(V.polygon_geom(traces["Pool C"]))
    ref = union.Buffer(150.0, 4)
    IO.write_geojson(os.path.join(tmp, "refinement.geojson"), "refinement", epsg, ogr.wkbPolygon,
                     [("name", "str"), ("size_m", "real")],
                     [({"name": "reservoir", "size_m": size_res}, ref)])

    aquifers = {u: V.aquifer(field, u) for u in ("Pool A", "Interlayer", "Pool C")}
    feats = []
    for u in ("Pool A", "Interlayer", "Pool C"):
        g = clip(aquifers[u], dom)
        if g.GetGeometryType() != ogr.wkbPolygon:
            raise RuntimeError(f"aquifer of {u} is not a single polygon")
        feats.append(({"name": u, "unit": u, "fault_z_m": V.AQUIFER_Z[u],
                       "note": "between its hydraulic limits across the axis at fault_z_m (the regional faults run"
                       f" at least {V.FAULT_CLEARANCE:.0f} m outside), within 9 km of the crest along the axis"
                       + ("; ends at the pinch-out of Pool C" if u == "Pool C" else "")}, g))
    IO.write_geojson(os.path.join(tmp, "aquifers.geojson"), "aquifers", epsg, ogr.wkbPolygon,
                     [("name", "str"), ("unit", "str"), ("fault_z_m", "real"), ("note", "str")], feats)

    faults = V.regional_fault_lines() + V.local_fault_lines()
    for i, (f1, l1) in enumerate(faults):
        for f2, l2 in faults[i + 1:]:
            if V.min_separation(f1, l1, f2, l2) < 300.0:
                raise RuntimeError(f"faults {f1['name']} and {f2['name']} come closer than 300 m")
    for f, line in V.regional_fault_lines():   # outside the depleted volume (thesis 4.3.4)
        for u, g in aquifers.items():
            d = V.aquifer_clearance(f, line, g)
            if d < V.FAULT_CLEARANCE:
                raise RuntimeError(f"fault {f['name']} comes {d:.0f} m from the {u} aquifer over the sands' "
                                   f"depths (at least {V.FAULT_CLEARANCE:.0f} m)")
    feats = []
    for f, line in faults:
        trace_z = V.REGIONAL_TRACE_Z if f in V.REGIONAL_FAULTS else f["top_m"]
        g = clip(V.line_geom(V.fault_line_at(f, line, trace_z)), inner)
        if g is None:
            continue
        if g.GetGeometryType() != ogr.wkbLineString:
            raise RuntimeError(f"fault {f['name']} splits when clipped")
        kind = f.get("kind", "local_extensional")
        note = f.get("note", "sub-vertical extensional/transtensive fault across the top of the trap")
        feats.append(({"name": f["name"], "kind": kind, "top_m": f["top_m"], "bottom_m": f["bottom_m"],
                       "dip_deg": f["dip_deg"], "dip_dir_deg": f["dip_dir_deg"], "trace_z_m": trace_z,
                       "note": note}, g))
    IO.write_geojson(os.path.join(tmp, "faults.geojson"), "faults", epsg, ogr.wkbLineString,
                     [("name", "str"), ("kind", "str"), ("top_m", "real"), ("bottom_m", "real"),
                      ("dip_deg", "real"), ("dip_dir_deg", "real"), ("trace_z_m", "real"), ("note", "str")], feats)

    feats = []
    for f, line in V.regional_fault_lines():
        g = clip(V.fault_footprint(f, line), dom)
        if g is None or g.GetGeometryType() != ogr.wkbPolygon:
            raise RuntimeError(f"footprint of fault {f['name']} is not a single polygon in the domain")
        feats.append(({"name": f["name"], "top_m": f["top_m"], "bottom_m": f["bottom_m"],
                       "note": "plan projection of the fault surface + 250 m: refinement of the faulted model's plan"}, g))
    IO.write_geojson(os.path.join(tmp, "fault_footprints.geojson"), "fault_footprints", epsg, ogr.wkbPolygon,
                     [("name", "str"), ("top_m", "real"), ("bottom_m", "real"), ("note", "str")], feats)

    feats = []
    for attrs, line in V.sections():
        g = V.line_geom(line)
        if not dom.Contains(g):
            raise RuntimeError(f"section {attrs['name']} leaves the domain")
        a = dict(attrs)
        a["length_m"] = round(g.Length(), 2)
        feats.append((a, g))
    IO.write_geojson(os.path.join(tmp, "sections.geojson"), "sections", epsg, ogr.wkbLineString,
                     [("name", "str"), ("from_label", "str"), ("to_label", "str"), ("view", "str"),
                      ("length_m", "real"), ("note", "str")], feats)

    pts = F.ps_points()
    heights = ps_heights(field, seed, pts)
    feats = []
    for (pid, x, y, inside, note), h in zip(pts, heights):
        g = ogr.Geometry(ogr.wkbPoint)
        g.AddPoint_2D(x, y)
        if not dom.Contains(g):
            raise RuntimeError(f"PS point {pid} outside the domain")
        for p in ("Pool A", "Pool C"):
            if bool(V.point_in_ring(x, y, traces[p])) != inside:
                raise RuntimeError(f"PS point {pid}: inside {p} trace = {not inside}, expected {inside}")
        feats.append(({"pid": pid, "inside": 1 if inside else 0, "height": round(h, 1), "note": note}, g))
    IO.write_geojson(os.path.join(tmp, "ps_points.geojson"), "ps_points", epsg, ogr.wkbPoint,
                     [("pid", "str"), ("inside", "int"), ("height", "real"), ("note", "str")], feats)
    return traces, aquifers, pts, heights


def ps_heights(field, seed, pts):
    """Orthometric height of each scatterer: ground (DEM) plus the height of the building (4-18 m)."""
    rng = np.random.default_rng([seed, 400])
    b = rng.uniform(4.0, 18.0, len(pts))
    return [float(field.surface_indep("dem", 50.0, np.array(x), np.array(y))) + bi
            for (pid, x, y, _, _), bi in zip(pts, b)]


def to_3035(pts):
    src = IO.srs_of(F.EPSG)
    dst = IO.srs_of(3035)
    ct = osr.CoordinateTransformation(src, dst)
    return [ct.TransformPoint(x, y)[:2] for _, x, y, _, _ in pts]


# --------------------------------------------------------------------------------------------------
def generate(args):
    variant = "small" if args.small else args.variant
    domain, cell, size_far, size_res = VARIANTS[variant]
    out = os.path.abspath(args.out)
    os.makedirs(out, exist_ok=True)
    tmp = tempfile.mkdtemp(prefix=".generate.", dir=out)
    try:
        os.makedirs(os.path.join(tmp, "surfaces"))
        field = F.Field(args.seed)

        grid = IO.Grid(domain, cell, margin_cells=1)
        log(args, f"{variant} twin, seed {args.seed}: surfaces {grid.nx} x {grid.ny} cells of {cell:g} m")
        S = build_surfaces(field, grid)
        for key, fname, name, z, unit, layers in F.SURFACES:
            IO.write_geotiff(os.path.join(tmp, "surfaces", fname), S[key], grid, F.EPSG, name, {
                "SURFACE": name, "UNIT_BELOW": unit, "LAYERS_BELOW": layers,
                "ELEVATION_AT_A016VJP_M": f"{z:.1f}", "GENERATOR": "data-samples/po-plain/generate.py",
                "SEED": args.seed, "VARIANT": variant})

        log(args, "vectors: domain, traces, aquifers, faults, fault footprints, sections, PS points")
        traces, aquifers, pts, heights = write_vectors(tmp, field, variant, domain, size_far, size_res, args.seed)

        with open(os.path.join(tmp, "strata.toml"), "w", newline="\n") as fh:
            fh.write(T.strata_toml(variant, args.seed))
        with open(os.path.join(tmp, "strata_coarse.toml"), "w", newline="\n") as fh:
            fh.write(T.strata_toml(variant, args.seed, coarse=True))
        with open(os.path.join(tmp, "strata_faulted.toml"), "w", newline="\n") as fh:
            fh.write(T.strata_toml(variant, args.seed, faulted=True))
        with open(os.path.join(tmp, "case.toml"), "w", newline="\n") as fh:
            fh.write(T.case_toml(variant, args.seed))

        log(args, "pressure histories 1950-01 .. 2033-12")
        dates, pa = PP.pool_a(args.seed)
        _, pc = PP.pool_c(args.seed)
        PP.write_csv(os.path.join(tmp, "pressure_pool_a.csv"), dates, pa)
        PP.write_csv(os.path.join(tmp, "pressure_pool_c.csv"), dates, pc)

        solver_model = os.path.join(HERE, "insar_model.csv")
        if not os.path.isfile(solver_model):
            solver_model = None
        log(args, "InSAR series (" + ("ugs-solve's displacement in insar_model.csv + noise" if solver_model
                                      else "Geertsma nuclei of strain + trend + noise") + ")")
        obs, data, _ = I.series(field, args.seed, traces, {"Pool A": aquifers["Pool A"], "Pool C": aquifers["Pool C"]},
                                {"Pool A": pa, "Pool C": pc}, pts, solver_model)
        en = to_3035(pts)
        I.write_egms_csv(os.path.join(tmp, "insar_vertical.csv"), pts, heights, en, obs, data["U"])
        I.write_egms_csv(os.path.join(tmp, "insar_east.csv"), pts, heights, en, obs, data["E"])

        missing = [p for p in OUTPUTS if not os.path.isfile(os.path.join(tmp, p))]
        extra = sorted(set(os.path.relpath(os.path.join(d, f), tmp) for d, _, fs in os.walk(tmp) for f in fs)
                       - set(OUTPUTS))
        if missing or extra:
            raise RuntimeError(f"outputs missing {missing} or unexpected {extra}")
        os.makedirs(os.path.join(out, "surfaces"), exist_ok=True)
        for p in OUTPUTS:
            os.replace(os.path.join(tmp, p), os.path.join(out, p))
        log(args, f"wrote {len(OUTPUTS)} files to {out}")
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog="generate.py", description="Generate the po-plain synthetic twin (see README.md).",
        epilog="example: /usr/bin/python3 data-samples/po-plain/generate.py --out /tmp/po-small --small",
        formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", default=HERE, help="output directory (default: %(default)s)")
    ap.add_argument("--seed", type=int, default=F.SEED_DEFAULT, help="seed (default: %(default)s)")
    ap.add_argument("--variant", choices=sorted(VARIANTS), default="full", help="twin to build (default: full)")
    ap.add_argument("--small", action="store_true", help="same as --variant small")
    ap.add_argument("-q", "--quiet", action="store_true", help="no progress on stderr")
    args = ap.parse_args(argv)
    try:
        generate(args)
    except (RuntimeError, ValueError, OSError) as e:
        print(f"generate.py: error: {e}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
