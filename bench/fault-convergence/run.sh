#!/bin/sh
# Mesh convergence of the po-plain twin's fault answer (issue 21, "a converged answer on the twin"):
# the demo's faulted model (data-samples/po-plain Makefile, SCALE=demo, target `faults`) on three
# fault-mesh resolutions FAULT_H (the plan size over the faults' plan projections and the reservoir),
# the maximum chi per fault over the demo's fault dates per resolution, the change between the two
# finest, the maximum safe scale of the 2025 swing and the wall times. The criterion (change < 0.05 per
# fault between the two finest) applies to the largest chi over the pairs at least CORNER_M (default
# 50 m) from the depleted volume's corners (corners.py: where a fault cuts the top or base of a depleted
# layer the stress change is singular and its maximum does not converge); the raw maximum is printed too.
#
#   sh bench/fault-convergence/run.sh BUILD_DIR [WORK_DIR] [H1 H2 H3]    (default 1400 1000 700 m)
#
# NO_SCALE=1 skips the safe-scale search; FAULT_STRATA=strata_faulted.toml meshes finer down dip.
#
# Each resolution runs in WORK_DIR/h<H> (default BUILD_DIR/bench-fault-convergence); a finished one
# (faulted.h5 newer than its inputs) is not rerun. FAULT_OPTS picks the saddle-point solver
# (default `--fault-solver mumps`: on these flat layered meshes the field split took 222 FGMRES
# iterations per Newton iteration at FAULT_H = 1500, 133 s for the 1964 step).
# Prints Markdown tables; exit 1 when a run fails or the criterion is not met.
set -eu
B=$(cd "${1:?usage: run.sh BUILD_DIR [WORK_DIR] [H1 H2 H3]}" && pwd)
W=${2:-$B/bench-fault-convergence}
shift $(( $# < 2 ? $# : 2 ))
[ $# -ge 3 ] && HS="$1 $2 $3" || HS="1400 1000 700"
HERE=$(cd "$(dirname "$0")" && pwd)
export HERE
SAMPLE=$(cd "$HERE/../../data-samples/po-plain" && pwd)
FAULT_OPTS=${FAULT_OPTS:---fault-solver mumps}
mkdir -p "$W"
W=$(cd "$W" && pwd)

# The faulted run's case: the sample's, with the fault fields and per-pair CSVs written at every step
# (the 11 fault dates and the 3 output dates: the same 14 steps), so that the measure away from the
# reservoir corners (below) sees the same dates as the faults CSV; schedule paths made absolute.
ALL_DATES='"1950-01-01", "1964-04-01", "1991-04-01", "2014-11-01", "2015-04-01", "2015-05-01", "2015-11-01", "2016-04-01", "2016-05-01", "2024-11-01", "2025-04-01", "2025-05-01", "2025-11-01", "2026-04-01"'
for h in $HS; do
  out=$W/h$h
  mkdir -p "$out"
  sed -e "s|^dates = \[.*|dates = [$ALL_DATES]|" -e "s|^schedule = \"|schedule = \"$SAMPLE/|" "$SAMPLE/case.toml" > "$out/case.tmp"
  cmp -s "$out/case.tmp" "$out/case.toml" && rm "$out/case.tmp" || mv "$out/case.tmp" "$out/case.toml"
  t0=$(date +%s)
  make -s -C "$SAMPLE" faults UGS_BIN="$B/tools" OUT="$out" SCALE=demo FAULT_H="$h" FAULT_OPTS="$FAULT_OPTS" FAULT_CASE="$out/case.toml" \
    ${NO_SCALE:+FAULT_SEARCH=} ${FAULT_STRATA:+FAULT_STRATA=$FAULT_STRATA} \
    > "$out/make.log" 2>&1 || { tail -5 "$out/make.log"; echo "FAIL: the faulted run at FAULT_H=$h failed"; exit 1; }
  t1=$(date +%s)
  [ -f "$out/seconds" ] && [ "$out/seconds" -nt "$out/faulted.h5" ] || echo $(( t1 - t0 )) > "$out/seconds"
done

# max chi per fault over the fault dates (node pairs on free degrees of freedom: the CSV's statistics),
# raw and over the pairs at least CORNER_M (default 50 m) from the depleted volume's corners (corners.py)
/usr/bin/python3 - "$W" "$SAMPLE" "${CORNER_M:-50}" $HS <<'EOF'
import csv, math, os, re, sys
sys.path.insert(0, os.environ["HERE"])
from corners import Corners
work, sample, dmin, hs = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4:]
C = Corners(sample, dmin)

def rows_of(path):
    with open(path, newline="") as fh:
        return list(csv.DictReader(l for l in fh if not l.startswith("#")))

rows, away, info = {}, {}, {}
for h in hs:
    d = os.path.join(work, "h" + h)
    best = {}
    for r in rows_of(os.path.join(d, "faulted_faults.csv")):
        if r["date"] == "1950-01-01":
            continue
        f, chi = r["fault"], float(r["max_chi"])
        if f not in best or chi > best[f][0]:
            best[f] = (chi, r["date"], float(r["z_m"]), int(r["slipping"]), int(r["open"]))
    rows[h] = best
    away[h] = {}
    for f in best:
        dist, top, n_near, n_all = {}, None, set(), set()
        for r in rows_of(os.path.join(d, "faulted_fault_%s.csv" % re.sub(r"[^A-Za-z0-9._-]", "_", f))):
            if r["date"] == "1950-01-01" or r["interpolated"] != "0":
                continue
            n = r["node"]
            if n not in dist:
                dist[n] = C.distance(float(r["x_m"]), float(r["y_m"]), float(r["z_m"]))
            n_all.add(n)
            if dist[n] < dmin:
                n_near.add(n)
                continue
            chi = float(r["chi"])
            if top is None or chi > top[0]:
                top = (chi, r["date"], float(r["z_m"]), dist[n])
        away[h][f] = (top, len(n_near), len(n_all))
    log = open(os.path.join(d, "faulted.log")).read()
    m = re.search(r"mesh: (\d+) nodes, (\d+) tetrahedra, (\d+) interface elements", log)
    s = re.search(r"maximum safe scale ([0-9.]+)", log)
    top = re.search(r"reaches chi = 1 up to scale ([0-9.]+)", log)
    info[h] = (m.groups() if m else ("?", "?", "?"), s.group(1) if s else
               ("none" if "no scale of the later swing" in log else ("> " + top.group(1) if top else "not run")),
               open(os.path.join(d, "seconds")).read().strip())
faults = list(rows[hs[0]])
print("Raw maximum (every pair; the faults CSV):")
print()
print("| FAULT_H (m) | nodes | tetrahedra | interface elements | " + " | ".join(faults) + " | safe scale | wall (s) |")
print("|---" * (6 + len(faults)) + "|")
for h in hs:
    (n, t, ie), safe, sec = info[h]
    cells = []
    for f in faults:
        chi, date, z, sl, op = rows[h][f]
        cells.append(f"{chi:.3f} ({date}, z {z:.0f}{', %d slip' % sl if sl else ''}{', %d open' % op if op else ''})")
    print(f"| {h} | {int(n):,} | {int(t):,} | {int(ie):,} | " + " | ".join(cells) + f" | {safe} | {sec} |")
print()
print(f"Away from the depleted volume's corners (pairs at least {dmin:g} m from the top or base of Pool A, the"
      " Interlayer or Pool C inside their aquifer polygons; pairs left out / pairs):")
print()
print("| FAULT_H (m) | " + " | ".join(faults) + " |")
print("|---" * (1 + len(faults)) + "|")
for h in hs:
    cells = []
    for f in faults:
        top, nn, na = away[h][f]
        cells.append("none" if top is None else f"{top[0]:.3f} ({top[1]}, z {top[2]:.0f}; {nn}/{na} out)")
    print(f"| {h} | " + " | ".join(cells) + " |")
a, b = hs[-2], hs[-1]
raw = {f: abs(rows[a][f][0] - rows[b][f][0]) for f in faults}
acc = {f: (abs(away[a][f][0][0] - away[b][f][0][0]) if away[a][f][0] and away[b][f][0] else math.inf)
       for f in faults}
print()
print("change of raw max chi between FAULT_H = %s and %s m: " % (a, b)
      + ", ".join(f"{f} {raw[f]:.3f}" for f in faults))
print("change away from the corners (the criterion, < 0.05): "
      + ", ".join(f"{f} {acc[f]:.3f}" for f in faults) + f"; largest {max(acc.values()):.3f}")
# Key metrics for bench/run-all (RESULTS.md, history.csv).
print(f"metric: fault-convergence.max_chi_change_away_from_corners {max(acc.values()):.4f} 1")
for h in hs:
    print(f"metric: fault-convergence.h{h}.wall {info[h][2]} s")
sys.exit(0 if max(acc.values()) < 0.05 else 1)
EOF
