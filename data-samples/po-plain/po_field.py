"""The po-plain synthetic twin: geometry of the field as closed-form functions.

Everything the sample contains (rasters, polygons, the InSAR generator's nuclei of strain) is sampled
from the functions of this module, so the two twins (full and small) describe the same field and
differ only in extent and raster resolution. Local coordinates X, Y are metres east and north of the
anticline culmination CREST (UTM 32N). The rotated frame (u, v) has u along the fold axis (bearing
AXIS_BEARING, towards ESE) and v across it (positive towards NNE, the forelimb side).

The values of the thesis' Table 4.1 at A016VJP are imposed exactly: every independent surface is
written as target + g(X, Y) - g(P), every thickness as target * h(X, Y) / h(P). The generator then
corrects the sampled rasters so that *bilinear* interpolation at A016VJP returns the same values.
"""

import math

import numpy as np

# --------------------------------------------------------------------------------------------------
# Location (see README.md, "Location")
# --------------------------------------------------------------------------------------------------
EPSG = 32632
CRS = "EPSG:32632"

# Domain of the full twin, 42 x 30 km (thesis section 4.1), reservoir almost at the centre.
DOMAIN_FULL = (661000.0, 4937000.0, 703000.0, 4967000.0)    # xmin, ymin, xmax, ymax
CELL_FULL = 100.0
# Small twin used by fast tests: 14 x 12 km around the reservoir (keeps all six PS points, both
# regional faults and both section lines inside), 250 m cells.
DOMAIN_SMALL = (674500.0, 4946300.0, 688500.0, 4958300.0)
CELL_SMALL = 250.0

CREST = (681500.0, 4952300.0)      # culmination of the anticline (Pool A top)
AXIS_BEARING = 105.0               # fold axis WNW-ESE (thesis 2.1: axis from E-W to NW-SE)

SEED_DEFAULT = 1948                # the year the field was discovered (thesis chapter 2)


def _unit(bearing_deg):
    b = math.radians(bearing_deg)
    return math.sin(b), math.cos(b)


AX = _unit(AXIS_BEARING)           # along the axis, towards ESE
NV = _unit(AXIS_BEARING - 90.0)    # across the axis, towards NNE (bearing 15)


def to_local(x, y):
    return np.asarray(x, dtype=float) - CREST[0], np.asarray(y, dtype=float) - CREST[1]


def to_uv(X, Y):
    return X * AX[0] + Y * AX[1], X * NV[0] + Y * NV[1]


def from_uv(u, v):
    """Local (u, v) -> absolute x, y."""
    u = np.asarray(u, dtype=float)
    v = np.asarray(v, dtype=float)
    return CREST[0] + u * AX[0] + v * NV[0], CREST[1] + u * AX[1] + v * NV[1]


# --------------------------------------------------------------------------------------------------
# Points of interest
# --------------------------------------------------------------------------------------------------
# PS points (thesis section 2.3.3, Figure 2.15): three inside the trace, three outside.
# A016VJP and A016VNW sit near the culmination, where the thesis sees the clearest correlation with
# the pressure; A00LFZ4 on the western side of the trace; the external ones 4-6 km away.
# Offsets are metres east, north of CREST.
PS_OFFSETS = [
    ("A00LFZ4", -1487.6, 311.4, True, "internal, western side of the trace"),
    ("A016VJP", 263.4, -128.2, True, "internal, near the culmination; Table 4.1 reference point"),
    ("A016VNW", 1093.7, 262.9, True, "internal, east of the culmination"),
    ("A00LFOB", -4306.2, -4087.5, False, "external, SW sector near the motorway and the railway"),
    ("A016VQ9", 1811.5, 3916.8, False, "external, 4 km N of the culmination, south of the overthrust trace"),
    ("A016VUG", 5588.9, -1893.1, False, "external, ESE, beyond the pinch-out of Pool C"),
]


def ps_points():
    """[(pid, x, y, inside, note)] in EPSG:32632."""
    return [(pid, CREST[0] + dx, CREST[1] + dy, inside, note) for pid, dx, dy, inside, note in PS_OFFSETS]


P_REF = (CREST[0] + PS_OFFSETS[1][1], CREST[1] + PS_OFFSETS[1][2])   # A016VJP

# --------------------------------------------------------------------------------------------------
# Table 4.1: surfaces top to bottom, elevation at A016VJP, sub-layers of the unit below each surface
# --------------------------------------------------------------------------------------------------
SURFACES = [
    # key, file, display name, elevation at A016VJP (m), name of the unit below, layers of that unit
    ("dem", "01_dem.tif", "DEM", 50.0, "Alluvium", 2),
    ("alluvial_base", "02_alluvial_base.tif", "Alluvial base", -346.0, "Pleistocene sands", 2),
    ("santerno_top", "03_santerno_top.tif", "Santerno top (Asti base)", -1024.0, "Upper Pliocene sands", 2),
    ("up_sands_base", "04_upper_pliocene_sands_base.tif", "Upper Pliocene sands base", -1152.0,
     "Santerno clays", 3),
    ("pool_a_top", "05_pool_a_top.tif", "Pool A top (Pliocene base)", -1410.0, "Pool A", 5),
    ("pool_a_base", "06_pool_a_base.tif", "Pool A base", -1476.0, "Interlayer", 3),
    ("pool_c_top", "07_pool_c_top.tif", "Pool C top", -1498.0, "Pool C", 8),
    ("pool_c_base", "08_pool_c_base.tif", "Pool C base", -1515.0, "Miocene sands", 2),
    ("miocene_clays_top", "09_miocene_clays_top.tif", "Miocene clays top (Miocene sands base)", -1543.0,
     "Miocene clays", 2),
    ("marls_top", "10_marls_top.tif", "Marls top", -1543.0, "Marls", 10),
    ("limestones_top", "11_limestones_top.tif", "Limestones top", -8655.0, "Limestones", 2),
]
MODEL_BOTTOM = -10000.0
UNITS = [s[4] for s in SURFACES]
LAYERS = [s[5] for s in SURFACES]
assert sum(LAYERS) == 41

# --------------------------------------------------------------------------------------------------
# Smooth random fields (seeded): sums of plane waves with wavelengths of 3-15 km, unit variance
# --------------------------------------------------------------------------------------------------


class SmoothField:
    def __init__(self, seed, stream, n_modes=24, lmin=3000.0, lmax=15000.0):
        rng = np.random.default_rng([seed, stream])
        lam = np.exp(rng.uniform(math.log(lmin), math.log(lmax), n_modes))
        theta = rng.uniform(0.0, 2.0 * math.pi, n_modes)
        self.kx = 2.0 * math.pi / lam * np.cos(theta)
        self.ky = 2.0 * math.pi / lam * np.sin(theta)
        self.phase = rng.uniform(0.0, 2.0 * math.pi, n_modes)
        amp = lam / lmax                         # red spectrum: long waves dominate
        self.amp = amp / math.sqrt(0.5 * float(np.sum(amp ** 2)))

    def __call__(self, X, Y):
        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        out = np.zeros(np.broadcast(X, Y).shape)
        for kx, ky, ph, a in zip(self.kx, self.ky, self.phase, self.amp):
            out += a * np.cos(kx * X + ky * Y + ph)
        return out


def fold(u, v, Lu, Ln, Ls):
    """Asymmetric dome: Gaussian along the axis, half-widths Ln on the north (forelimb, steeper) and
    Ls on the south (backlimb) side."""
    Lv = np.where(v >= 0.0, Ln, Ls)
    return np.exp(-(u / Lu) ** 2 - (v / Lv) ** 2)


def regional(X, Y, slope, bearing):
    """Planar regional dip: deepens by `slope` m per m towards `bearing`."""
    s, c = _unit(bearing)
    return -slope * (X * s + Y * c)


# Pinch-out of Pool C towards E-NE (thesis 2.1): the unit vanishes beyond a gently curved line
# PINCH_D0 m ENE of A016VJP.
PINCH_BEARING = 67.5
PINCH_D0 = 1700.0
PINCH_RC = 12000.0            # radius of curvature of the line (concave towards WSW)
PC_T_WEST = 20.0              # Pool C thickness far WSW of the line
PC_DECAY = 900.0              # m, e-folding distance of the thinning

# Pinch-out of the Miocene clays: absent on an ellipse over the structure (onlap of the clays onto
# the growing anticline), 150 m at 1.5x the ellipse and up to 450 m in the synclines.
MC_WU, MC_WV = 5500.0, 2800.0
MC_CENTRE = (-200.0, 100.0)   # local X, Y of the ellipse centre


class Field:
    """All surfaces and thicknesses as vectorized functions of absolute x, y (EPSG:32632)."""

    def __init__(self, seed=SEED_DEFAULT):
        self.seed = seed
        f = [SmoothField(seed, k) for k in range(12)]
        self.noise = f
        XP, YP = to_local(*P_REF)
        self.XP, self.YP = float(XP), float(YP)

    # ---------------------------------------------------------------- independent surfaces (shape)
    def _g(self, key, X, Y):
        u, v = to_uv(X, Y)
        n = self.noise
        if key == "dem":        # Po plain: ~0.6 m/km towards the Po (NNE), metre-scale undulation
            return regional(X, Y, 0.0006, 30.0) + 0.6 * n[0](X, Y)
        if key == "alluvial_base":
            return regional(X, Y, 0.003, 20.0) + 15.0 * fold(u, v, 9000.0, 6000.0, 8000.0) + 4.0 * n[1](X, Y)
        if key == "santerno_top":
            return regional(X, Y, 0.007, 20.0) + 45.0 * fold(u, v, 7000.0, 4000.0, 6000.0) + 5.0 * n[2](X, Y)
        if key == "up_sands_base":
            return regional(X, Y, 0.009, 20.0) + 70.0 * fold(u, v, 5500.0, 2500.0, 4000.0) + 3.0 * n[3](X, Y)
        if key == "pool_a_top":
            return regional(X, Y, 0.010, 20.0) + 165.0 * fold(u, v, 3800.0, 1400.0, 2500.0) + 1.5 * n[4](X, Y)
        if key == "limestones_top":
            return regional(X, Y, 0.020, 20.0) + 350.0 * fold(u, v, 12000.0, 5000.0, 9000.0) + 20.0 * n[5](X, Y)
        raise KeyError(key)

    # ---------------------------------------------------------------- thicknesses (shape)
    def _h(self, unit, X, Y):
        u, v = to_uv(X, Y)
        n = self.noise
        if unit == "Pool A":     # lens thinning eastwards, ~100 m to ~25 m across the trace (2.1)
            return (1.0 - 0.65 * np.tanh(u / 3000.0)) * (1.0 + 0.04 * n[6](X, Y))
        if unit == "Interlayer":  # metric to decametric clays between the pools (2.1)
            return np.clip(1.0 + 0.2 * n[7](X, Y), 0.4, 1.8)
        if unit == "Pool C":
            return self.pool_c_shape(X, Y) * (1.0 + 0.05 * n[8](X, Y))
        if unit == "Miocene sands":
            return np.clip(1.0 + 0.15 * n[9](X, Y), 0.5, 1.6)
        if unit == "Miocene clays":
            Xc, Yc = X - MC_CENTRE[0], Y - MC_CENTRE[1]
            uc, vc = to_uv(Xc, Yc)
            q = np.sqrt((uc / MC_WU) ** 2 + (vc / MC_WV) ** 2)
            base = np.minimum(150.0 * np.maximum(q - 1.0, 0.0) ** 1.2, 450.0)
            return base * np.clip(1.0 + 0.1 * n[10](X, Y), 0.5, 1.5)
        raise KeyError(unit)

    def pinch_d(self, X, Y):
        """(distance ENE of A016VJP, distance of the pinch-out line) for local X, Y."""
        e = _unit(PINCH_BEARING)
        p = _unit(PINCH_BEARING - 90.0)
        dX, dY = X - self.XP, Y - self.YP
        d = dX * e[0] + dY * e[1]
        s = dX * p[0] + dY * p[1]
        return d, PINCH_D0 + s * s / (2.0 * PINCH_RC)

    def pool_c_shape(self, X, Y):
        d, dpo = self.pinch_d(X, Y)
        return np.where(d < dpo, PC_T_WEST * (1.0 - np.exp(-(dpo - d) / PC_DECAY)), 0.0)

    # ---------------------------------------------------------------- public, absolute coordinates
    def surface_indep(self, key, target, x, y):
        X, Y = to_local(x, y)
        return target + self._g(key, X, Y) - self._g(key, np.array(self.XP), np.array(self.YP))

    def thickness(self, unit, target, x, y):
        """Thickness (m) of `unit`; `target` is its thickness at A016VJP (Table 4.1)."""
        X, Y = to_local(x, y)
        hp = float(self._h(unit, np.array(self.XP), np.array(self.YP)))
        if target == 0.0:
            # a unit pinched out at A016VJP (the Miocene clays): its shape is already in metres
            if hp != 0.0:
                raise ValueError(f"{unit}: zero thickness required at A016VJP, shape gives {hp}")
            return self._h(unit, X, Y)
        return target * self._h(unit, X, Y) / hp

    def all_surfaces(self, x, y):
        """Dict key -> elevation for the 11 surfaces, analytic (no raster correction)."""
        t = {s[0]: s[3] for s in SURFACES}
        out = {}
        for key in ("dem", "alluvial_base", "santerno_top", "up_sands_base", "pool_a_top"):
            out[key] = self.surface_indep(key, t[key], x, y)
        out["pool_a_base"] = out["pool_a_top"] - self.thickness("Pool A", t["pool_a_top"] - t["pool_a_base"], x, y)
        out["pool_c_top"] = out["pool_a_base"] - self.thickness("Interlayer", t["pool_a_base"] - t["pool_c_top"], x, y)
        out["pool_c_base"] = out["pool_c_top"] - self.thickness("Pool C", t["pool_c_top"] - t["pool_c_base"], x, y)
        out["miocene_clays_top"] = out["pool_c_base"] - self.thickness(
            "Miocene sands", t["pool_c_base"] - t["miocene_clays_top"], x, y)
        out["marls_top"] = out["miocene_clays_top"] - self.thickness("Miocene clays", 0.0, x, y)
        out["limestones_top"] = self.surface_indep("limestones_top", t["limestones_top"], x, y)
        return out
