#!/bin/sh
# Mesh convergence of the po-plain twin's fault answer (issue 21, "a converged answer on the twin"):
# the demo's faulted model (data-samples/po-plain Makefile, SCALE=demo, target `faults`) on three
# fault-mesh resolutions FAULT_H (the plan size over the faults' plan projections and the reservoir),
# the maximum chi per fault over the demo's fault dates per resolution, the change between the two
# finest (target < 0.05 per fault), the maximum safe scale of the 2025 swing and the wall times.
#
#   sh bench/fault-convergence/run.sh BUILD_DIR [WORK_DIR] [H1 H2 H3]    (default 2000 1400 1000 m)
#
# Each resolution runs in WORK_DIR/h<H> (default BUILD_DIR/bench-fault-convergence); a finished one
# (faulted.h5 newer than its inputs) is not rerun. FAULT_OPTS picks the saddle-point solver
# (default `--fault-solver mumps`: on these flat layered meshes the field split took 222 FGMRES
# iterations per Newton iteration at FAULT_H = 1500, 133 s for the 1964 step).
# Prints a Markdown table; exit 1 when a run fails or the two finest differ by 0.05 or more.
set -eu
B=$(cd "${1:?usage: run.sh BUILD_DIR [WORK_DIR] [H1 H2 H3]}" && pwd)
W=${2:-$B/bench-fault-convergence}
shift $(( $# < 2 ? $# : 2 ))
[ $# -ge 3 ] && HS="$1 $2 $3" || HS="2000 1400 1000"
HERE=$(cd "$(dirname "$0")" && pwd)
SAMPLE=$HERE/../../data-samples/po-plain
FAULT_OPTS=${FAULT_OPTS:---fault-solver mumps}
mkdir -p "$W"
W=$(cd "$W" && pwd)

for h in $HS; do
  out=$W/h$h
  mkdir -p "$out"
  t0=$(date +%s)
  make -s -C "$SAMPLE" faults UGS_BIN="$B/tools" OUT="$out" SCALE=demo FAULT_H="$h" FAULT_OPTS="$FAULT_OPTS" \
    > "$out/make.log" 2>&1 || { tail -5 "$out/make.log"; echo "FAIL: the faulted run at FAULT_H=$h failed"; exit 1; }
  t1=$(date +%s)
  [ -f "$out/seconds" ] && [ "$out/seconds" -nt "$out/faulted.h5" ] || echo $(( t1 - t0 )) > "$out/seconds"
done

# max chi per fault over the fault dates (node pairs on free degrees of freedom: the CSV's statistics)
/usr/bin/python3 - "$W" $HS <<'EOF'
import csv, os, re, sys
work, hs = sys.argv[1], sys.argv[2:]
rows, info = {}, {}
for h in hs:
    d = os.path.join(work, "h" + h)
    with open(os.path.join(d, "faulted_faults.csv"), newline="") as fh:
        lines = [l for l in fh if not l.startswith("#")]
    best = {}
    for r in csv.DictReader(lines):
        if r["date"] == "1950-01-01":
            continue
        f, chi = r["fault"], float(r["max_chi"])
        if f not in best or chi > best[f][0]:
            best[f] = (chi, r["date"], float(r["z_m"]), int(r["slipping"]), int(r["open"]))
    rows[h] = best
    log = open(os.path.join(d, "faulted.log")).read()
    m = re.search(r"mesh: (\d+) nodes, (\d+) tetrahedra, (\d+) interface elements", log)
    s = re.search(r"maximum safe scale ([0-9.]+)", log)
    top = re.search(r"reaches chi = 1 up to scale ([0-9.]+)", log)
    info[h] = (m.groups() if m else ("?", "?", "?"), s.group(1) if s else
               ("none" if "no scale of the later swing" in log else ("> " + top.group(1) if top else "?")),
               open(os.path.join(d, "seconds")).read().strip())
faults = list(rows[hs[0]])
print("| FAULT_H (m) | nodes | tetrahedra | interface elements | " + " | ".join(faults) + " | safe scale | wall (s) |")
print("|---" * (6 + len(faults)) + "|")
for h in hs:
    (n, t, ie), safe, sec = info[h]
    cells = []
    for f in faults:
        chi, date, z, sl, op = rows[h][f]
        cells.append(f"{chi:.3f} ({date}, z {z:.0f}{', %d slip' % sl if sl else ''}{', %d open' % op if op else ''})")
    print(f"| {h} | {int(n):,} | {int(t):,} | {int(ie):,} | " + " | ".join(cells) + f" | {safe} | {sec} |")
a, b = rows[hs[-2]], rows[hs[-1]]
worst = max(abs(a[f][0] - b[f][0]) for f in faults)
print()
print("change of max chi between FAULT_H = %s and %s m: " % (hs[-2], hs[-1])
      + ", ".join(f"{f} {abs(a[f][0] - b[f][0]):.3f}" for f in faults) + f"; largest {worst:.3f} (target < 0.05)")
sys.exit(0 if worst < 0.05 else 1)
EOF
