#!/usr/bin/python3
"""Compares the uplift over Pool C from the OPM Flow pressures with that from the schedule-driven
flow model (make -C data-samples/po-plain opm; docs/eclipse.md).

usage: compare.py --opm OPM_top.h5 --flow FLOW_top.h5 --restart POOL_C.UNRST -o comparison.csv

For every date of the simulator's run that both top-surface files hold: the pressure change since the
simulation's start, in Pool C's gas cap (cells with SGAS > 0.3 at the start, mean) and in the twin's
schedule (pressure_pool_c.csv), and the vertical displacement change since the start, mean and largest
magnitude over the top-surface nodes inside Pool C's trace, from each run. Writes the CSV and
the same table as Markdown (comparison.md) with a line of summary.
"""
import sys

sys.dont_write_bytecode = True

import argparse  # noqa: E402
import json  # noqa: E402
import os  # noqa: E402

import h5py  # noqa: E402
import numpy as np  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
SAMPLE = os.path.dirname(HERE)
sys.path.insert(0, HERE)
import eclbin  # noqa: E402


def fail(msg):
    """Bad input: one line on stderr, exit 2 (docs/cli.md)."""
    print(msg, file=sys.stderr)
    sys.exit(2)


def inside(ring, x, y):
    """Even-odd rule: which points (x, y) lie inside the closed ring."""
    res = np.zeros(len(x), bool)
    for (x1, y1), (x2, y2) in zip(ring[:-1], ring[1:]):
        cross = (y1 > y) != (y2 > y)
        with np.errstate(divide="ignore", invalid="ignore"):
            xi = x1 + (y - y1) * (x2 - x1) / (y2 - y1)
        res ^= cross & (x < xi)
    return res


def top_series(path, mask_of):
    with h5py.File(path, "r") as f:
        xyz = f["mesh/coordinates"][:]
        m = mask_of(xyz[:, 0], xyz[:, 1])
        out = {}
        for k in f["steps"]:
            s = f["steps"][k]
            d = s.attrs["date"]
            d = d.decode() if isinstance(d, bytes) else str(d)
            uz = s["node/u_mm"][:, 2][m]
            out[d] = uz
    if not m.any():
        fail("compare.py: %s: no top-surface node inside Pool C's trace" % path)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--opm", required=True)
    ap.add_argument("--flow", required=True)
    ap.add_argument("--restart", required=True)
    ap.add_argument("-o", "--output", required=True)
    a = ap.parse_args()

    with open(os.path.join(SAMPLE, "reservoir_traces.geojson")) as f:
        ring = np.array([ft for ft in json.load(f)["features"]
                         if ft["properties"]["name"] == "Pool C"][0]["geometry"]["coordinates"][0])
    with open(os.path.join(SAMPLE, "pressure_pool_c.csv")) as f:
        twin = {c[0]: float(c[2]) for c in (line.strip().split(",") for line in f) if c[0][:1].isdigit()}
    try:
        steps = eclbin.restart_steps(a.restart)
        sgas = [x for n, x in eclbin.read(a.restart) if n == "SGAS"]
    except (OSError, ValueError) as e:
        fail("compare.py: %s" % e)
    if not steps or len(sgas) != len(steps):
        fail("compare.py: %s: no PRESSURE/SGAS report steps" % a.restart)
    gas = sgas[0] > 0.3
    d0, p0 = steps[0]
    opm = top_series(a.opm, lambda x, y: inside(ring, x, y))
    flo = top_series(a.flow, lambda x, y: inside(ring, x, y))
    if d0 not in opm or d0 not in flo:
        fail("compare.py: the start date %s is not in both top-surface files" % d0)
    rows = []
    for d, p in steps:
        if d not in opm or d not in flo:
            continue
        uo, uf = opm[d] - opm[d0], flo[d] - flo[d0]
        rows.append((d, 0.1 * (p[gas].mean() - p0[gas].mean()), twin[d] - twin[d0],
                     uo.mean(), uo[np.argmax(np.abs(uo))], uf.mean(), uf[np.argmax(np.abs(uf))]))
    if len(rows) < 2:
        fail("compare.py: fewer than two common dates in %s and %s" % (a.opm, a.flow))
    head = ["date", "dp_opm_gas_MPa", "dp_schedule_MPa", "uz_opm_mean_mm", "uz_opm_peak_mm",
            "uz_flow_mean_mm", "uz_flow_peak_mm"]
    tmp = a.output + ".part"
    with open(tmp, "w") as f:
        f.write("# uplift over Pool C's trace since %s: OPM Flow pressures vs the schedule-driven flow model\n" % d0)
        f.write(",".join(head) + "\n")
        for r in rows:
            f.write(r[0] + "," + ",".join("%.4f" % v for v in r[1:]) + "\n")
    md = os.path.splitext(a.output)[0] + ".md"
    n_in = len(next(iter(opm.values())))
    lines = ["# Pool C: uplift from the OPM Flow pressures vs the schedule-driven flow model", "",
             "Changes since %s over the %d top-surface nodes inside Pool C's trace (make opm)." % (d0, n_in),
             "dp: Pool C's gas-cap mean pressure change (OPM Flow) and the twin's schedule (pressure_pool_c.csv).", "",
             "| date | dp OPM (MPa) | dp schedule (MPa) | uz OPM mean / peak (mm) | uz flow model mean / peak (mm) |",
             "|---|---|---|---|---|"]
    for r in rows:
        lines.append("| %s | %+.2f | %+.2f | %+.2f / %+.2f | %+.2f / %+.2f |" % r)
    swing = [r for r in rows if abs(r[5]) > 1e-9]
    if swing:
        ratio = [r[3] / r[5] for r in swing]
        lines += ["", "Mean uplift ratio OPM / flow model at the common dates: %.2f .. %.2f." % (min(ratio), max(ratio))]
    with open(md + ".part", "w") as f:
        f.write("\n".join(lines) + "\n")
    os.replace(tmp, a.output)
    os.replace(md + ".part", md)


if __name__ == "__main__":
    main()
