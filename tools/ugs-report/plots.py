#!/usr/bin/python3
"""Figures of ugs-report, drawn with matplotlib.

ugs-report writes every figure's data into work/ (CSV and .npy files, never pickles) and a list of
figures, work/manifest.json; this script draws each one into a PNG of the requested size in the
current folder. Run by ugs-report as `/usr/bin/python3 plots.py work/manifest.json`; it can be
re-run by hand on a report made with --keep-work.

Kinds: map (node values on the top surface, reservoir trace, PS points), pooltop (cell values on
the top of a pool's layer), section (polygons of a vertical section, vertical exaggeration),
series (simulated vs measured at a PS point, pool pressures), faults (chi, or the ensemble's
probability that chi reaches a threshold, on each fault in its plane: node values linear on
triangles with the pools' outline, or values per cell), chi_series
(max chi per fault against time, pool pressures), profile (calibration misfit of every evaluation).
"""
import csv
import json
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.dates as mdates  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402
from matplotlib.tri import Triangulation  # noqa: E402

CMAP_SIGNED = "RdBu_r"


def load(path):
    return np.load(path, allow_pickle=False)


def read_csv(path):
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(line for line in f if not line.startswith("#"))]
    return rows[0], rows[1:]


def grouped(rows):
    """Long-format rows (name, date, value): {name: ([dates], [values])}, in the order met."""
    out = {}
    for name, d, val in rows:
        out.setdefault(name, ([], []))
        out[name][0].append(d)
        out[name][1].append(float(val))
    return out


def dates(values):
    return np.array([np.datetime64(v[:19]) for v in values], dtype="datetime64[s]")


def symmetric_limit(values):
    finite = np.abs(values[np.isfinite(values)])
    vmax = float(finite.max()) if finite.size else 1.0
    return vmax if vmax > 0 else 1.0


def draw_trace(ax, path, scale=1e-3):
    if not path:
        return
    _, rows = read_csv(path)
    parts = {}
    for part, x, y in rows:
        parts.setdefault(part, []).append((float(x) * scale, float(y) * scale))
    for i, pts in enumerate(parts.values()):
        a = np.array(pts)
        ax.plot(a[:, 0], a[:, 1], color="black", lw=1.2, label="reservoir trace" if i == 0 else None)


def draw_points(ax, path, extent):
    if not path:
        return
    _, rows = read_csv(path)
    for pid, x, y in rows:
        x, y = float(x), float(y)
        if extent[0] <= x <= extent[1] and extent[2] <= y <= extent[3]:
            ax.plot(x * 1e-3, y * 1e-3, marker="^", color="black", ms=5, mfc="white")
            ax.annotate(pid, (x * 1e-3, y * 1e-3), xytext=(4, 4), textcoords="offset points", fontsize=7)


def new_figure(m, fig, layout=None):
    f = plt.figure(figsize=(m["width"] / m["dpi"], m["height"] / m["dpi"]), dpi=m["dpi"], layout=layout)
    f.suptitle(fig["title"], fontsize=11)
    return f


def plot_map(m, fig, cells=False):
    f = new_figure(m, fig)
    ax = f.add_subplot(1, 1, 1)
    xy = load(fig["nodes"]) * 1e-3
    tri = Triangulation(xy[:, 0], xy[:, 1], load(fig["triangles"]))
    v = load(fig["values"])
    vmax = None
    if cells:
        mask = ~np.isfinite(v)
        tri.set_mask(mask)
        vals = np.where(mask, 0.0, v)
        vmax = symmetric_limit(v)
        pc = ax.tripcolor(tri, facecolors=vals, cmap=CMAP_SIGNED, vmin=-vmax, vmax=vmax)
        x0, x1 = xy[:, 0].min(), xy[:, 0].max()
        y0, y1 = xy[:, 1].min(), xy[:, 1].max()
        extent = [x0 * 1e3, x1 * 1e3, y0 * 1e3, y1 * 1e3]
    else:
        extent = fig["extent"]
        inside = (xy[:, 0] >= extent[0] * 1e-3) & (xy[:, 0] <= extent[1] * 1e-3)
        inside &= (xy[:, 1] >= extent[2] * 1e-3) & (xy[:, 1] <= extent[3] * 1e-3)
        vmax = symmetric_limit(v[inside] if inside.any() else v)
        pc = ax.tripcolor(tri, v, shading="gouraud", cmap=CMAP_SIGNED, vmin=-vmax, vmax=vmax)
        levels = np.linspace(-vmax, vmax, 11)
        ax.tricontour(tri, v, levels=levels, colors="k", linewidths=0.3, alpha=0.5)
    cb = f.colorbar(pc, ax=ax, shrink=0.85)
    cb.set_label(fig["label"])
    draw_trace(ax, fig.get("trace"))
    draw_points(ax, fig.get("points"), extent)
    ax.set_xlim(extent[0] * 1e-3, extent[1] * 1e-3)
    ax.set_ylim(extent[2] * 1e-3, extent[3] * 1e-3)
    ax.set_aspect("equal")
    ax.set_xlabel("x, east (km)")
    ax.set_ylabel("y, north (km)")
    ax.ticklabel_format(useOffset=False, style="plain")
    ax.grid(True, lw=0.3, alpha=0.5)
    if fig.get("trace"):
        ax.legend(loc="lower right", fontsize=8)
    return f


def plot_section(m, fig):
    f = new_figure(m, fig)
    ax = f.add_subplot(1, 1, 1)
    sz = load(fig["sz"])
    off = load(fig["offsets"])
    v = load(fig["values"])
    polys = [np.column_stack((sz[a:b, 0] * 1e-3, sz[a:b, 1])) for a, b in zip(off[:-1], off[1:])]
    vmax = symmetric_limit(v)
    pc = PolyCollection(polys, array=v, cmap=CMAP_SIGNED, edgecolors="face", linewidths=0.1)
    pc.set_clim(-vmax, vmax)
    ax.add_collection(pc)
    ax.set_xlim(0, fig["length"] * 1e-3)
    ax.set_ylim(sz[:, 1].min(), sz[:, 1].max())
    # s in km, z in m: the displayed z scale is `exaggeration` times the s scale.
    ax.set_aspect(fig["exaggeration"] * 1e-3)
    ax.set_xlabel("distance along the section (km)")
    ax.set_ylabel(f"elevation (m), vertical exaggeration x{fig['exaggeration']:g}")
    for text, x, ha in ((fig.get("from"), 0.0, "left"), (fig.get("to"), fig["length"] * 1e-3, "right")):
        if text:
            ax.annotate(text, (x, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 4), textcoords="offset points",
                        ha=ha, fontsize=10, fontweight="bold")
    cb = f.colorbar(pc, ax=ax, orientation="horizontal", fraction=0.06, pad=0.18)
    cb.set_label(fig["label"])
    return f


def draw_pressures(ax, fig, lo, hi, colors, fit):
    """The pool pressures (fig["pressure"], long CSV pool,date,value) on a second y axis over [lo, hi],
    and the legend of both axes. colors: one colour per pool (else grey); fit: the y range of what
    is visible."""
    handles, labels = ax.get_legend_handles_labels()
    if fig.get("pressure"):
        ax2 = ax.twinx()
        pools = grouped(read_csv(fig["pressure"])[1])
        styles = ["--", ":", "-."]
        for i, (pool, (pd, pv)) in enumerate(pools.items()):
            ax2.plot(dates(pd), np.array(pv), styles[i % 3], color=f"C{i}" if colors else "0.35", lw=1.0 if colors else 0.9,
                     label=f"{pool} pressure")
        ax2.set_xlim(lo, hi)
        if fit:
            pvis = np.concatenate([np.array(pv)[(dates(pd) >= lo) & (dates(pd) <= hi)] for pd, pv in pools.values()])
            if pvis.size:
                ppad = 0.08 * max(float(np.ptp(pvis)), 1e-3)
                ax2.set_ylim(float(pvis.min()) - ppad, float(pvis.max()) + ppad)
        ax2.set_ylabel(fig["pressure_label"])
        h2, l2 = ax2.get_legend_handles_labels()
        handles += h2
        labels += l2
    ax.legend(handles, labels, loc="upper left", fontsize=8)


def plot_series(m, fig):
    f = new_figure(m, fig)
    ax = f.add_subplot(1, 1, 1)
    _, rows = read_csv(fig["sim"])
    ts = dates([r[0] for r in rows])
    vs = np.array([float(r[1]) for r in rows])
    lo, hi = ts.min(), ts.max()
    if fig.get("meas"):
        _, mrows = read_csv(fig["meas"])
        tm = dates([r[0] for r in mrows])
        vm = np.array([float(r[1]) for r in mrows])
        ax.plot(tm, vm, ".", color="0.45", ms=3, label="InSAR (measured)")
        lo, hi = tm.min(), tm.max()
    # Steps just outside the window are drawn too (clipped by the axes), so the line reaches its edges.
    ax.plot(ts, vs, "-", color="tab:red", lw=1.6, marker="." if ts.size < 30 else None, label="simulated")
    ax.set_xlim(lo, hi)
    # The y range of what is visible (the simulation may start decades before the window).
    visible = [vs[(ts >= lo) & (ts <= hi)]]
    if fig.get("meas"):
        visible.append(vm)
    visible = np.concatenate(visible)
    if visible.size:
        pad = 0.08 * max(float(np.ptp(visible)), 0.5)
        ax.set_ylim(float(visible.min()) - pad, float(visible.max()) + pad)
    ax.set_ylabel(fig["label"])
    ax.grid(True, lw=0.3, alpha=0.6)
    locator = mdates.AutoDateLocator()
    ax.xaxis.set_major_locator(locator)
    ax.xaxis.set_major_formatter(mdates.ConciseDateFormatter(locator))
    draw_pressures(ax, fig, lo, hi, colors=True, fit=True)
    return f


def plot_faults(m, fig):
    f = new_figure(m, fig, layout="constrained")
    panels = fig["panels"]
    n = len(panels)
    cols = 1 if n <= 3 else 2
    rows = (n + cols - 1) // cols
    pc = None
    axes = []
    for i, p in enumerate(panels):
        ax = f.add_subplot(rows, cols, i + 1)
        axes.append(ax)
        v = load(p["values"])
        if "nodes" in p:
            # Node values (the node pairs'), linear on each triangle: the colours reach the maximum.
            # Without the fault's triangles (the ensemble's per-pair table): the Delaunay
            # triangles of the pairs in the plane, in metres both ways.
            sz = load(p["nodes"]).reshape(-1, 2)
            if "tri" in p:
                triangles = load(p["tri"]).reshape(-1, 3)
            else:
                triangles = Triangulation(sz[:, 0], sz[:, 1]).triangles
            tri = Triangulation(sz[:, 0] * 1e-3, sz[:, 1], triangles)
            pc = ax.tripcolor(tri, v, shading="gouraud", cmap="viridis", vmin=0.0, vmax=fig["vmax"])
            s, z = sz[:, 0] * 1e-3, sz[:, 1]
            top = p["max"]
        else:
            sz = load(p["sz"]).reshape(-1, 3, 2).copy()
            sz[:, :, 0] *= 1e-3
            pc = PolyCollection(list(sz), array=v, cmap="viridis", edgecolors="face", linewidths=0.1)
            pc.set_clim(0.0, fig["vmax"])
            ax.add_collection(pc)
            s, z = sz[:, :, 0], sz[:, :, 1]
            finite = v[np.isfinite(v)]
            top = finite.max() if finite.size else float("nan")
        if p.get("pools"):
            _, prow = read_csv(p["pools"])
            outlines = {}
            for pool, ps, pz in prow:
                outlines.setdefault(pool, []).append((float(ps) * 1e-3, float(pz)))
            for j, (pool, pts) in enumerate(outlines.items()):
                a = np.array(pts)
                ax.plot(a[:, 0], a[:, 1], "-", color="white", lw=2.4)
                ax.plot(a[:, 0], a[:, 1], ["-", "--", ":", "-."][j % 4], color="black", lw=1.2, label=pool)
        if p.get("at"):
            # Where the maximum is: on a coarse fault mesh a single node pair, too small to see.
            ax.plot(p["at"][0] * 1e-3, p["at"][1], "x", color="red", ms=9, mew=2.0, clip_on=False, label=f"max χ {top:.3f}")
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=7, loc="lower right")
        ax.set_xlim(s.min(), s.max())
        ax.set_ylim(z.min(), z.max())
        ax.set_title(p.get("title", f"{p['name']}: max χ = {top:.3f}"), fontsize=9)
        ax.set_xlabel("along strike (km)", fontsize=8)
        ax.set_ylabel("elevation (m)", fontsize=8)
        ax.tick_params(labelsize=7)
    if pc is not None:
        cb = f.colorbar(pc, ax=axes, shrink=0.9)
        cb.set_label(fig["label"])
    return f


def plot_chi_series(m, fig):
    f = new_figure(m, fig, layout="constrained")
    ax = f.add_subplot(1, 1, 1)
    faults = grouped(read_csv(fig["csv"])[1])
    lo = hi = None
    for i, (fault, (fd, fv)) in enumerate(faults.items()):
        t = dates(fd)
        ax.plot(t, np.array(fv), "-", color=f"C{i}", lw=1.4, marker="." if t.size < 40 else None, label=f"max χ, {fault}")
        lo = t.min() if lo is None else min(lo, t.min())
        hi = t.max() if hi is None else max(hi, t.max())
    if lo == hi:
        lo, hi = lo - np.timedelta64(1, "D"), hi + np.timedelta64(1, "D")
    ax.set_xlim(lo, hi)
    ax.set_ylim(0.0, 1.05)
    ax.axhline(1.0, color="0.3", lw=0.6, ls=":")
    ax.set_ylabel("largest χ on the fault")
    ax.grid(True, lw=0.3, alpha=0.6)
    locator = mdates.AutoDateLocator()
    ax.xaxis.set_major_locator(locator)
    ax.xaxis.set_major_formatter(mdates.ConciseDateFormatter(locator))
    draw_pressures(ax, fig, lo, hi, colors=False, fit=False)
    return f


def plot_rate_series(m, fig):
    """R/r per fault against time (log scale): area-weighted (solid) and the largest over the pairs (dashed)."""
    f = new_figure(m, fig, layout="constrained")
    ax = f.add_subplot(1, 1, 1)
    _, rows = read_csv(fig["csv"])
    faults = {}
    for fault, d, v, mx in rows:
        faults.setdefault(fault, ([], [], []))
        faults[fault][0].append(d)
        faults[fault][1].append(float(v))
        faults[fault][2].append(float(mx))
    lo = hi = None
    for i, (fault, (fd, fv, fm)) in enumerate(faults.items()):
        t = dates(fd)
        ax.plot(t, np.array(fv), "-", color=f"C{i}", lw=1.4, marker="." if t.size < 40 else None, label=f"R/r, {fault}")
        ax.plot(t, np.array(fm), "--", color=f"C{i}", lw=0.9, label=f"largest R/r over pairs, {fault}")
        lo = t.min() if lo is None else min(lo, t.min())
        hi = t.max() if hi is None else max(hi, t.max())
    if lo == hi:
        lo, hi = lo - np.timedelta64(1, "D"), hi + np.timedelta64(1, "D")
    ax.set_xlim(lo, hi)
    ax.set_yscale("log")
    ax.axhline(1.0, color="0.3", lw=0.6, ls=":")
    ax.set_ylabel("seismicity rate / background rate (R/r)")
    ax.grid(True, lw=0.3, alpha=0.6, which="both")
    locator = mdates.AutoDateLocator()
    ax.xaxis.set_major_locator(locator)
    ax.xaxis.set_major_formatter(mdates.ConciseDateFormatter(locator))
    draw_pressures(ax, fig, lo, hi, colors=False, fit=False)
    return f


def plot_profile(m, fig):
    f = new_figure(m, fig, layout="constrained")
    header, rows = read_csv(fig["csv"])
    # Each cache entry once: the first time it was evaluated.
    seen = set()
    unique = []
    for r in rows:
        if r[header.index("entry")] not in seen:
            seen.add(r[header.index("entry")])
            unique.append(r)
    rows = unique
    rms = np.array([float(r[header.index("rms_mm")]) for r in rows])
    phase = [r[header.index("phase")] for r in rows]
    best = int(np.argmin(rms))
    params = fig["params"]
    for i, name in enumerate(params):
        ax = f.add_subplot(1, len(params), i + 1)
        x = np.array([float(r[header.index(name)]) for r in rows])
        for ph, marker in (("scan", "o"), ("brent", "s"), ("bobyqa", "D"), ("reciprocal", "^"), ("check", "v")):
            k = np.array([p == ph for p in phase])
            if k.any():
                ax.plot(x[k], rms[k], marker, ls="none", ms=5, label=ph)
        ax.plot(x[best], rms[best], "*", color="red", ms=14, label=f"best {x[best]:.4g}")
        ax.set_xlabel(name)
        ax.set_ylabel("RMS misfit (mm)")
        ax.grid(True, lw=0.3, alpha=0.6)
        ax.legend(fontsize=8)
    return f


def plot_compare(m, fig):
    """Runs side by side: the mean (solid) and peak (dashed) u_z change of each run against time."""
    f = new_figure(m, fig)
    ax = f.add_subplot(1, 1, 1)
    _, rows = read_csv(fig["data"])
    runs = {}
    for run, d, mean, peak in rows:
        runs.setdefault(run, ([], [], []))
        runs[run][0].append(d)
        runs[run][1].append(float(mean))
        runs[run][2].append(float(peak))
    for i, (run, (d, mean, peak)) in enumerate(runs.items()):
        t = dates(d)
        ax.plot(t, mean, "-", color=f"C{i}", lw=1.6, marker="." if len(d) < 30 else None, label=f"{run}: mean")
        ax.plot(t, peak, "--", color=f"C{i}", lw=1.0, label=f"{run}: peak")
    ax.set_ylabel(fig["label"])
    ax.grid(True, lw=0.3, alpha=0.6)
    locator = mdates.AutoDateLocator()
    ax.xaxis.set_major_locator(locator)
    ax.xaxis.set_major_formatter(mdates.ConciseDateFormatter(locator))
    ax.legend(loc="best", fontsize=8)
    return f


def plot_tornado(m, fig):
    """Sensitivity indices per metric, largest first: S1 and ST with their intervals, or mu* and sigma.
    Per-date metrics (names ending in .YYYY-MM-DD) are left to the CSV."""
    header, rows = read_csv(fig["csv"])
    col = {n: i for i, n in enumerate(header)}
    per_metric = {}
    for r in rows:
        if re.search(r"\.\d{4}-\d{2}-\d{2}$", r[col["metric"]]):
            continue
        per_metric.setdefault(r[col["metric"]], []).append(r)
    # Metrics on which no parameter acts (every index 0, e.g. no settlement in a storage phase) stay in the CSV.
    key = "st" if fig["method"] == "sobol" else "mu_star"
    acted = [k for k, rs in per_metric.items() if any(float(r[col[key]]) != 0 for r in rs)]
    # The answers first: the event count and P(M >= m) over all faults, the safe scale, chi per fault,
    # then the surface and misfit metrics, in the CSV's order within each kind; six panels.
    kinds = (r"^seismic_events\.all\.", r"^p_event_M[0-9.]+\.all\.", r"^safe_scale$", r"^chi_max\.", r"^(ps_)?uplift",
             r"^(ps_)?settlement", r"^misfit")
    rank = lambda k: next((i for i, p in enumerate(kinds) if re.search(p, k)), len(kinds))
    metrics = sorted(acted, key=rank)[:6] or list(per_metric)[:1]
    # One parameter order for every panel (labels on the first only): by the sum over the panels of
    # each parameter's index over the panel's largest.
    weight = {}
    for name in metrics:
        top = max(float(r[col[key]]) for r in per_metric[name]) or 1.0
        for r in per_metric[name]:
            weight[r[col["parameter"]]] = weight.get(r[col["parameter"]], 0.0) + float(r[col[key]]) / top
    order = sorted(weight, key=lambda p: (weight[p], p))
    f = new_figure(m, fig, layout="constrained")
    sobol = fig["method"] == "sobol"
    for i, name in enumerate(metrics):
        ax = f.add_subplot(1, len(metrics), i + 1)
        by_param = {r[col["parameter"]]: r for r in per_metric[name]}
        rs = [by_param[p] for p in order if p in by_param]
        y = np.arange(len(rs))
        labels = [r[col["parameter"]] for r in rs]
        if sobol:
            for off, k, lab in ((-0.2, "s1", "S1"), (0.2, "st", "ST")):
                v = np.array([float(r[col[k]]) for r in rs])
                lo = np.array([float(r[col[k + "_low"]]) for r in rs])
                hi = np.array([float(r[col[k + "_high"]]) for r in rs])
                ax.barh(y + off, v, height=0.4, xerr=[np.maximum(v - lo, 0), np.maximum(hi - v, 0)], capsize=3, label=lab)
            if i == 0:
                f.supxlabel("Sobol' index (bars: 95 % intervals)", fontsize=8)
        else:
            v = np.array([float(r[col["mu_star"]]) for r in rs])
            s = np.array([float(r[col["sigma"]]) for r in rs])
            ax.barh(y - 0.2, v, height=0.4, label="μ*")
            ax.barh(y + 0.2, s, height=0.4, label="σ")
            if i == 0:
                f.supxlabel("elementary effect (metric units per unit of probability)", fontsize=8)
        ax.set_yticks(y)
        ax.set_yticklabels(labels if i == 0 else [""] * len(labels), fontsize=7)
        ax.set_title(name.replace(".", ".\n", 1) if len(name) > 24 else name, fontsize=7)
        ax.grid(True, axis="x", lw=0.3, alpha=0.6)
        if i == 0:
            ax.legend(fontsize=7)
    return f


def plot_fan(m, fig):
    """P10-P90 band and P50 of the simulated series at up to 9 PS points, with the measured series
    shifted to the same zero (its first value)."""
    header, rows = read_csv(fig["csv"])
    col = {n: i for i, n in enumerate(header)}
    by_pid = {}
    for r in rows:
        by_pid.setdefault(r[col["pid"]], []).append(r)
    pids = list(by_pid)[:9]
    n = len(pids)
    ncol = min(3, n)
    nrow = (n + ncol - 1) // ncol
    f = new_figure(m, fig, layout="constrained")
    for i, pid in enumerate(pids):
        ax = f.add_subplot(nrow, ncol, i + 1)
        rs = by_pid[pid]
        t = dates([r[col["date"]] for r in rs])
        p10, p50, p90 = (np.array([float(r[col[k]]) for r in rs]) for k in ("p10_mm", "p50_mm", "p90_mm"))
        ax.fill_between(t, p10, p90, color="C0", alpha=0.3, lw=0, label="P10-P90")
        ax.plot(t, p50, "-", color="C0", lw=1.2, label="P50")
        meas = np.array([float(r[col["measured_mm"]]) if r[col["measured_mm"]] else np.nan for r in rs])
        finite = np.isfinite(meas)
        if finite.any():
            ax.plot(t[finite], meas[finite] - meas[finite][0], ".", color="k", ms=3, label="InSAR")
        ax.set_title(pid, fontsize=8)
        ax.grid(True, lw=0.3, alpha=0.6)
        locator = mdates.AutoDateLocator()
        ax.xaxis.set_major_locator(locator)
        ax.xaxis.set_major_formatter(mdates.ConciseDateFormatter(locator))
        if i % ncol == 0:
            ax.set_ylabel("u_z (mm)")
        if i == 0:
            ax.legend(fontsize=7)
    return f


def main():
    with open(sys.argv[1], encoding="utf-8") as fh:
        m = json.load(fh)
    plt.rcParams.update({"font.size": 9, "svg.hashsalt": "ugs", "path.simplify": True})
    for fig in m["figures"]:
        kind = fig["kind"]
        if kind == "map":
            f = plot_map(m, fig)
        elif kind == "pooltop":
            f = plot_map(m, fig, cells=True)
        elif kind == "section":
            f = plot_section(m, fig)
        elif kind == "series":
            f = plot_series(m, fig)
        elif kind == "faults":
            f = plot_faults(m, fig)
        elif kind == "rate_series":
            f = plot_rate_series(m, fig)
        elif kind == "chi_series":
            f = plot_chi_series(m, fig)
        elif kind == "profile":
            f = plot_profile(m, fig)
        elif kind == "compare":
            f = plot_compare(m, fig)
        elif kind == "tornado":
            f = plot_tornado(m, fig)
        elif kind == "fan":
            f = plot_fan(m, fig)
        else:
            raise SystemExit(f"plots.py: unknown figure kind {kind!r}")
        f.savefig(fig["png"], dpi=m["dpi"], metadata={"Software": None})
        plt.close(f)
        print(f"plots.py: {fig['png']}", flush=True)


if __name__ == "__main__":
    main()
