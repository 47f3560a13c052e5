#!/usr/bin/python3
"""Plots V8 (Jansen et al. 2019, a depleted reservoir offset by a locked fault): the normal and dip
shear traction change along the fault against the closed form, from the profiles that
test_offset_fault_long (6, 12, 24 cells per reservoir height) and test_offset_fault (12) write into
<build>/tests/fault_mechanics (front side of the slab).

    /usr/bin/python3 tests/fault_mechanics/plot_offset_fault.py build/tests/fault_mechanics   # -> offset_fault.png there
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        rows = [r for r in csv.DictReader(f) if r["side"] == "0"]
    rows.sort(key=lambda r: float(r["z_m"]))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    d = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    runs = {n: read(d / f"v8_profile_{n}.csv") for n in (6, 12, 24) if (d / f"v8_profile_{n}.csv").exists()}
    fig, ax = plt.subplots(1, 2, figsize=(11, 6), sharey=True)
    finest = runs[max(runs)]
    for a, key, title in ((ax[0], "dsigma_n", "normal traction change"), (ax[1], "dtau_dip", "dip shear traction change")):
        a.plot(finest["exact_" + key + "_MPa"], finest["z_m"], "k-", lw=1, label="closed form")
        for n, r in runs.items():
            a.plot(r[key + "_MPa"], r["z_m"], "o-", ms=3, lw=0.5, label=f"ugs-solve, h/{n}")
        for zc in (-200 / 3, -100 / 3, 100 / 3, 200 / 3):
            a.axhline(zc, color="0.8", lw=0.5)
        a.set(title=f"V8 {title}", xlabel="[MPa]", ylabel="z [m]")
        a.legend()
    fig.tight_layout()
    fig.savefig(d / "offset_fault.png", dpi=120)
    print(d / "offset_fault.png")


if __name__ == "__main__":
    main()
