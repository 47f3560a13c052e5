"""End-to-end test of the po-plain pipeline (data-samples/po-plain/Makefile) at its tiny scale.

    /usr/bin/python3 tests/e2e/test_pipeline.py BUILD_DIR [WORK_DIR]

Runs plan -> mesh -> faults -> flow -> continuous mechanics -> faulted mechanics -> sampling ->
calibration -> report, then checks the headline numbers against ranges derived from the twin's own
parameters (case.toml, the traces, the pressure schedules) by closed forms — not against a previous
run:
  * storage 2015 uplift and 2015-16 settlement: Geertsma's disk (1973) for Pool C and Pool A, each
    with the area of its trace, thickness and depth at the crest, the unloading/reloading
    compressibility c_M(sigma_max) / c_R and the pool's pressure swing; the mesh is coarse and the
    model bottom and sides are fixed, so the range is a factor 0.4 .. 2.5 around the sum;
  * chi on the regional faults before production: the geostatic value on a plane of the fault's dip
    under sigma'_h = k0 sigma'_v with the case's friction angle (cohesionless, so the same at every
    depth), within 3 %; later chi never exceeds 1 (Mohr-Coulomb), and where a fault slips it does
    so at the depth of the depleted pools (the stress change is largest at the reservoir's edges);
  * c_R(Pool C) recovered by the calibration: the InSAR twin was made by the solver with c_R = 3
    (data-samples/po-plain/README.md) on the demo mesh; on the tiny mesh within +-0.6;
  * the seismicity forecast over 2025-2033 (docs/seismicity.md) from the faulted history: every fault of
    the case has a finite, positive expected count, the background rate r x area at the geostatic start
    (R/r = 1 exactly where the Coulomb stress change is 0), P = 1 - exp(-N), Gutenberg-Richter between
    the magnitudes, the sum over the faults, and the report's headline rows holding those counts;
  * the small ensemble (ensemble.toml: friction, A sigma, s_r; Morris on 2 levels): 8 members on two
    solver runs (the seismicity values are forecast-only), the friction at its two levels 27.5 and 32.5
    deg, members of one run with the same chi, mu* of the seismicity values exactly 0 on chi, a member's
    expected events equal to ugs-seismicity on its own per-pair CSVs with its own values, and the
    report's tornado chart and P(chi >= 0.8) / P(event) rows;
  * Make reruns only what an edit affects (a raster -> the mesh and what follows, not the plan).
"""

import csv
import datetime as dt
import math
import os
import shutil
import subprocess
import tempfile
import sys
import time
import tomllib

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
SAMPLE = os.path.join(ROOT, "data-samples", "po-plain")
failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        failures.append(what)


def pressure(path, date):
    with open(path, newline="") as fh:
        for r in csv.DictReader(fh):
            if r["date"] == date:
                return float(r["p_MPa"])
    raise KeyError(f"{path}: no row {date}")


def min_pressure(path):
    with open(path, newline="") as fh:
        return min(float(r["p_MPa"]) for r in csv.DictReader(fh))


def raster_at(path, x, y):
    from osgeo import gdal
    ds = gdal.Open(path)
    gt = ds.GetGeoTransform()
    col = int((x - gt[0]) / gt[1])
    row = int((y - gt[3]) / gt[5])
    return float(ds.GetRasterBand(1).ReadAsArray(col, row, 1, 1)[0, 0])


def trace_centroid(name):
    from osgeo import ogr
    ds = ogr.Open(os.path.join(SAMPLE, "reservoir_traces.geojson"))
    for f in ds.GetLayer(0):
        if f.GetField("name") == name:
            c = f.GetGeometryRef().Centroid()
            return c.GetX(), c.GetY(), f.GetField("area_km2") * 1e6
    raise KeyError(name)


def geertsma_centre(cm_per_MPa, dp_MPa, h, area, depth, nu=0.3):
    """Uplift (m) above the centre of a disk reservoir of the trace's area (Geertsma 1973)."""
    radius = math.sqrt(area / math.pi)
    eta = depth / radius
    return 2.0 * cm_per_MPa * (1.0 - nu) * dp_MPa * h * (1.0 - eta / math.sqrt(1.0 + eta * eta))


def expected_uplift(case, d1, d0):
    """Sum over the two pools of Geertsma's centre uplift for the pressure change d0 -> d1."""
    ist = case["initial_stress"]
    mats = {m["name"]: m for m in case["material"]}
    total = 0.0
    for pool, mat, top, base in (("Pool C", "pool_c", "07_pool_c_top", "08_pool_c_base"),
                                 ("Pool A", "pool_a", "05_pool_a_top", "06_pool_a_base")):
        x, y, area = trace_centroid(pool)
        zt = raster_at(os.path.join(SAMPLE, "surfaces", top + ".tif"), x, y)
        zb = raster_at(os.path.join(SAMPLE, "surfaces", base + ".tif"), x, y)
        zg = raster_at(os.path.join(SAMPLE, "surfaces", "01_dem.tif"), x, y)
        depth = zg - 0.5 * (zt + zb)
        sched = os.path.join(SAMPLE, next(p["schedule"] for p in case["pool"] if p["name"] == pool))
        m = mats[mat]
        p0 = pressure(sched, "1950-01-01")
        # preconsolidation: the geostatic effective stress plus the deepest depletion of the pool
        s0 = (ist["lithostatic_gradient_MPa_per_m"] - m["biot"] * ist["hydrostatic_gradient_MPa_per_m"]) * (
            ist["surface_elevation_m"] - 0.5 * (zt + zb))
        smax = s0 + m["biot"] * (p0 - min_pressure(sched))
        cm = m["cm_a"] * smax ** (-m["cm_b"]) / m["c_R"]
        dp = pressure(sched, d1) - pressure(sched, d0)
        total += geertsma_centre(cm, m["biot"] * dp, zt - zb, area, depth)
    return total * 1e3


def geostatic_chi(dip_deg, k0, phi_deg):
    d = math.radians(dip_deg)
    tau = (1.0 - k0) * math.sin(d) * math.cos(d)
    sn = math.cos(d) ** 2 + k0 * math.sin(d) ** 2
    return tau / (sn * math.tan(math.radians(phi_deg)))


def headlines(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(fh))


def value(rows, group_prefix, quantity):
    for r in rows:
        if r["group"].startswith(group_prefix) and r["quantity"] == quantity:
            return float(r["value_number"])
    raise KeyError(f"no headline '{group_prefix}' / '{quantity}'")


def data_rows(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(row for row in fh if not row.startswith("#")))


def check_forecast(out, case, rows, summary):
    """The rate-and-state forecast of the faulted history and its headline rows in the report."""
    seis = case["seismicity"]
    faults = [f["name"] for f in case["fault"]]
    r_km2, b, mc = seis["background_rate_per_yr_km2"], seis.get("b_value", 1.0), seis["M_c"]
    for f in ("forecast.csv", "forecast_windows.csv", "forecast_pairs.csv", "report/seismicity_rate_series.png",
              "report/seismicity_density.png"):
        check(os.path.isfile(os.path.join(out, f)), f"{f} written")
    path = os.path.join(out, "forecast.csv")
    with open(path) as fh:
        area = {line.split(":")[0][len("# fault "):]: float(line.rsplit("area_km2 = ", 1)[1])
                for line in fh if line.startswith("# fault ")}
    check(sorted(area) == sorted(faults) and all(a > 0 for a in area.values()),
          f"forecast.csv: every fault of the case with its area ({', '.join(f'{k} {v:.3g} km2' for k, v in sorted(area.items()))})")
    series = data_rows(path)
    first = [r for r in series if r["date"] == "1950-01-01"]
    check(len(first) == len(faults) and all(float(r["cfs_change_mean_MPa"]) == 0 and float(r["R_over_r"]) == 1 and
                                            abs(float(r["rate_per_yr"]) - r_km2 * area[r["fault"]]) <= 1e-12 * r_km2 * area[r["fault"]]
                                            for r in first),
          "1950-01-01: dCFS 0, R/r = 1 and the rate r x area on every fault (the steady state)")
    check(all(math.isfinite(float(r[k])) and float(r[k]) >= 0 for r in series
              for k in ("R_over_r", "R_over_r_max", "rate_per_yr", "events_from_start")),
          f"forecast.csv: {len(series)} rows, every R/r, rate and count finite and >= 0")
    win = data_rows(os.path.join(out, "forecast_windows.csv"))
    count = {(r["fault"], float(r["magnitude"])): float(r["expected_events"]) for r in win
             if (r["start"], r["end"]) == ("2025-01-01", "2033-01-01")}
    n = {f: count.get((f, mc), float("nan")) for f in faults}
    check(all(math.isfinite(v) and v > 0 for v in n.values()),
          "expected events M >= %g over 2025-2033 finite and > 0 on every fault: %s" % (
              mc, ", ".join(f"{f} {v:.3g}" for f, v in n.items())))
    total = count.get(("all", mc), float("nan"))
    check(abs(total - sum(n.values())) <= 1e-12 * total, f"all faults: {total:.4g} = the sum over the faults")
    check(all(abs(float(r["p_at_least_one"]) - -math.expm1(-float(r["expected_events"]))) <= 1e-12 for r in win),
          "P(at least one) = 1 - exp(-N) in every row")
    for m in seis.get("magnitudes", []):
        nm = count.get(("all", float(m)), float("nan"))
        ref = total * 10 ** (-b * (m - mc))
        check(abs(nm - ref) <= 1e-12 * ref, f"expected events M >= {m:g}: {nm:.4g} = Gutenberg-Richter {ref:.4g}")
    group = "seismicity, 2025-01-01 to 2033-01-01"
    for f in faults:
        q = f"expected events M ≥ {mc:g}, {f}"
        got = [float(r["value_number"]) for r in rows if r["group"] == group and r["quantity"] == q]
        check(len(got) == 1 and abs(got[0] - n[f]) <= 5e-3 * n[f], f"headline '{q}' = {n[f]:.3g} ({got})")
    q = "expected events M ≥ 2, all faults"
    got = [float(r["value_number"]) for r in rows if r["group"] == group and r["quantity"] == q]
    n2 = count.get(("all", 2.0), float("nan"))
    check(len(got) == 1 and abs(got[0] - n2) <= 5e-3 * n2 and q in summary, f"headline and summary '{q}' = {n2:.3g}")


def check_caprock(out, case, rows):
    """The seal check of the faulted run (docs/caprock.md): at 1950-01-01 (no pressure change, u = 0) each
    seal element's margins are the geostatic closed form of [initial_stress] (Biot 1, k0 < 1: S3 = S_h),
    with the element's pore pressure the highest of its nodes'; the report's safety headlines."""
    import h5py
    seals = case["seal"]
    table = data_rows(os.path.join(out, "faulted_caprock.csv"))
    first = [r for r in table if r["date"] == table[0]["date"]]
    check(table[0]["date"] == "1950-01-01" and sorted(r["seal"] for r in first) == sorted(s["material"] for s in seals),
          f"faulted_caprock.csv: one row per seal ({len(first)}) on the first date {table[0]['date']}")
    st = case["initial_stress"]
    zs, gl, gh, k0 = st["surface_elevation_m"], st["lithostatic_gradient_MPa_per_m"], st["hydrostatic_gradient_MPa_per_m"], st["k0"]
    with h5py.File(os.path.join(out, "faulted_caprock.h5"), "r") as f:
        x = f["mesh/coordinates"][:]
        tets = f["mesh/tetrahedra"][:]
        mat = f["mesh/material"][:]
    seal = seals[0]
    c, phi = seal["cohesion_MPa"], math.radians(seal["friction_deg"])
    tmin = smin = math.inf
    for t in tets:
        z = [x[n][2] for n in t]
        dc, dn = zs - sum(z) / 4, zs - min(z)
        sv, sh, p = gl * dc, k0 * (gl - gh) * dc + gh * dc, gh * dn
        s1, s3 = max(sv, sh) - p, min(sv, sh) - p
        tmin = min(tmin, min(sv, sh) + seal["tensile_strength_MPa"] - p)
        smin = min(smin, c * math.cos(phi) + 0.5 * (s1 + s3) * math.sin(phi) - 0.5 * (s1 - s3))
    got_t, got_s = float(first[0]["min_tensile_margin_MPa"]), float(first[0]["min_shear_margin_MPa"])
    check(len(seals) == 1 and len(set(mat)) == 1 and abs(got_t - tmin) <= 1e-3 and abs(got_s - smin) <= 1e-3,
          f"geostatic seal margins {got_t:.4f} / {got_s:.4f} MPa = closed form {tmin:.4f} / {smin:.4f} MPa "
          f"over {len(tets)} {seal['material']} elements")
    pics = [f for f in os.listdir(os.path.join(out, "report")) if f.startswith("seal_")]
    check({"seal_base_tensile.png", "seal_base_shear.png"} <= set(pics) and any(f.startswith("seal_sec_") for f in pics),
          f"report: the seal's margins on its base and along the sections ({len(pics)} pictures)")
    safety = {r["quantity"]: r["value"] for r in rows if r["group"] == "safety"}
    pools = [q for q in safety if q.startswith("maximum safe pressure, ")]
    margins = [q for q in safety if q.startswith("caprock: smallest")]
    # At the tiny scale local_2 slips in every cycle, before the reference date: no scale is safe, and
    # then no pool has a safe pressure either.
    none = safety.get("maximum safe scale of the swing", "").startswith("none")
    check("what limits it" in safety and len(pools) == (0 if none else len(case["pool"])) and len(margins) == 2,
          f"report: what limits the safe scale ({safety.get('what limits it', 'missing')}), the safe pressure of "
          f"{len(pools)} pools, {len(margins)} caprock margins")


def check_ensemble(build, out, summary, rows):
    """The small ensemble of the demo (ensemble.toml) and its rows in the report."""
    ens = os.path.join(out, "ensemble")
    members = data_rows(os.path.join(ens, "members.csv"))
    fric, a_sigma, s_r = "friction_deg (all faults)", "seismicity.A_sigma_MPa", "seismicity.stressing_rate_MPa_per_yr"
    check(len(members) == 8 and all(m["status"] == "ok" for m in members), f"ensemble: {len(members)} members, all ok")
    levels = sorted({float(m[fric]) for m in members})
    check(len(levels) == 2 and all(abs(x - y) <= 1e-9 for x, y in zip(levels, (27.5, 32.5))),
          f"ensemble: the friction at its two Morris levels {levels} (27.5, 32.5 deg)")
    entries = {m["entry"] for m in members}
    runs = [d for d in os.listdir(os.path.join(out, "ensemble.cache")) if d.startswith("member-")]
    check(len(entries) == 2 and len(runs) == 2, f"ensemble: {len(entries)} entries, {len(runs)} solver runs for 8 members")
    chi = [k for k in members[0] if k.startswith("chi_max.")]
    same = all(m[k] == n[k] for m in members for n in members if m["entry"] == n["entry"] for k in chi)
    check(chi and same, f"ensemble: members sharing a run have the same {len(chi)} chi metrics")
    morris = data_rows(os.path.join(ens, "morris.csv"))
    zero = [r for r in morris if r["parameter"] in (a_sigma, s_r) and r["metric"].startswith("chi_max.")]
    check(zero and all(float(r["mu_star"]) == 0 for r in zero), f"morris: mu* of A sigma and s_r exactly 0 on chi ({len(zero)} rows)")
    # Member 1's forecast again by ugs-seismicity on its per-pair CSVs, with its values in a case copy.
    m = members[0]
    folder = os.path.join(out, "ensemble.cache", m["entry"])
    with open(os.path.join(folder, "case.toml")) as fh:
        text = fh.read()
    text = text.replace("A_sigma_MPa = 0.05", f"A_sigma_MPa = {float(m[a_sigma])!r}")
    text = text.replace("stressing_rate_MPa_per_yr = 1e-3", f"stressing_rate_MPa_per_yr = {float(m[s_r])!r}")
    work = tempfile.mkdtemp(prefix="ugs-e2e-ensemble-")  # not in OUT: the determinism test compares OUT's files
    copy = os.path.join(work, "case.toml")
    with open(copy, "w") as fh:
        fh.write(text)
    pairs = sorted(os.path.join(folder, f) for f in os.listdir(folder) if "_fault_" in f and f.endswith(".csv"))
    table = os.path.join(work, "forecast.csv")
    r = subprocess.run([f"{build}/tools/ugs-seismicity/ugs-seismicity", *pairs, "--case", copy, "--start", "2025-01-01",
                        "--window", "2025-01-01/2033-01-01", "-q", "-o", table], capture_output=True, text=True)
    win = data_rows(table[:-4] + "_windows.csv") if r.returncode == 0 else []
    shutil.rmtree(work)
    mc = tomllib.loads(text)["seismicity"]["M_c"]
    n = [float(w["expected_events"]) for w in win if w["fault"] == "all" and float(w["magnitude"]) == mc]
    got = float(m["seismic_events.all.forecast"])
    check(len(n) == 1 and abs(got - n[0]) <= 1e-9 * n[0],
          f"member 1 (A sigma {float(m[a_sigma]):.4g} MPa, s_r {float(m[s_r]):.3g} MPa/yr): {got:.6g} expected events = "
          f"ugs-seismicity on its own CSVs {n}" + (f" ({r.stderr.strip()})" if r.returncode else ""))
    for f in ("report/ensemble_tornado_morris.png",):
        check(os.path.isfile(os.path.join(out, f)), f"{f} written")
    chi_rows = [x for x in rows if x["group"] == "ensemble" and x["quantity"].startswith("P(chi >= 0.8)")]
    event_rows = [x for x in rows if x["group"].startswith("ensemble, seismicity window") and x["quantity"].startswith("P(event")]
    check(len(chi_rows) >= 2 and event_rows and "8 of 8" in summary,
          f"report: {len(chi_rows)} P(chi >= 0.8) rows, {len(event_rows)} P(event) rows, '8 of 8' members")


def main():
    build = os.path.abspath(sys.argv[1])
    out = os.path.abspath(sys.argv[2]) if len(sys.argv) > 2 else os.path.join(build, "e2e-tiny")
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    make = ["make", "-s", "-j2", "-C", SAMPLE, f"UGS_BIN={build}/tools", f"OUT={out}", "SCALE=tiny"]
    subprocess.run(["rm", "-rf", out], check=True)
    t0 = time.time()
    r = subprocess.run(make + ["demo"], env=env, capture_output=True, text=True)
    elapsed = time.time() - t0
    if r.returncode != 0:
        print(r.stdout[-3000:], r.stderr[-3000:])
    check(r.returncode == 0, f"make demo SCALE=tiny exits 0 ({elapsed:.0f} s)")
    if r.returncode != 0:
        return 1
    check(f"the report is {out}/report/summary.md" in r.stdout, "make demo prints where the report is")

    for f in ("model.msh", "faulted.msh", "pool_a_dp.h5", "pool_c_dp.h5", "solve.h5", "solve.xdmf", "solve_top.h5",
              "faulted_faults.h5", "faulted_faults.xdmf", "faulted_faults.csv", "faulted_history.h5", "samples.csv",
              "calibration/best.toml", "report/summary.md", "report/summary.html", "report/headlines.csv"):
        check(os.path.isfile(os.path.join(out, f)), f"{f} written")
    pngs = [f for f in os.listdir(os.path.join(out, "report")) if f.endswith(".png")]
    tifs = [f for f in os.listdir(os.path.join(out, "report")) if f.endswith(".tif")]
    check(len(pngs) >= 20 and len(tifs) >= 9, f"report: {len(pngs)} PNG, {len(tifs)} GeoTIFF")
    with open(os.path.join(out, "report", "summary.md")) as fh:
        summary = fh.read()
    check("## Comparison with the thesis" in summary, "the summary says where and why the numbers differ from the thesis'")

    with open(os.path.join(SAMPLE, "case.toml"), "rb") as fh:
        case = tomllib.load(fh)
    rows = headlines(os.path.join(out, "report", "headlines.csv"))

    up = value(rows, "storage 2015", "maximum uplift")
    up_ref = expected_uplift(case, "2015-11-01", "2015-05-01")
    check(0.4 * up_ref <= up <= 2.5 * up_ref,
          f"storage 2015 uplift {up:.2f} mm within 0.4 .. 2.5 x Geertsma's {up_ref:.2f} mm")
    down = value(rows, "production 2015", "maximum settlement")
    down_ref = -expected_uplift(case, "2016-05-01", "2015-11-01")
    check(0.4 * down_ref <= down <= 2.5 * down_ref,
          f"production 2015-16 settlement {down:.2f} mm within 0.4 .. 2.5 x Geertsma's {down_ref:.2f} mm")
    fc = value(rows, "forecast storage 2025", "maximum uplift")
    fc_ref = expected_uplift(case, "2025-11-01", "2025-05-01")
    check(0.4 * fc_ref <= fc <= 2.5 * fc_ref and fc > up,
          f"forecast 2025 uplift {fc:.2f} mm within 0.4 .. 2.5 x Geertsma's {fc_ref:.2f} mm and above 2015's")

    from osgeo import ogr
    fault_ds = ogr.Open(os.path.join(SAMPLE, "faults.geojson"))  # (kept: its layer dies with it)
    faults = {f.GetField("name"): f.GetField("dip_deg") for f in fault_ds.GetLayer(0)}
    k0 = case["initial_stress"]["k0"]
    with open(os.path.join(out, "faulted_faults.csv"), newline="") as fh:
        stats = list(csv.DictReader(row for row in fh if not row.startswith("#")))
    tops = [raster_at(os.path.join(SAMPLE, "surfaces", s + ".tif"), *trace_centroid(p)[:2])
            for s, p in (("05_pool_a_top", "Pool A"), ("07_pool_c_top", "Pool C"))]
    bases = [raster_at(os.path.join(SAMPLE, "surfaces", s + ".tif"), *trace_centroid(p)[:2])
             for s, p in (("06_pool_a_base", "Pool A"), ("08_pool_c_base", "Pool C"))]
    for name in ("overthrust_north", "backthrust_south"):
        phi = next(f["friction_deg"] for f in case["fault"] if f["name"] == name)
        ref = geostatic_chi(faults[name], k0, phi)
        rows_f = [r for r in stats if r["fault"] == name]
        chi0 = float(rows_f[0]["max_chi"])
        check(rows_f[0]["date"] == "1950-01-01" and abs(chi0 - ref) <= 0.03 * ref,
              f"initial chi on {name} {chi0:.4f} = geostatic {ref:.4f} (dip {faults[name]} deg) within 3 %")
        check(all(float(r["max_chi"]) <= 1 + 1e-6 for r in rows_f), f"chi on {name} never above 1")
        slip_z = [float(r["z_m"]) for r in rows_f if int(r["slipping"]) > 0]
        lo, hi = min(bases) - 500.0, max(tops) + 500.0
        check(all(lo <= z <= hi for z in slip_z),
              f"{name} slips only at the pools' depth ({len(slip_z)} dates with slip, z in [{lo:.0f}, {hi:.0f}] m)")

    check_forecast(out, case, rows, summary)
    check_caprock(out, case, rows)
    check_ensemble(build, out, summary, rows)

    with open(os.path.join(out, "calibration", "best.toml"), "rb") as fh:
        best = tomllib.load(fh)
    cr = next(m["c_R"] for m in best["material"] if m["name"] == "pool_c")
    check(abs(cr - 3.0) <= 0.6, f"calibrated c_R(Pool C) = {cr:.3f} (twin: 3, tolerance 0.6 on the tiny mesh)")

    # Make's dependencies: a raster edit reruns the mesh and what follows, not the plan or the flow
    # schedules' CSVs; nothing to do on an unchanged tree.
    r = subprocess.run(make + ["-n", "demo"], env=env, capture_output=True, text=True)
    check(r.returncode == 0 and "ugs-" not in r.stdout, "nothing reruns on an unchanged tree")
    r = subprocess.run(make + ["-n", "-W", "surfaces/05_pool_a_top.tif", "demo"], env=env, capture_output=True, text=True)
    cmds = r.stdout
    check("ugs-meshgen" in cmds and "ugs-solve" in cmds and "ugs-report" in cmds and "ugs-mesh2d" not in cmds,
          "a raster edit reruns meshgen .. report but not mesh2d")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
