#!/usr/bin/python3
"""Plots the V3 aquifer cases (tests/flow/test_flow_verification.cpp) against their closed forms.

    UGS_V3_OUT=/tmp/v3 build/tests/flow/test_flow_verification && tests/flow/plot_v3.py /tmp/v3

Writes v3.png in the same folder: the semi-infinite erfc profiles, the finite closed aquifer series
and the van Everdingen-Hurst W_D(t_D) with the tabulated values of VERIFICATION.md.
"""
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

d = sys.argv[1]
fig, ax = plt.subplots(1, 3, figsize=(15, 4.5))
for name, a, key, label in (("semi_infinite.csv", ax[0], "t_s", "t = {:.0f} s"), ("finite.csv", ax[1], "tD", "eta t / L^2 = {:g}")):
    t = np.genfromtxt(f"{d}/{name}", delimiter=",", names=True)
    for v in np.unique(t[key]):
        s = t[t[key] == v]
        line, = a.plot(s["x_m"], s["exact_Pa"] / 1e6, "-", lw=1, label=label.format(v))
        a.plot(s["x_m"], s["dp_Pa"] / 1e6, ".", ms=3, color=line.get_color())
    a.set_xlabel("x [m]")
    a.set_ylabel("dp [MPa]")
    a.legend(fontsize=8)
ax[0].set_title("semi-infinite aquifer: erfc (lines), ugs-flow (dots)")
ax[1].set_title("finite closed aquifer: series (lines), ugs-flow (dots)")
r = np.genfromtxt(f"{d}/radial.csv", delimiter=",", names=True)
ax[2].loglog(r["tD"], r["WD"], "-", label="ugs-flow")
ax[2].loglog([0.1, 1, 10], [0.404339, 1.568292, 7.401522], "o", label="van Everdingen-Hurst")
ax[2].set_xlabel("t_D")
ax[2].set_ylabel("W_D")
ax[2].set_title("radial aquifer, constant terminal pressure")
ax[2].legend()
fig.tight_layout()
fig.savefig(f"{d}/v3.png", dpi=120)
print(f"{d}/v3.png")
