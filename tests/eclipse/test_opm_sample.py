#!/usr/bin/python3
"""`make -C data-samples/po-plain opm` at SCALE=tiny, one storage year (OPM_YEARS=1), checked.

usage: test_opm_sample.py BUILD_DIR WORK_DIR --first-run PIPELINE_OUT

The tiny mesh and ugs-flow's fields come from the pipeline test's output (PIPELINE_OUT, the fixture
po_plain_tiny), copied into WORK_DIR so that run's folder is not touched. Then make runs OPM Flow on the
Pool C deck, the import, the two ugs-solve runs and the comparison. Checks:
  - every tetrahedron of the imported dp.h5 at every report step: dp equals PRESSURE(step) -
    PRESSURE(first step) of the grid cell holding its centroid, the cell found here from the EGRID's
    pillars and ZCORN and the restart read with a reader of our own (opm/eclbin.py), not EclIO;
    within 1 m of a cell face any neighbour's value is accepted;
  - the uplift over Pool C has the sign of the pressure change: up on injection (2003-04 -> 2003-11),
    down on production (2003-11 -> 2004-04), from the simulator's pressures and from the flow model,
    and the two agree within a factor of 2 at the end of injection.
"""
import sys

sys.dont_write_bytecode = True   # keep data-samples/po-plain/opm free of __pycache__

import os  # noqa: E402
import shutil
import subprocess
import time

import h5py
import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLE = os.path.join(os.path.dirname(os.path.dirname(HERE)), "data-samples", "po-plain")
sys.path.insert(0, os.path.join(SAMPLE, "opm"))
import eclbin  # noqa: E402

FAILS = []


def check(cond, what):
    print(("ok   " if cond else "FAIL ") + what)
    if not cond:
        FAILS.append(what)


def locate(egrid, pts):
    """(ijk natural index or -1, distance to the nearest face in m) of map points, vertical pillars."""
    g = dict(eclbin.read(egrid))
    nx, ny, nz = (int(v) for v in g["GRIDHEAD"][1:4])
    ma = g["MAPAXES"].astype(float)
    ox, oy = ma[2], ma[3]
    coord = g["COORD"].astype(float).reshape(ny + 1, nx + 1, 6)
    # the deck's pillars are vertical on a regular grid: check that, then index directly
    assert np.allclose(coord[..., 0], coord[..., 3]) and np.allclose(coord[..., 1], coord[..., 4])
    dx = coord[0, 1, 0] - coord[0, 0, 0]
    dy = coord[1, 0, 1] - coord[0, 0, 1]
    z = g["ZCORN"].astype(float).reshape(nz, 2, ny, 2, nx, 2)
    fx = (pts[:, 0] - ox) / dx
    fy = (pts[:, 1] - oy) / dy
    depth = -pts[:, 2]
    i = np.floor(fx).astype(int)
    j = np.floor(fy).astype(int)
    idx = np.full(len(pts), -1)
    dist = np.zeros(len(pts))
    for n in range(len(pts)):
        if not (0 <= i[n] < nx and 0 <= j[n] < ny):
            continue
        tx, ty = fx[n] - i[n], fy[n] - j[n]
        dh = min(tx * dx, (1 - tx) * dx, ty * dy, (1 - ty) * dy)
        # horizon depths at the point: bilinear over the column's 4 corners, top of each layer and base
        c = z[:, :, j[n], :, i[n], :]                     # (nz, top/bottom, y, x)
        h = (1 - tx) * (1 - ty) * c[:, :, 0, 0] + tx * (1 - ty) * c[:, :, 0, 1] \
            + (1 - tx) * ty * c[:, :, 1, 0] + tx * ty * c[:, :, 1, 1]
        for k in range(nz):
            if h[k, 0] <= depth[n] <= h[k, 1]:
                idx[n] = i[n] + nx * (j[n] + ny * k)
                dist[n] = min(dh, depth[n] - h[k, 0], h[k, 1] - depth[n])
                break
        else:
            # just above the top or below the base of the bilinear horizons: the importer's cells have
            # triangulated faces (docs/eclipse.md), which depart from the bilinear surface by centimetres
            gap = max(h[0, 0] - depth[n], depth[n] - h[-1, 1])
            if gap < 1.0:
                k = 0 if depth[n] < h[0, 0] else nz - 1
                idx[n] = i[n] + nx * (j[n] + ny * k)
                dist[n] = 0.0
            else:
                dist[n] = gap
    return idx, dist, (nx, ny, nz), g["ACTNUM"]


def main():
    build, work = sys.argv[1], sys.argv[2]
    first = sys.argv[sys.argv.index("--first-run") + 1]
    if os.path.isdir(work):
        shutil.rmtree(work)
    os.makedirs(work)
    t = time.time() - 100
    for k, f in enumerate(["plan.msh", "model.msh", "pool_a.msh", "pool_c.msh", "pool_a_dp.h5", "pool_c_dp.h5"]):
        if os.path.exists(os.path.join(first, f)):
            shutil.copy(os.path.join(first, f), os.path.join(work, f))
            os.utime(os.path.join(work, f), (t + k, t + k))
    t0 = time.time()
    r = subprocess.run(["make", "-C", SAMPLE, "opm", "SCALE=tiny", "OPM_YEARS=1", "OUT=" + os.path.abspath(work),
                        "UGS_BIN=" + os.path.join(os.path.abspath(build), "tools")],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(r.stdout[-3000:])
    check(r.returncode == 0, "make opm exit 0 (%.1f s)" % (time.time() - t0))
    if r.returncode:
        return 1
    opm = os.path.join(work, "opm")
    steps = eclbin.restart_steps(os.path.join(opm, "POOL_C.UNRST"))
    check(len(steps) == 13 and steps[0][0] == "2003-04-01" and steps[-1][0] == "2004-04-01",
          "13 monthly report steps 2003-04-01 .. 2004-04-01 (%d)" % len(steps))

    with h5py.File(os.path.join(opm, "dp.h5"), "r") as f:
        xyz = f["mesh/coordinates"][:]
        tets = f["mesh/tetrahedra"][:]
        cen = xyz[tets].mean(axis=1)
        idx, dist, dims, actnum = locate(os.path.join(opm, "POOL_C.EGRID"), cen)
        active = np.cumsum(actnum > 0) - 1            # natural index -> active index
        check(len(tets) > 1000, "%d tetrahedra imported" % len(tets))
        check(bool((idx >= 0).all()), "every imported tetrahedron's centroid lies in the grid or within 1 m of"
              " it (%d farther; %d within 1 m)" % ((idx < 0).sum(), ((idx >= 0) & (dist == 0)).sum()))
        nx, ny, nz = dims
        keys = sorted(f["steps"])
        check(len(keys) == len(steps), "dp.h5 has the restart's %d steps (%d)" % (len(steps), len(keys)))
        bad = 0
        worst = 0.0
        for s, (date, p) in zip(keys, steps):
            st = f["steps"][s]
            d = st.attrs["date"]
            d = d.decode() if isinstance(d, bytes) else str(d)
            if d != date:
                check(False, "step %s date %s is the restart's %s" % (s, d, date))
            dp = st["cell/dp"][:]
            want = (p - steps[0][1]) * 1e5
            for n in range(len(tets)):
                c = idx[n]
                ok = c >= 0 and actnum[c] > 0 and abs(dp[n] - want[active[c]]) <= 1e-6 * 1e5
                if not ok and c >= 0 and dist[n] < 1.0:       # on a face: any neighbour
                    i, j, k = c % nx, (c // nx) % ny, c // (nx * ny)
                    for di, dj, dk in ((1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)):
                        ii, jj, kk = i + di, j + dj, k + dk
                        if 0 <= ii < nx and 0 <= jj < ny and 0 <= kk < nz:
                            m = ii + nx * (jj + ny * kk)
                            if actnum[m] > 0 and abs(dp[n] - want[active[m]]) <= 1e-6 * 1e5:
                                ok = True
                if not ok:
                    bad += 1
                elif c >= 0 and actnum[c] > 0:
                    worst = max(worst, abs(dp[n] - want[active[c]]) if dist[n] >= 1.0 else 0.0)
        check(bad == 0, "dp of every tetrahedron at every step = its cell's PRESSURE change "
              "(%d mismatches of %d; largest error off faces %.3g Pa)" % (bad, len(tets) * len(keys), worst))
        peak = max(np.abs(f["steps"][s]["cell/dp"][:]).max() for s in keys)
        check(peak > 1e6, "the imported dp reaches %.2f MPa (> 1 MPa)" % (peak / 1e6))

    rows = {}
    with open(os.path.join(opm, "comparison.csv")) as f:
        head = None
        for line in f:
            if line.startswith("#"):
                continue
            c = line.strip().split(",")
            if head is None:
                head = c
                continue
            rows[c[0]] = dict(zip(head[1:], map(float, c[1:])))
    check(set(rows) == {"2003-04-01", "2003-11-01", "2004-04-01"}, "comparison dates %s" % sorted(rows))
    if len(FAILS) == 0:
        a, b, c = rows["2003-04-01"], rows["2003-11-01"], rows["2004-04-01"]
        check(b["dp_opm_gas_MPa"] > 2 and c["dp_opm_gas_MPa"] - b["dp_opm_gas_MPa"] < -2,
              "gas cap: +%.2f MPa on injection, %.2f MPa on production"
              % (b["dp_opm_gas_MPa"], c["dp_opm_gas_MPa"] - b["dp_opm_gas_MPa"]))
        for run in ("opm", "flow"):
            up = b["uz_%s_mean_mm" % run] - a["uz_%s_mean_mm" % run]
            down = c["uz_%s_mean_mm" % run] - b["uz_%s_mean_mm" % run]
            check(up > 0.5 and down < -0.5, "%s: uplift %+.2f mm on injection, %+.2f mm on production"
                  % (run, up, down))
        ratio = b["uz_opm_mean_mm"] / b["uz_flow_mean_mm"]
        check(0.5 < ratio < 2.0, "uplift OPM / flow model at 2003-11-01: %.2f (0.5 .. 2)" % ratio)
        # ugs-report --compare computes the same means (C++, over the mesh's bnd:top nodes inside the
        # trace) as compare.py (numpy, over the top file's nodes): they must agree.
        rep = {}
        with open(os.path.join(opm, "report", "comparison.csv")) as f:
            next(f)
            for line in f:
                run, date, mean, _ = line.strip().split(",")
                rep[(run, date)] = float(mean)
        worst = 0.0
        for date, r in rows.items():
            for run, col in (("this run", "uz_opm_mean_mm"), ("schedule-driven flow model", "uz_flow_mean_mm")):
                got = rep.get((run, date))
                worst = max(worst, abs(got - (r[col] - a[col])) if got is not None else float("inf"))
        check(worst < 2e-4, "ugs-report's comparison.csv equals compare.py's mean uplift (largest difference %.2g mm)" % worst)
    return 1 if FAILS else 0


if __name__ == "__main__":
    sys.exit(main())
