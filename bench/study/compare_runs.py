#!/usr/bin/python3
"""Compare two ugs-solve results (HDF5) at the dates both hold, in the measures of issue 43:
max |u - u_ref| over max |u_ref|, and max |stress change - ref| over the largest stress change of the
reference (every component, every cell), per date and over all dates.

    compare_runs.py REFERENCE.h5 CANDIDATE.h5 [--u-tol 1e-5] [--stress-tol 5e-3]

Exit 0 when both measures are within their tolerances at every common date, 1 otherwise."""
import argparse
import sys

import h5py
import numpy as np


def by_date(path):
    f = h5py.File(path, "r")
    return f, {f["steps"][s].attrs["date"].decode(): f["steps"][s] for s in f["steps"]}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("reference")
    ap.add_argument("candidate")
    ap.add_argument("--u-tol", type=float, default=1e-5)
    ap.add_argument("--stress-tol", type=float, default=5e-3)
    a = ap.parse_args()
    _, ref = by_date(a.reference)
    _, cand = by_date(a.candidate)
    dates = sorted(set(ref) & set(cand))
    if not dates:
        sys.exit("compare_runs: no date in common")
    u_scale = max(np.abs(ref[d]["node/u"][:]).max() for d in dates)
    s_scale = max(np.abs(ref[d]["cell/stress_change"][:]).max() for d in dates)
    worst_u = worst_s = 0.0
    for d in dates:
        du = np.abs(ref[d]["node/u"][:] - cand[d]["node/u"][:]).max() / u_scale
        ds = np.abs(ref[d]["cell/stress_change"][:] - cand[d]["cell/stress_change"][:]).max() / s_scale
        worst_u, worst_s = max(worst_u, du), max(worst_s, ds)
        print(f"{d}: u {du:.2e} of max |u|, stress change {ds:.2e} of the largest")
    print(f"all {len(dates)} dates: u {worst_u:.2e} (tolerance {a.u_tol:g}), stress change {worst_s:.2e} "
          f"(tolerance {a.stress_tol:g}); max |u| {u_scale * 1e3:.3f} mm, largest stress change {s_scale / 1e6:.3f} MPa")
    sys.exit(0 if worst_u <= a.u_tol and worst_s <= a.stress_tol else 1)


if __name__ == "__main__":
    main()
