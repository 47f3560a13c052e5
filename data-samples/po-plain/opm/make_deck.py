#!/usr/bin/python3
"""Writes the OPM Flow deck of the twin's Pool C (data-samples/po-plain/opm, docs/eclipse.md).

usage: make_deck.py OUT.DATA [--cell 250] [--layers 3] [--years 2]

A corner-point grid following the twin's Pool C top and base (surfaces/07_pool_c_top.tif,
surfaces/08_pool_c_base.tif, read with GDAL): vertical pillars every --cell metres over Pool C's trace
(reservoir_traces.geojson) and 2 km around it, --layers layers of equal thickness between the two
surfaces. Columns thinner than 0.5 m (the pinch-out to the E-NE) are inactive. MAPAXES puts the local
grid at its map origin (EPSG:32632, integers: exact in the EGRID's float32).

Three phases with an all-gas cap (OPM Flow 2022.10 stops a two-phase GAS WATER deck with "data member
deactivated"): the gas-oil contact at the gas-water contact of the trace (1,575 m), no oil zone. The
simulation starts on 1 April 2003 at the twin's pressure of that day (pressure_pool_c.csv) and follows
--years storage years: gas injected April-October, produced November-March, by three wells on the crest,
at rates that roughly reproduce the twin's seasonal swing (8.8 -> 12.2 MPa). One report step a month.
"""
import sys

sys.dont_write_bytecode = True

import argparse  # noqa: E402
import datetime  # noqa: E402
import json  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402
from osgeo import gdal  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))

SAMPLE = os.path.dirname(HERE)
START = datetime.date(2003, 4, 1)
GWC = 1575.0          # m below sea level: the gas-water contact of Pool C's trace
MARGIN = 2000.0       # m of aquifer around the trace
# Well rates (sm3/day, the three wells together) for injection (April-October) and production
# (November-March); tuned so the pool pressure swings about as pressure_pool_c.csv does.
INJ_RATE = 5.0e6
PROD_RATE = 7.0e6
WELLS = (("C1", -600.0, 0.0), ("C2", 0.0, 0.0), ("C3", 600.0, 0.0))   # offsets from the crest, m


def fail(msg):
    """Bad input: one line on stderr, exit 2 (docs/cli.md)."""
    print(msg, file=sys.stderr)
    sys.exit(2)


def raster(name):
    d = gdal.Open(os.path.join(SAMPLE, "surfaces", name))
    if d is None:
        fail("make_deck.py: cannot read surfaces/%s" % name)
    return d.ReadAsArray().astype(float), d.GetGeoTransform()


def sample(a, gt, x, y):
    """Bilinear value of raster a (pixel centres) at map points x, y."""
    fx = (x - gt[0]) / gt[1] - 0.5
    fy = (y - gt[3]) / gt[5] - 0.5
    i0 = np.clip(np.floor(fx).astype(int), 0, a.shape[1] - 2)
    j0 = np.clip(np.floor(fy).astype(int), 0, a.shape[0] - 2)
    tx, ty = np.clip(fx - i0, 0, 1), np.clip(fy - j0, 0, 1)
    return ((1 - tx) * (1 - ty) * a[j0, i0] + tx * (1 - ty) * a[j0, i0 + 1]
            + (1 - tx) * ty * a[j0 + 1, i0] + tx * ty * a[j0 + 1, i0 + 1])


def twin_pressure(date):
    with open(os.path.join(SAMPLE, "pressure_pool_c.csv")) as f:
        for line in f:
            c = line.strip().split(",")
            if c[0] == date.isoformat():
                return float(c[2])
    fail("make_deck.py: pressure_pool_c.csv has no %s" % date)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("out")
    ap.add_argument("--cell", type=float, default=250.0)
    ap.add_argument("--layers", type=int, default=3)
    ap.add_argument("--years", type=int, default=2)
    a = ap.parse_args()
    if not (50.0 <= a.cell <= 2000.0) or not (1 <= a.layers <= 20) or not (1 <= a.years <= 30):
        fail("make_deck.py: --cell %g --layers %d --years %d (expected 50..2000 m, 1..20 layers, "
                 "1..30 years)" % (a.cell, a.layers, a.years))

    with open(os.path.join(SAMPLE, "reservoir_traces.geojson")) as f:
        trace = [ft for ft in json.load(f)["features"] if ft["properties"]["name"] == "Pool C"][0]
    ring = np.array(trace["geometry"]["coordinates"][0])
    x0 = np.floor((ring[:, 0].min() - MARGIN) / 100) * 100
    y0 = np.floor((ring[:, 1].min() - MARGIN) / 100) * 100
    nx = int(np.ceil((ring[:, 0].max() + MARGIN - x0) / a.cell))
    ny = int(np.ceil((ring[:, 1].max() + MARGIN - y0) / a.cell))
    nz = a.layers
    top, gt = raster("07_pool_c_top.tif")
    base, gt2 = raster("08_pool_c_base.tif")
    px, py = np.meshgrid(x0 + a.cell * np.arange(nx + 1), y0 + a.cell * np.arange(ny + 1))
    dtop = -sample(top, gt, px, py)         # depth, positive down, at the pillars (ny+1, nx+1)
    dbase = np.maximum(-sample(base, gt2, px, py), dtop)
    crest = np.unravel_index(np.argmin(dtop), dtop.shape)

    out = []
    w = out.append
    w("-- OPM Flow deck of the po-plain twin's Pool C, written by opm/make_deck.py "
      "--cell %g --layers %d --years %d" % (a.cell, nz, a.years))
    w("RUNSPEC\nTITLE\npo-plain Pool C")
    w("DIMENS\n %d %d %d /" % (nx, ny, nz))
    w("OIL\nWATER\nGAS\nMETRIC")
    w("START\n 1 'APR' 2003 /")
    w("WELLDIMS\n 3 %d 1 3 /" % nz)
    w("TABDIMS\n 1 1 20 20 /")
    w("UNIFOUT")
    w("GRID")
    w("MAPUNITS\n 'METRES' /")
    w("MAPAXES\n %.1f %.1f %.1f %.1f %.1f %.1f /" % (x0, y0 + 1000, x0, y0, x0 + 1000, y0))
    w("GRIDUNIT\n 'METRES' /")
    coord = []
    for j in range(ny + 1):
        for i in range(nx + 1):
            x, y = i * a.cell, j * a.cell
            coord += [x, y, 1000.0, x, y, 2500.0]
    w("COORD")
    for n in range(0, len(coord), 6):
        w(" " + " ".join("%.2f" % v for v in coord[n:n + 6]))
    w("/")
    zc = []
    for k in range(nz):
        for kk in (k, k + 1):
            h = dtop + (dbase - dtop) * kk / nz
            for j in range(ny):
                for jj in (j, j + 1):
                    for i in range(nx):
                        zc += [h[jj, i], h[jj, i + 1]]
    w("ZCORN")
    for n in range(0, len(zc), 8):
        w(" " + " ".join("%.3f" % v for v in zc[n:n + 8]))
    w("/")
    thick = (dbase - dtop)
    tcol = 0.25 * (thick[:-1, :-1] + thick[1:, :-1] + thick[:-1, 1:] + thick[1:, 1:])
    act = [1 if tcol[j, i] >= 0.5 else 0 for k in range(nz) for j in range(ny) for i in range(nx)]
    w("ACTNUM")
    for n in range(0, len(act), 20):
        w(" " + " ".join(str(v) for v in act[n:n + 20]))
    w("/")
    n = nx * ny * nz
    w("PORO\n %d*0.25 /" % n)
    w("PERMX\n %d*300 /\nPERMY\n %d*300 /\nPERMZ\n %d*30 /" % (n, n, n))
    w("PROPS")
    w("SWOF\n 0.2 0 1 0\n 1.0 1 0 0 /")
    w("SGOF\n 0 0 1 0\n 0.8 1 0 0 /")
    w("DENSITY\n 850 1030 0.75 /")
    w("PVTW\n 150 1.0 4.5e-5 0.5 0 /")
    w("PVDO\n 50 1.10 2.0\n 300 1.05 2.2 /")
    w("PVDG")
    for p, bg, mu in ((30, 0.040, 0.012), (60, 0.0195, 0.013), (90, 0.0128, 0.014), (120, 0.0095, 0.016),
                      (150, 0.0077, 0.018), (200, 0.0059, 0.021), (300, 0.0042, 0.026)):
        w(" %g %g %g" % (p, bg, mu))
    w("/")
    w("ROCK\n 100 4.0e-5 /")
    w("SOLUTION")
    p0 = twin_pressure(START) * 10.0   # MPa -> bar, at 1,500 m (the twin's reference depth)
    w("EQUIL\n 1500 %.3f %.1f 0 %.1f 0 /" % (p0, GWC, GWC))
    w("RPTRST\n 'BASIC=2' /")
    w("SUMMARY\nFPR\nFGIR\nFGPR")
    w("SCHEDULE")
    cj, ci = crest
    w("WELSPECS")
    cells = []
    for name, dx, dy in WELLS:
        i = int(min(max(ci + round(dx / a.cell), 0), nx - 1)) + 1
        j = int(min(max(cj + round(dy / a.cell), 0), ny - 1)) + 1
        cells.append((name, i, j))
        w(" '%s' 'G' %d %d 1* 'GAS' /" % (name, i, j))
    w("/")
    w("COMPDAT")
    for name, i, j in cells:
        w(" '%s' %d %d 1 %d 'OPEN' 1* 1* 0.2 /" % (name, i, j, max(1, nz - 1)))
    w("/")
    d = START
    end = datetime.date(START.year + a.years, 4, 1)
    mode = None
    while d < end:
        nxt = datetime.date(d.year + (d.month == 12), d.month % 12 + 1, 1)
        inj = 4 <= d.month <= 10
        if inj != mode:
            if inj:
                w("WCONINJE")
                for name, _, _ in cells:
                    w(" '%s' 'GAS' 'OPEN' 'RATE' %.0f 1* 250 /" % (name, INJ_RATE / len(cells)))
            else:
                w("WCONPROD")
                for name, _, _ in cells:
                    w(" '%s' 'OPEN' 'GRAT' 2* %.0f 2* 20 /" % (name, PROD_RATE / len(cells)))
            w("/")
            mode = inj
        w("TSTEP\n %d /" % (nxt - d).days)
        d = nxt
    w("END")
    tmp = a.out + ".part"
    with open(tmp, "w") as f:
        f.write("\n".join(out) + "\n")
    os.replace(tmp, a.out)
    print("make_deck.py: %s: %d x %d x %d cells, %d active, crest (%d, %d) at %.0f m, p0 %.2f bar"
          % (a.out, nx, ny, nz, sum(act), ci + 1, cj + 1, dtop[crest], p0))


if __name__ == "__main__":
    main()
