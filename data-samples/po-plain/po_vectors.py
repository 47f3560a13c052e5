"""Vector geometry of the po-plain twin: traces, aquifers, faults, sections, points, domain.

Geometries are plain lists of (x, y) in EPSG:32632; po_io writes them through OGR.
"""

import math

import numpy as np
from osgeo import ogr

import po_field as F

# --------------------------------------------------------------------------------------------------
# Regional faults (thesis 2.1, 4.3.4): an overthrust with northern (Apennine) vergence and a
# back-thrust with southern vergence, E-W to NW-SE, from -500 to -5,000 m. Each line is the trace of
# the fault plane at z = top_m; the surface is that line translated down-dip along dip_dir_deg with
# the dip dip_deg down to bottom_m. Vertices in the fold frame (u along the axis, v towards NNE).
# The faults lie outside the depleted volume (thesis 4.3.4): both dip towards the pools, so their
# surfaces come closest to the aquifers at the deepest sands (about -1,800 m on the flanks);
# FAULT_OFFSET_V moves each fault across the axis, away from the aquifers' hydraulic limits (the
# lines "v" at AQUIFER_Z, which stay where they were), so that every fault surface keeps at least
# FAULT_CLEARANCE from every aquifer over the sands' depths (generate.py checks it).
# --------------------------------------------------------------------------------------------------
FAULT_OFFSET_V = {"overthrust_north": 2500.0, "backthrust_south": -2200.0}
FAULT_CLEARANCE = 1800.0                  # m, horizontal, fault surface to aquifer polygon
SANDS_Z = (-1400.0, -1850.0)              # elevations of the pools' sands in the aquifers (top, bottom)
REGIONAL_TRACE_Z = -1500.0                # faults.geojson gives the regional traces at the pools' level
                                          # (trace_z_m), which keeps them inside the small twin's domain

REGIONAL_FAULTS = [
    {
        "name": "overthrust_north", "kind": "regional_overthrust",
        "u": [-15000.0, -7000.0, 0.0, 7000.0, 15000.0], "v": [4800.0, 5100.0, 5200.0, 5000.0, 4700.0],
        "top_m": -500.0, "bottom_m": -5000.0, "dip_deg": 35.0, "dip_dir_deg": F.AXIS_BEARING + 90.0,
        "note": "main thrust of the buried Apennine front, verging N; dips SSW beneath the anticline, under the pools below -3,500 m",
    },
    {
        "name": "backthrust_south", "kind": "regional_backthrust",
        "u": [-14000.0, -7000.0, 0.0, 7000.0, 14000.0], "v": [-5100.0, -5200.0, -5300.0, -5100.0, -5000.0],
        "top_m": -500.0, "bottom_m": -5000.0, "dip_deg": 60.0, "dip_dir_deg": F.AXIS_BEARING - 90.0,
        "note": "back-thrust verging S; dips NNE, about 5.4 km clear of the overthrust at -5,000 m",
    },
]

# Local extensional/transtensive faults on the top and southern side of the trap (thesis 2.1):
# sub-vertical, NE-SW to E-W, short, confined around the reservoir.
# centre in the fold frame (u, v), strike bearing, length.
LOCAL_FAULTS = [
    {"name": "local_1", "u": -600.0, "v": 350.0, "bearing": 95.0, "length": 2400.0,
     "top_m": -1300.0, "bottom_m": -1650.0, "dip_deg": 84.0, "dip_dir_deg": 185.0},
    {"name": "local_2", "u": 1850.0, "v": 250.0, "bearing": 65.0, "length": 1800.0,
     "top_m": -1320.0, "bottom_m": -1640.0, "dip_deg": 80.0, "dip_dir_deg": 335.0},
    {"name": "local_3", "u": -150.0, "v": -1250.0, "bearing": 50.0, "length": 1500.0,
     "top_m": -1350.0, "bottom_m": -1680.0, "dip_deg": 82.0, "dip_dir_deg": 140.0},
    {"name": "local_4", "u": -1800.0, "v": -1500.0, "bearing": 100.0, "length": 2000.0,
     "top_m": -1350.0, "bottom_m": -1700.0, "dip_deg": 80.0, "dip_dir_deg": 10.0},
]

# Gas-water contacts (elevation of the contour of each pool's top that bounds the trace).
GWC = {"Pool A": -1495.0, "Pool C": -1575.0}
# Elevation at which the regional faults bound each pool's aquifer (about mid-pool on the structure).
AQUIFER_Z = {"Pool A": -1445.0, "Interlayer": -1487.0, "Pool C": -1507.0}
AQUIFER_HALF_LENGTH = 9000.0   # lateral (along-axis) limit of the aquifers either side of the crest


def regional_fault_lines():
    out = []
    for f in REGIONAL_FAULTS:
        x, y = F.from_uv(f["u"], np.asarray(f["v"]) + FAULT_OFFSET_V[f["name"]])
        out.append((f, list(zip(x.tolist(), y.tolist()))))
    return out


def local_fault_lines():
    out = []
    for f in LOCAL_FAULTS:
        cx, cy = F.from_uv(f["u"], f["v"])
        b = math.radians(f["bearing"])
        dx, dy = 0.5 * f["length"] * math.sin(b), 0.5 * f["length"] * math.cos(b)
        out.append((f, [(float(cx) - dx, float(cy) - dy), (float(cx) + dx, float(cy) + dy)]))
    return out


def fault_line_at(f, line, z):
    """The fault's trace at elevation z (the top trace translated down-dip)."""
    shift = (f["top_m"] - z) / math.tan(math.radians(f["dip_deg"]))
    b = math.radians(f["dip_dir_deg"])
    return [(x + shift * math.sin(b), y + shift * math.cos(b)) for x, y in line]


# --------------------------------------------------------------------------------------------------
# Traces: contours of the pool tops at the gas-water contact, found along rays from a point inside
# --------------------------------------------------------------------------------------------------

def ray_boundary(inside, origin, n=180, rmax=9000.0, step=20.0):
    th = np.arange(n) * (2.0 * math.pi / n)
    s, c = np.sin(th), np.cos(th)
    r = np.arange(0.0, rmax + step, step)
    X = origin[0] + np.outer(s, r)
    Y = origin[1] + np.outer(c, r)
    ins = inside(X, Y)
    if not ins[:, 0].all():
        raise ValueError("ray origin is not inside the region")
    first_out = np.argmax(~ins, axis=1)
    if (first_out == 0).any():
        raise ValueError("region not closed within rmax")
    lo = r[first_out - 1].copy()
    hi = r[first_out].copy()
    for _ in range(40):
        mid = 0.5 * (lo + hi)
        m_in = inside(origin[0] + s * mid, origin[1] + c * mid)
        lo = np.where(m_in, mid, lo)
        hi = np.where(m_in, hi, mid)
    rr = 0.5 * (lo + hi)
    pts = [(float(origin[0] + si * ri), float(origin[1] + ci * ri)) for si, ci, ri in zip(s, c, rr)]
    # clockwise by bearing; OGR/GeoJSON readers accept either orientation. Close the ring.
    pts.reverse()
    pts.append(pts[0])
    return pts


def trace(field, pool):
    t = {s[0]: s[3] for s in F.SURFACES}

    if pool == "Pool A":
        def inside(x, y):
            return field.surface_indep("pool_a_top", t["pool_a_top"], x, y) >= GWC["Pool A"]
        return ray_boundary(inside, F.CREST)

    if pool == "Pool C":
        def inside(x, y):
            s = field.all_surfaces(x, y)
            X, Y = F.to_local(x, y)
            d, dpo = field.pinch_d(X, Y)
            # the gas column needs sand: stop 50 m short of the zero-thickness line
            return (s["pool_c_top"] >= GWC["Pool C"]) & (d < dpo - 50.0)
        return ray_boundary(inside, F.P_REF)
    raise KeyError(pool)


# --------------------------------------------------------------------------------------------------
# Aquifers: the pool's sand between the two regional faults at the pool's depth, within
# AQUIFER_HALF_LENGTH of the crest along the axis; Pool C's also ends at its pinch-out line.
# --------------------------------------------------------------------------------------------------

def _interp_v(f, u, z):
    """v of the aquifer's hydraulic limit at elevation z, at along-axis positions u: the fault's trace
    there before FAULT_OFFSET_V moved the fault away (the aquifers keep the limits they had)."""
    shift = (f["top_m"] - z) / math.tan(math.radians(f["dip_deg"]))
    b = math.radians(f["dip_dir_deg"])
    du = shift * (math.sin(b) * F.AX[0] + math.cos(b) * F.AX[1])
    dv = shift * (math.sin(b) * F.NV[0] + math.cos(b) * F.NV[1])
    if abs(du) > 1e-6 * max(shift, 1.0):
        raise ValueError(f"{f['name']}: dip direction not across the fold axis")
    return np.interp(u, f["u"], f["v"]) + dv


def min_separation(f1, line1, f2, line2, n=20):
    """Smallest horizontal distance between two fault surfaces over their common depth range."""
    lo, hi = max(f1["bottom_m"], f2["bottom_m"]), min(f1["top_m"], f2["top_m"])
    if lo > hi:
        return math.inf
    return min(line_geom(fault_line_at(f1, line1, z)).Distance(line_geom(fault_line_at(f2, line2, z)))
               for z in np.linspace(lo, hi, n))


def fault_footprint(f, line, margin=250.0):
    """Plan projection of a fault surface (its trace at top_m, then at bottom_m reversed), widened by
    margin: the band ugs-mesh2d refines so that the faulted model meshes the fault, not just its trace."""
    ring = fault_line_at(f, line, f["top_m"]) + fault_line_at(f, line, f["bottom_m"])[::-1]
    ring.append(ring[0])
    return polygon_geom(ring).Buffer(margin, 4)


def aquifer_clearance(f, line, geom, n=10):
    """Smallest horizontal distance between a fault surface and a polygon over the sands' depths."""
    return min(line_geom(fault_line_at(f, line, z)).Distance(geom) for z in np.linspace(*SANDS_Z, n))


def aquifer(field, unit):
    z = AQUIFER_Z[unit]
    u = np.arange(-AQUIFER_HALF_LENGTH, AQUIFER_HALF_LENGTH + 1.0, 250.0)
    vn = _interp_v(REGIONAL_FAULTS[0], u, z)
    vs = _interp_v(REGIONAL_FAULTS[1], u, z)
    uu = np.concatenate([u, u[::-1]])
    vv = np.concatenate([vn, vs[::-1]])
    x, y = F.from_uv(uu, vv)
    ring = list(zip(x.tolist(), y.tolist()))
    ring.append(ring[0])
    geom = polygon_geom(ring)
    if unit == "Pool C":
        geom = geom.Intersection(polygon_geom(pinch_region(field)))
    return geom


def pinch_region(field):
    """Polygon of the plan where Pool C has sand (WSW of its pinch-out line)."""
    e = (math.sin(math.radians(F.PINCH_BEARING)), math.cos(math.radians(F.PINCH_BEARING)))
    p = (math.sin(math.radians(F.PINCH_BEARING - 90.0)), math.cos(math.radians(F.PINCH_BEARING - 90.0)))
    s = np.arange(-30000.0, 30000.0 + 1.0, 250.0)
    d = F.PINCH_D0 + s * s / (2.0 * F.PINCH_RC)
    xP, yP = F.P_REF
    line = [(xP + di * e[0] + si * p[0], yP + di * e[1] + si * p[1]) for di, si in zip(d, s)]
    far = -60000.0
    ring = line + [(xP + far * e[0] + s[-1] * p[0], yP + far * e[1] + s[-1] * p[1]),
                   (xP + far * e[0] + s[0] * p[0], yP + far * e[1] + s[0] * p[1])]
    ring.append(ring[0])
    return ring


# --------------------------------------------------------------------------------------------------
# Sections (thesis Figure 4.1, 4.3, 4.4): A-A along the axis (seen from SW), B-B N-S (seen from E)
# --------------------------------------------------------------------------------------------------

def sections():
    ax, ay = F.from_uv([-6000.0, 6000.0], [0.0, 0.0])
    return [
        ({"name": "A-A", "from_label": "A", "to_label": "A'", "view": "from SW to NE",
          "note": "along the fold axis, WNW-ESE"},
         [(float(ax[0]), float(ay[0])), (float(ax[1]), float(ay[1]))]),
        ({"name": "B-B", "from_label": "B", "to_label": "B'", "view": "from E to W",
          "note": "N-S across the fold through the culmination"},
         [(F.CREST[0], F.CREST[1] + 5500.0), (F.CREST[0], F.CREST[1] - 5500.0)]),
    ]


# --------------------------------------------------------------------------------------------------
# OGR helpers
# --------------------------------------------------------------------------------------------------

def polygon_geom(ring):
    r = ogr.Geometry(ogr.wkbLinearRing)
    for x, y in ring:
        r.AddPoint_2D(float(x), float(y))
    g = ogr.Geometry(ogr.wkbPolygon)
    g.AddGeometry(r)
    return g


def line_geom(pts):
    g = ogr.Geometry(ogr.wkbLineString)
    for x, y in pts:
        g.AddPoint_2D(float(x), float(y))
    return g


def point_in_ring(x, y, ring):
    """Even-odd point-in-polygon, vectorized over x, y."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float)
    inside = np.zeros(np.broadcast(x, y).shape, dtype=bool)
    pts = np.asarray(ring, dtype=float)
    x1, y1 = pts[:-1, 0], pts[:-1, 1]
    x2, y2 = pts[1:, 0], pts[1:, 1]
    for a, b, c, d in zip(x1, y1, x2, y2):
        if b == d:
            continue
        cond = ((b > y) != (d > y))
        xint = a + (y - b) * (c - a) / (d - b)
        inside ^= cond & (x < xint)
    return inside


def distance_to_ring(x, y, ring):
    """Distance (m) from points to the boundary of a ring, vectorized over points."""
    x = np.asarray(x, dtype=float).ravel()
    y = np.asarray(y, dtype=float).ravel()
    pts = np.asarray(ring, dtype=float)
    best = np.full(x.shape, np.inf)
    for (a, b), (c, d) in zip(pts[:-1], pts[1:]):
        ex, ey = c - a, d - b
        L2 = ex * ex + ey * ey
        t = np.clip(((x - a) * ex + (y - b) * ey) / L2, 0.0, 1.0) if L2 > 0 else np.zeros_like(x)
        dx = x - (a + t * ex)
        dy = y - (b + t * ey)
        best = np.minimum(best, np.hypot(dx, dy))
    return best


def ring_of(geom):
    """Exterior ring of an OGR polygon (largest part of a multipolygon) as a list of (x, y)."""
    if geom.GetGeometryType() in (ogr.wkbMultiPolygon, ogr.wkbMultiPolygon25D):
        parts = [geom.GetGeometryRef(i) for i in range(geom.GetGeometryCount())]
        geom = max(parts, key=lambda g: g.GetArea())
    r = geom.GetGeometryRef(0)
    return [(r.GetX(i), r.GetY(i)) for i in range(r.GetPointCount())]
