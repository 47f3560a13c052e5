#!/usr/bin/python3
"""Plots the crack benchmarks V4 (Phan et al. 2003, slip of an inclined crack with friction) and
V5 (Sneddon, opening of a pressurised crack) against their closed forms, from the profiles that
test_crack_benchmarks writes into <build>/tests/fault_mechanics.

    /usr/bin/python3 tests/fault_mechanics/plot_cracks.py build/tests/fault_mechanics      # -> cracks.png there
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def read(path):
    with open(path) as f:
        rows = [r for r in csv.DictReader(f)]
    rows.sort(key=lambda r: float(r["s_m"]))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    d = Path(sys.argv[1] if len(sys.argv) > 1 else ".")
    v4, v5 = read(d / "v4_profile.csv"), read(d / "v5_profile.csv")
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    ax[0].plot(v4["s_m"], v4["exact_mm"], "k-", label="closed form")
    ax[0].plot(v4["s_m"], v4["slip_mm"], "o", ms=3, label="ugs-solve")
    ax[0].set(title="V4 slip (Phan et al. 2003)", xlabel="s / b", ylabel="slip [mm]")
    ax[1].axhline(-11.698, color="k", label="closed form")
    ax[1].plot(v4["s_m"], v4["normal_traction_MPa"], "o", ms=3, label="ugs-solve")
    ax[1].set(title="V4 normal traction", xlabel="s / b", ylabel="t_N [MPa]")
    ax[2].plot(v5["s_m"], v5["exact_mm"], "k-", label="closed form")
    ax[2].plot(v5["s_m"], v5["opening_mm"], "o", ms=3, label="ugs-solve")
    ax[2].set(title="V5 opening (Sneddon)", xlabel="s / a", ylabel="opening [mm]")
    for a in ax:
        a.axvspan(-0.8, 0.8, color="0.93", zorder=0)
        a.legend()
    fig.tight_layout()
    fig.savefig(d / "cracks.png", dpi=120)
    print(d / "cracks.png")


if __name__ == "__main__":
    main()
