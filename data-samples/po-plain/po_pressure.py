"""Average pool pressures of the po-plain twin, monthly 1950-01 .. 2033-12 (thesis 2.2, 4.2.1, 4.3.3).

Pressures are normalized to the initial pressure of Pool C (as in the thesis' Figure 2.7), which we
take hydrostatic at the Pool C datum:

    P0_C = GAMMA_W * (Z_WATER_TABLE - Z_DATUM_C) = 0.00981 MPa/m * (50 m + 1,500 m) = 15.2055 MPa

with the water table at the ground surface (DEM = 50 m at A016VJP) and the Pool C datum at -1,500 m
(the top of Pool C is at -1,498 m there). Pool A starts from its own hydrostatic pressure at its datum
-1,440 m: 0.00981 * 1,490 = 14.6169 MPa = 0.96129 P0_C.

Storage cycles are built from one minimum (1 April) and one maximum (1 November) per year: the
injection runs April -> November, the withdrawal November -> April, both as half-cosine ramps.
"""

import datetime as dt
import math

import numpy as np

GAMMA_W = 9810.0                        # N/m3, water unit weight
GRAD_W = GAMMA_W * 1e-6                 # MPa/m
Z_WATER_TABLE = 50.0                    # m, ground level at A016VJP
Z_DATUM = {"Pool A": -1440.0, "Pool C": -1500.0}
P0_C = GRAD_W * (Z_WATER_TABLE - Z_DATUM["Pool C"])    # 15.2055 MPa
P0_A_NORM = (Z_WATER_TABLE - Z_DATUM["Pool A"]) / (Z_WATER_TABLE - Z_DATUM["Pool C"])

START = (1950, 1)
END = (2033, 12)

# Pool C primary production: drops of 35 % by 1960-01 and 52 % by 1964-01 (thesis 4.2.1, Figure 4.6)
DROP_1960 = 0.35
DROP_1964 = 0.52
PC_EXPONENT = math.log(DROP_1964 / DROP_1960) / math.log(14.0 / 10.0)
# forecast cycles 2022-2033 (thesis 4.3.3): identical, spanning 37 % of P0_C
FORECAST_MIN, FORECAST_MAX = 0.585, 0.955
RECENT_SPAN = 0.25                      # 2010s cycles (thesis 4.3.3: "from around 25 % to 37 %")


def months():
    out = []
    y, m = START
    while (y, m) <= END:
        out.append(dt.date(y, m, 1))
        m += 1
        if m == 13:
            y, m = y + 1, 1
    return out


def _t(d):
    return d.year - 1950 + (d.month - 1) / 12.0


def _cycles(dates, p, first_year, last_year, mins, maxs, start_value):
    """Fill p (in place) from 1 April of first_year onwards with the annual cycles.

    mins[Y] is the pressure on 1 April of year Y, maxs[Y] on 1 November of year Y; the cycle of
    last_year ends on 1 April of last_year + 1 (mins[last_year + 1] must exist)."""
    idx = {d: i for i, d in enumerate(dates)}
    assert abs(mins[first_year] - start_value) < 1e-12
    for Y in range(first_year, last_year + 1):
        i_apr = idx.get(dt.date(Y, 4, 1))
        if i_apr is None:
            break
        for k in range(0, 7):            # April .. October: rising to the November maximum
            i = i_apr + k
            if i >= len(dates):
                return
            tau = k / 7.0
            p[i] = mins[Y] + (maxs[Y] - mins[Y]) * 0.5 * (1.0 - math.cos(math.pi * tau))
        for k in range(0, 5):            # November .. March: falling to next April's minimum
            i = i_apr + 7 + k
            if i >= len(dates):
                return
            tau = k / 5.0
            p[i] = mins[Y + 1] + (maxs[Y] - mins[Y + 1]) * 0.5 * (1.0 + math.cos(math.pi * tau))


def pool_c(seed):
    dates = months()
    n = len(dates)
    p = np.full(n, np.nan)
    rng = np.random.default_rng([seed, 201])
    # primary production 1950-01 .. 1964-04 (continues over the first winter of 1964)
    for i, d in enumerate(dates):
        t = _t(d)
        if t <= 14.25 + 1e-9:
            p[i] = 1.0 - DROP_1960 * (t / 10.0) ** PC_EXPONENT
    m1964 = 1.0 - DROP_1960 * (14.25 / 10.0) ** PC_EXPONENT
    mins, maxs = {1964: m1964}, {1964: m1964 + 0.09}
    for Y in range(1965, 2022):
        if Y <= 1996:       # storage grows while some wells keep producing (until 1996)
            mid = 0.52 + 0.14 * ((Y - 1964) / 32.0) ** 0.8
            span = 0.09 + 0.12 * (Y - 1964) / 32.0
        elif Y <= 2009:
            mid = 0.66 + 0.075 * (Y - 1996) / 13.0
            span = 0.21 + 0.04 * (Y - 1996) / 13.0
        else:               # recent cycles: ~25 % span, slight upward drift of the oscillation
            mid = 0.735 + 0.03 * (Y - 2009) / 12.0
            span = RECENT_SPAN
        mid += float(np.clip(rng.normal(0.0, 0.008), -0.02, 0.02))
        span += float(np.clip(rng.normal(0.0, 0.012), -0.025, 0.025))
        mins[Y] = max(mid - 0.5 * span, m1964 + 0.005)
        maxs[Y] = mid + 0.5 * span
    for Y in range(2022, 2035):
        mins[Y], maxs[Y] = FORECAST_MIN, FORECAST_MAX
    _cycles(dates, p, 1964, 2033, mins, maxs, m1964)
    assert not np.isnan(p).any()
    return dates, p


def pool_a(seed):
    dates = months()
    n = len(dates)
    p = np.full(n, np.nan)
    rng = np.random.default_rng([seed, 202])
    p0 = P0_A_NORM
    p1971, p1991 = 0.47, 0.425
    t_store = 41.25                       # 1991-04-01
    for i, d in enumerate(dates):
        t = _t(d)
        if t <= 21.0 + 1e-9:              # primary production 1950-1971
            p[i] = p0 - (p0 - p1971) * (1.0 - math.exp(-t / 9.0)) / (1.0 - math.exp(-21.0 / 9.0))
        elif t <= t_store + 1e-9:         # production tail of a few wells, 1971-1991
            p[i] = p1971 - (p1971 - p1991) * (1.0 - math.exp(-(t - 21.0) / 7.0)) / \
                (1.0 - math.exp(-(t_store - 21.0) / 7.0))
    mins, maxs = {1991: p1991}, {}
    for Y in range(1991, 2002):           # storage 1991-2002, low efficiency: small cycles
        mid = 0.47 + 0.06 * (Y - 1991) / 10.0 + float(np.clip(rng.normal(0.0, 0.006), -0.015, 0.015))
        span = 0.08 + 0.06 * (Y - 1991) / 10.0 + float(np.clip(rng.normal(0.0, 0.008), -0.02, 0.02))
        if Y > 1991:
            mins[Y] = max(mid - 0.5 * span, p1991 + 0.003)
        maxs[Y] = mins[Y] + span if Y == 1991 else mid + 0.5 * span
    mins[2002] = 0.5 * (mins[2001] + maxs[2001]) - 0.02     # last withdrawal, storage stopped 2002
    _cycles(dates, p, 1991, 2001, mins, maxs, p1991)
    # natural re-pressurization by the aquifer after 2002-04, towards the hydrostatic pressure
    t2002 = 52.25
    for i, d in enumerate(dates):
        t = _t(d)
        if t >= t2002 - 1e-9:
            p[i] = p0 - (p0 - mins[2002]) * math.exp(-(t - t2002) / 25.0)
    assert not np.isnan(p).any()
    return dates, p


def write_csv(path, dates, p):
    with open(path, "w", newline="\n") as fh:
        fh.write("date,p_norm,p_MPa\n")
        for d, v in zip(dates, p):
            fh.write(f"{d.isoformat()},{v:.5f},{v * P0_C:.4f}\n")
