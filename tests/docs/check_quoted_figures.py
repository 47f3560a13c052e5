#!/usr/bin/env python3
"""Every figure the documentation quotes with a source marker equals its source.

A marker is an HTML comment right after the quoted figure (GitHub and most renderers hide it):

    117.7 s<!--R:faulted/ugs-solve.faulted.wall-->   bench/RESULTS.md: section `faulted`, metric of its table
    2026-11-28<!--R:faulted/date-->, c502f5b<!--R:faulted/commit-->   that section's date and commit
    1,920 m<!--S:clearance/overthrust_north-->       computed from data-samples/po-plain's files (below)
    0.092<!--F:docs/fault-convergence.md-->          appears, as written, in that file

Between the figure and the marker only a unit may stand (no digit). A number matches when the
source value, in the same unit or scaled by 1e-3 / 1e3 (MB -> GB, m -> km), rounds to the quoted
figure at the quoted number of decimals. The sample's quantities (S):

    clearance/<fault>         least horizontal distance (m) between the regional fault's surface and every
                              aquifer polygon over the sands' depths (po_vectors.SANDS_Z), from
                              faults.geojson (trace at trace_z_m, moved down dip) and aquifers.geojson
    generator/<NAME>          a number of po_vectors.py (FAULT_CLEARANCE, REGIONAL_TRACE_Z, ...)
    fault/<name>/<attribute>  an attribute of faults.geojson
    separation/<z>            distance (m) between the two regional fault surfaces at elevation z
    crest/<fault>/<z>         distance (m) from the crest of the anticline (po_field.CREST) to the fault at z

Files read: README.md, docs/*.md, data-samples/po-plain/README.md (markers inside `code spans` are
examples and are skipped). Fails on a marker whose source
does not hold the figure, on an unknown marker, and on a marker with no figure before it.
Run: check_quoted_figures.py --source REPO
"""

import argparse
import glob
import math
import os
import re
import sys

FAILED = []


def check(ok, what):
    print(("ok    " if ok else "FAIL  ") + what)
    if not ok:
        FAILED.append(what)


MARKER = re.compile(r"<!--([RSF]):([^>]*?)-->")
# The figure just before a marker: a date, a commit hash, or a number (1,920 / -1,500 / 0.092);
# then at most a unit (no digit) up to the marker.
FIGURE = re.compile(r"(\d{4}-\d{2}-\d{2}|\b[0-9a-f]{7,40}\b|-?\d[\d,]*(?:\.\d+)?)([^\d<>]{0,12})$")


def quoted_markers(path):
    """(line number, figure, kind, key) for every marker of a Markdown file."""
    out = []
    for n, line in enumerate(open(path, encoding="utf-8"), 1):
        for m in MARKER.finditer(line):
            if line[:m.start()].count("`") % 2:
                continue   # inside a code span: an example of the syntax, not a quote
            f = FIGURE.search(line[:m.start()])
            out.append((n, f.group(1) if f else None, m.group(1), m.group(2).strip()))
    return out


def number_matches(quoted, value):
    q = quoted.replace(",", "")
    decimals = len(q.split(".")[1]) if "." in q else 0
    for scale in (1.0, 1e-3, 1e3):
        if math.isclose(round(value * scale, decimals), float(q), rel_tol=0.0, abs_tol=1e-9):
            return True
    return False


# ---------------------------------------------------------------------------------------------------
# bench/RESULTS.md: sections between <!-- bench: NAME --> and <!-- end bench: NAME -->

def results_sections(path):
    text = open(path, encoding="utf-8").read()
    out = {}
    for m in re.finditer(r"<!-- bench: (\S+) -->(.*?)<!-- end bench: \1 -->", text, re.S):
        name, body = m.group(1), m.group(2)
        sec = {}
        head = re.search(r"; (\d{4}-\d{2}-\d{2})T[^;]*; commit ([0-9a-f]+)", body)
        if head:
            sec["date"], sec["commit"] = head.group(1), head.group(2)
        for row in re.finditer(r"^\| (\S+) \| (-?[\d.]+) \| \S+ \|$", body, re.M):
            sec[row.group(1)] = float(row.group(2))
        out[name] = sec
    return out


def results_value(sections, key, quoted):
    name, _, metric = key.partition("/")
    if name not in sections:
        return False, f"no section '{name}' in bench/RESULTS.md"
    sec = sections[name]
    if metric not in sec:
        return False, f"section '{name}' has no '{metric}'"
    v = sec[metric]
    if metric == "commit":
        return v.startswith(quoted) and len(quoted) >= 7, f"commit {v[:12]}"
    if metric == "date":
        return v == quoted, f"date {v}"
    return number_matches(quoted, v), f"{metric} = {v:g}"


# ---------------------------------------------------------------------------------------------------
# data-samples/po-plain: the generator's constants and its committed files

class Sample:
    def __init__(self, root):
        self.dir = os.path.join(root, "data-samples", "po-plain")
        sys.path.insert(0, self.dir)
        sys.dont_write_bytecode = True   # no __pycache__ in the sample folder
        import po_field   # noqa: E402  (the generator's modules: GDAL and NumPy, Debian's python3)
        import po_vectors
        from osgeo import ogr
        self.F, self.V, self.ogr = po_field, po_vectors, ogr
        self.faults = {a["name"]: (a, g) for a, g in self.features("faults.geojson")}
        self.aquifers = [g for _, g in self.features("aquifers.geojson")]

    def features(self, name):
        ds = self.ogr.Open(os.path.join(self.dir, name))
        lyr = ds.GetLayer()
        out = [({k: f.GetField(k) for k in f.keys()}, f.GetGeometryRef().Clone()) for f in lyr]
        return out

    def surface_at(self, fault, z):
        """The fault's surface at elevation z: its trace (at trace_z_m) moved down dip."""
        a, g = self.faults[fault]
        shift = (a["trace_z_m"] - z) / math.tan(math.radians(a["dip_deg"]))
        b = math.radians(a["dip_dir_deg"])
        line = self.ogr.Geometry(self.ogr.wkbLineString)
        for x, y in g.GetPoints():
            line.AddPoint_2D(x + shift * math.sin(b), y + shift * math.cos(b))
        return line

    def regional(self):
        return [n for n, (a, _) in self.faults.items() if a["kind"].startswith("regional")]

    def value(self, key):
        parts = key.split("/")
        if parts[0] == "clearance" and len(parts) == 2 and parts[1] in self.faults:
            top, bottom = self.V.SANDS_Z
            zs = [top + (bottom - top) * i / 9 for i in range(10)]
            return min(self.surface_at(parts[1], z).Distance(p) for z in zs for p in self.aquifers)
        if parts[0] == "generator" and len(parts) == 2 and isinstance(getattr(self.V, parts[1], None), float):
            return getattr(self.V, parts[1])
        if parts[0] == "fault" and len(parts) == 3 and parts[1] in self.faults:
            v = self.faults[parts[1]][0].get(parts[2])
            return float(v) if isinstance(v, (int, float)) else None
        if parts[0] == "separation" and len(parts) == 2:
            a, b = self.regional()
            z = float(parts[1])
            return self.surface_at(a, z).Distance(self.surface_at(b, z))
        if parts[0] == "crest" and len(parts) == 3 and parts[1] in self.faults:
            crest = self.ogr.Geometry(self.ogr.wkbPoint)
            crest.AddPoint_2D(*self.F.CREST)
            return self.surface_at(parts[1], float(parts[2])).Distance(crest)
        return None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, help="the repository")
    args = ap.parse_args()
    root = os.path.abspath(args.source)
    docs = [os.path.join(root, "README.md"), os.path.join(root, "data-samples", "po-plain", "README.md")]
    docs += sorted(glob.glob(os.path.join(root, "docs", "*.md")))
    sections = results_sections(os.path.join(root, "bench", "RESULTS.md"))
    sample = None
    count = 0
    for path in docs:
        rel = os.path.relpath(path, root)
        for line, quoted, kind, key in quoted_markers(path):
            count += 1
            where = f"{rel}:{line}: '{quoted}' <!--{kind}:{key}-->"
            if quoted is None:
                check(False, f"{rel}:{line}: marker <!--{kind}:{key}--> with no figure right before it")
                continue
            if kind == "R":
                ok, said = results_value(sections, key, quoted)
            elif kind == "F":
                src = os.path.join(root, key)
                ok = os.path.isfile(src) and quoted in open(src, encoding="utf-8").read()
                said = "in the file" if ok else ("not in the file" if os.path.isfile(src) else "no such file")
            else:
                sample = sample or Sample(root)
                v = sample.value(key)
                ok = v is not None and number_matches(quoted, v)
                said = "unknown quantity" if v is None else f"{v:.6g}"
            check(ok, f"{where} (source: {said})")
    check(count > 0, f"{count} quoted figures with a source marker")
    if FAILED:
        print(f"{len(FAILED)} of {count} quoted figures disagree with their source: update the text "
              "(or the marker) to what the source holds now")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())
