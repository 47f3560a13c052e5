"""Synthetic InSAR series for the six PS points (thesis 2.3): a Geertsma-type generator.

Model (documented in README.md, "InSAR generator"):
  * each pool (Pool A, Pool C) and its aquifer is cut into 100 m x 100 m columns ("nuclei"); a
    nucleus has the pool unit's local thickness h and mid-depth below ground D (from the surfaces);
  * pressure change: inside the trace, the pool's average pressure (pressure_pool_*.csv); in the
    aquifer, the 1D diffusion of that history from the trace boundary (Duhamel superposition of
    erfc(d / (2 sqrt(c t))), d = distance to the trace, c = K / S_s from Table 4.2);
  * compaction of each nucleus, one-dimensional and hysteretic (thesis 4.2):
        dh = h c dsigma',  sigma' = sigma'_0 - alpha dp,  sigma'_0 = (g_lith - g_w) D,
        c = c_M(sigma') = 1.0044e-2 sigma'^-1.1347 on virgin loading (sigma' above its past maximum),
        c = c_M(sigma') / c_R on unloading and reloading (c_R = 3 Pool C and its aquifer, 5 Pool A);
  * surface displacement of a nucleus of volume change dV at depth D (Geertsma 1973, half-space):
        u_z = (1 - nu) / pi * dV * D / (r^2 + D^2)^(3/2),
        u_r = (1 - nu) / pi * dV * r / (r^2 + D^2)^(3/2)  (outward for expansion), nu = 0.3;
    the sum over a uniform disk gives Geertsma's u_z(0) = 2 c_m (1 - nu) alpha dp h (1 - eta/sqrt(1+eta^2));
  * measured series = model displacement relative to the first acquisition + a small linear trend per
    point + Gaussian noise (1.8 mm vertical / 1.5 mm east on the monthly Radarsat epochs, 1.2 / 1.0 mm
    on the weekly Sentinel-1 epochs), seeded.
"""

import datetime as dt
import math

import numpy as np

import po_pressure as PP
import po_vectors as V

NU = 0.3
ALPHA = 1.0
GRAD_LITH = 0.0226          # MPa/m
GRAD_W = PP.GRAD_W          # MPa/m
CM_A, CM_B = 1.0044e-2, 1.1347
C_R = {"Pool A": 5.0, "Pool C": 3.0}
K_H = 2.04e-7               # m/s, Table 4.2
POROSITY = 0.20
BETA_W = 4.4e-10            # 1/Pa, water compressibility
NUCLEUS = 100.0             # m

# per point: vertical trend, east trend (mm/yr) not explained by the reservoirs. Inside the trace they
# mimic thesis 4.2.2 (the model over-estimates the long trend at A00LFZ4 and under-estimates it at
# A016VNW, by less than 1 mm/yr); the SW point sits near the motorway and the railway whose
# embankments settle (thesis 2.3.1).
TRENDS = {
    "A00LFZ4": (-0.5, 0.1), "A016VJP": (-0.1, -0.1), "A016VNW": (0.3, 0.0),
    "A00LFOB": (-0.9, 0.2), "A016VQ9": (0.1, -0.2), "A016VUG": (-0.2, 0.1),
}
NOISE = {"U": (1.8, 1.2), "E": (1.5, 1.0)}     # mm: (monthly Radarsat epochs, weekly Sentinel-1)
SENTINEL_START = dt.date(2015, 3, 1)


def c_m(sigma):
    return CM_A * np.power(sigma, -CM_B)


def diffusivity():
    s_s = PP.GAMMA_W * (c_m(20.0) * 1e-6 + POROSITY * BETA_W)      # 1/m
    return K_H / s_s                                                # m2/s


def kernel(dx, dy, depth):
    """Surface displacement (u_z, u_east) per m3 of volume increase of a nucleus at `depth` below
    ground, seen at horizontal offset (dx, dy) from it (Geertsma 1973, homogeneous half-space)."""
    R3 = (dx * dx + dy * dy + depth * depth) ** 1.5
    return (1.0 - NU) / math.pi * depth / R3, (1.0 - NU) / math.pi * dx / R3


def geertsma_disk_centre(cm, dp, h, radius, depth):
    """Closed form: uplift above the centre of a disk reservoir (m), Geertsma (1973)."""
    eta = depth / radius
    return 2.0 * cm * (1.0 - NU) * ALPHA * dp * h * (1.0 - eta / math.sqrt(1.0 + eta * eta))


def nuclei_disk_centre(cm, dp, h, radius, depth, cell=NUCLEUS):
    """The same quantity summed over nuclei of `cell` x `cell` m, as the generator does."""
    n = int(math.ceil(radius / cell)) + 1
    g = (np.arange(-n, n + 1) + 0.0) * cell
    X, Y = np.meshgrid(g, g)
    inside = X * X + Y * Y <= radius * radius
    gz, _ = kernel(-X[inside], -Y[inside], depth)
    return float(np.sum(gz)) * cell * cell * cm * ALPHA * dp * h


def acquisition_dates():
    """Monthly (day 11) 2003-10 .. 2015-02, then weekly from 2015-03-04 to 2021-10-27."""
    out = []
    y, m = 2003, 10
    while (y, m) <= (2015, 2):
        out.append(dt.date(y, m, 11))
        m += 1
        if m == 13:
            y, m = y + 1, 1
    d = dt.date(2015, 3, 4)
    while d <= dt.date(2021, 10, 31):
        out.append(d)
        d += dt.timedelta(days=7)
    return out


def nuclei(field, pool, trace_ring, aquifer_geom):
    ring = V.ring_of(aquifer_geom)
    xs = np.array([p[0] for p in ring])
    ys = np.array([p[1] for p in ring])
    x0 = math.floor(xs.min() / NUCLEUS) * NUCLEUS + 0.5 * NUCLEUS
    y0 = math.floor(ys.min() / NUCLEUS) * NUCLEUS + 0.5 * NUCLEUS
    gx = np.arange(x0, xs.max(), NUCLEUS)
    gy = np.arange(y0, ys.max(), NUCLEUS)
    X, Y = np.meshgrid(gx, gy)
    X, Y = X.ravel(), Y.ravel()
    keep = V.point_in_ring(X, Y, ring)
    X, Y = X[keep], Y[keep]
    s = field.all_surfaces(X, Y)
    top, base = {"Pool A": ("pool_a_top", "pool_a_base"), "Pool C": ("pool_c_top", "pool_c_base")}[pool]
    h = s[top] - s[base]
    ok = h > 0.01
    X, Y, h = X[ok], Y[ok], h[ok]
    zc = 0.5 * (s[top] + s[base])[ok]
    depth = (s["dem"][ok] - zc)
    inside = V.point_in_ring(X, Y, trace_ring)
    dist = np.where(inside, 0.0, V.distance_to_ring(X, Y, trace_ring))
    return X, Y, h, depth, dist


def aquifer_pressure(dp_pool, dist, dates):
    """Pressure change (MPa) per nucleus and month: diffusion from the trace boundary (Duhamel)."""
    n = len(dates)
    c = diffusivity()
    days = np.array([d.toordinal() for d in dates], dtype=float)
    lag = (days - days[0]) * 86400.0                  # s, lags of the monthly grid (uniform enough)
    bins = np.arange(0.0, dist.max() + 2 * NUCLEUS, NUCLEUS)
    inc = np.diff(np.concatenate([[0.0], dp_pool]))
    table = np.empty((len(bins), n))
    for k, d in enumerate(bins):
        if d == 0.0:
            kern = np.ones(n)
        else:
            kern = np.array([0.0] + [math.erfc(d / (2.0 * math.sqrt(c * t))) for t in lag[1:]])
        table[k] = np.convolve(inc, kern)[:n]
    j = np.minimum((dist / NUCLEUS).astype(int), len(bins) - 2)
    w = (dist - bins[j]) / NUCLEUS
    return table, j, w


def model_displacements(field, traces, aquifers, pressures, points):
    """Monthly u_z, u_e (mm) at the points, 1950-01 .. 2033-12."""
    dates = PP.months()
    n = len(dates)
    px = np.array([p[1] for p in points])
    py = np.array([p[2] for p in points])
    uz = np.zeros((len(points), n))
    ue = np.zeros((len(points), n))
    for pool in ("Pool A", "Pool C"):
        X, Y, h, depth, dist = nuclei(field, pool, traces[pool], aquifers[pool])
        dp_pool = (pressures[pool] - pressures[pool][0]) * PP.P0_C          # MPa, signed
        table, j, w = aquifer_pressure(dp_pool, dist, dates)
        sig0 = (GRAD_LITH - GRAD_W) * depth
        sig_prev = sig0.copy()
        sig_max = sig0.copy()
        comp = np.zeros_like(h)                                            # m, compaction (+)
        gz, ge = kernel(px[:, None] - X[None, :], py[:, None] - Y[None, :], depth[None, :])
        gz = gz * (NUCLEUS * NUCLEUS)                                      # per m of expansion
        ge = ge * (NUCLEUS * NUCLEUS)
        cr = C_R[pool]
        for i in range(1, n):
            dp = (1.0 - w) * table[j, i] + w * table[j + 1, i]
            sig = sig0 - ALPHA * dp
            ds = sig - sig_prev
            virgin = np.maximum(sig - sig_max, 0.0)                        # sig_max >= sig_prev
            reload = ds - virgin                                           # any sign
            mid_r = 0.5 * (sig_prev + np.minimum(sig, sig_max))
            mid_v = sig_max + 0.5 * virgin
            dh = h * (c_m(mid_v) * virgin + c_m(mid_r) / cr * reload)
            comp += dh
            sig_max = np.maximum(sig_max, sig)
            sig_prev = sig
            dv = -comp                                                      # m (x nucleus area in g)
            uz[:, i] += gz @ dv * 1000.0
            ue[:, i] += ge @ dv * 1000.0
    return dates, uz, ue


def _interp(dates_model, series, dates_obs):
    xm = np.array([d.toordinal() for d in dates_model], dtype=float)
    xo = np.array([d.toordinal() for d in dates_obs], dtype=float)
    return np.array([np.interp(xo, xm, s) for s in series])


def fit_stats(days, y):
    """EGMS-style statistics of a series: fit a + v t + acc t^2 / 2 + seasonal sinusoid."""
    t = (days - days.mean()) / 365.25
    A = np.column_stack([np.ones_like(t), t, 0.5 * t * t, np.sin(2 * math.pi * t), np.cos(2 * math.pi * t)])
    coef, *_ = np.linalg.lstsq(A, y, rcond=None)
    res = y - A @ coef
    dof = max(len(y) - A.shape[1], 1)
    s2 = float(res @ res) / dof
    cov = np.linalg.inv(A.T @ A) * s2
    amp = math.hypot(coef[3], coef[4])
    if amp > 0:
        g = np.array([0, 0, 0, coef[3] / amp, coef[4] / amp])
        amp_std = math.sqrt(max(float(g @ cov @ g), 0.0))
    else:
        amp_std = math.sqrt(cov[3, 3])
    return {
        "rmse": math.sqrt(float(res @ res) / len(y)),
        "mean_velocity": coef[1], "mean_velocity_std": math.sqrt(cov[1, 1]),
        "acceleration": coef[2], "acceleration_std": math.sqrt(cov[2, 2]),
        "seasonality": amp, "seasonality_std": amp_std,
    }


def solver_displacements(path, points):
    """The noise-free twin from ugs-solve: a ugs-sample table (pid, date, east_mm, up_mm, ... at the
    solver's steps) for the six PS points -> (dates, uz, ue) in mm, points in `points` order."""
    import csv
    rows = {}
    with open(path, newline="") as fh:
        reader = csv.DictReader(line for line in fh if not line.startswith("#"))
        for r in reader:
            rows.setdefault(r["pid"], []).append((dt.date.fromisoformat(r["date"]), float(r["up_mm"]), float(r["east_mm"])))
    missing = [p[0] for p in points if p[0] not in rows]
    if missing:
        raise RuntimeError(f"{path}: no series for PS points {missing}")
    dates = [d for d, _, _ in rows[points[0][0]]]
    for p in points:
        if [d for d, _, _ in rows[p[0]]] != dates:
            raise RuntimeError(f"{path}: the series of {p[0]} has other dates than {points[0][0]}'s")
    uz = np.array([[u for _, u, _ in rows[p[0]]] for p in points])
    ue = np.array([[e for _, _, e in rows[p[0]]] for p in points])
    return dates, uz, ue


def series(field, seed, traces, aquifers, pressures, points, solver_model=None):
    """Return (acquisition dates, {"U": array, "E": array} in mm, model (dates, uz, ue)).

    With `solver_model` (a ugs-sample table, see solver_displacements) the measured series are the
    solver's displacement plus noise only: the twin the calibration must recover. Without it, the
    Geertsma nuclei model plus a trend per point plus noise (the generator's own model)."""
    if solver_model:
        dates_m, uz, ue = solver_displacements(solver_model, points)
    else:
        dates_m, uz, ue = model_displacements(field, traces, aquifers, pressures, points)
    obs = acquisition_dates()
    days = np.array([d.toordinal() for d in obs], dtype=float)
    yrs = (days - days[0]) / 365.25
    out = {}
    for comp, model in (("U", uz), ("E", ue)):
        m = _interp(dates_m, model, obs)
        m = m - m[:, :1]
        data = np.empty_like(m)
        for k, p in enumerate(points):
            rng = np.random.default_rng([seed, 300 + k, 0 if comp == "U" else 1])
            sig = np.array([NOISE[comp][0] if d < SENTINEL_START else NOISE[comp][1] for d in obs])
            noise = rng.normal(0.0, 1.0, len(obs)) * sig
            noise[0] = 0.0
            trend = 0.0 if solver_model else TRENDS[p[0]][0 if comp == "U" else 1]
            data[k] = m[k] + trend * yrs + noise
        out[comp] = data
    return obs, out, (dates_m, uz, ue)


def _f(v, nd):
    s = f"{v:.{nd}f}"
    return s[1:] if s.startswith("-") and float(s) == 0.0 else s


def write_egms_csv(path, points, heights, east_north_3035, obs, data):
    """EGMS L3 (ortho) CSV layout: static columns then one column per date (YYYYMMDD), mm."""
    days = np.array([d.toordinal() for d in obs], dtype=float)
    cols = ["pid", "easting", "northing", "height", "rmse", "mean_velocity", "mean_velocity_std",
            "acceleration", "acceleration_std", "seasonality", "seasonality_std"]
    with open(path, "w", newline="\n") as fh:
        fh.write(",".join(cols + [d.strftime("%Y%m%d") for d in obs]) + "\n")
        for k, p in enumerate(points):
            y = np.round(data[k], 2)
            st = fit_stats(days, y)
            e, nn = east_north_3035[k]
            row = [p[0], _f(e, 2), _f(nn, 2), _f(heights[k], 1), _f(st["rmse"], 2),
                   _f(st["mean_velocity"], 2), _f(st["mean_velocity_std"], 2),
                   _f(st["acceleration"], 3), _f(st["acceleration_std"], 3),
                   _f(st["seasonality"], 2), _f(st["seasonality_std"], 2)]
            row += [_f(v, 2) for v in y]
            fh.write(",".join(row) + "\n")
