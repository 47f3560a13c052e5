#!/usr/bin/env bash
# Import speed of ugs-import-eclipse (issue 22): a 1-million-cell restart with 100 report steps after
# the first onto a 3-million-tetrahedron mesh, target under a minute on 2 cores.
#
#   bench/import-eclipse/run.sh [BUILD_DIR]     (default BUILD_DIR: build)
#   BENCH_ECLIPSE_SIZE="NX NY NZ STEPS HX HY HZ" overrides the case (default 100 100 100 100 80 80 78)
#
# The case comes from bench/import-eclipse/make_bench_case.cpp: a 100 x 100 x 100 corner-point grid
# (980,000 active cells), a restart written in the ECLIPSE binary format, and a box of 80 x 80 x 78
# hexahedra split into 2,995,200 tetrahedra half inside the grid. No other tool maps simulator
# pressures onto a tetrahedral mesh (ResInsight reads the files but computes no mapping), so the
# reference measured in the same run is the floor every importer pays: opm-common's EclIO reading the
# restart's PRESSURE arrays (the tool times that part itself). Wall, CPU and peak RSS from
# /usr/bin/time; the tool's -v line splits the time into reading, locating and the steps.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
tool=$build/tools/ugs-import-eclipse/ugs-import-eclipse
gen=$build/bench/eclipse_make_bench_case
for f in "$tool" "$gen"; do
  [[ -x $f ]] || { echo "run.sh: error: $f not built" >&2; exit 2; }
done
[[ -x /usr/bin/time ]] || { echo "run.sh: error: /usr/bin/time missing (apt-get install time)" >&2; exit 2; }
read -r -a size <<< "${BENCH_ECLIPSE_SIZE:-100 100 100 100 80 80 78}"
work=$(mktemp -d "${TMPDIR:-/tmp}/ugs-bench-eclipse.XXXXXX")
trap 'rm -rf "$work"' EXIT

"$gen" "$work" "${size[@]}" > "$work/gen.out"
load=$(cut -d' ' -f1 /proc/loadavg)
/usr/bin/time -f "%e %U %S %M" -o "$work/time" "$tool" -v "$work/BENCH.EGRID" --mesh "$work/mesh.msh" \
  -o "$work/dp.h5" 2> "$work/import.err" || { cat "$work/import.err" >&2; exit 1; }
read -r wall user sys rss < "$work/time"
timing=$(grep 'timing:' "$work/import.err" | sed 's/.*timing: //')
cells=$(grep -o '[0-9]* active,' "$work/import.err" | head -1 | cut -d' ' -f1)
tets=$(grep -o '[0-9]* tetrahedra' "$work/gen.out" | head -1 | cut -d' ' -f1)
steps=$(grep -o '[0-9]* report steps' "$work/import.err" | head -1 | cut -d' ' -f1)
read_per_step=$(sed -n 's/.*reading PRESSURE \([0-9.]*\) s.*/\1/p' <<< "$timing")
per_step=$(sed -n 's/.*(\([0-9.]*\) s per step.*/\1/p' <<< "$timing")
echo "| case | wall | CPU (user + sys) | peak RSS | target |"
echo "|---|---|---|---|---|"
printf '| %s active cells, %s report steps, %s tetrahedra | %.1f s | %.1f s | %.0f MB | < 60 s wall |\n' \
  "$cells" "$steps" "$tets" "$wall" "$(awk "BEGIN{print $user + $sys}")" "$(awk "BEGIN{print $rss / 1024}")"
echo
echo "Split (the tool's -v line): $timing."
echo "Per step: $per_step s, of which EclIO reading PRESSURE (the floor any importer pays) $read_per_step s."
echo "Load average when it started: $load (the CPU time is what an idle machine's wall time approaches)."
awk -v w="$wall" -v u="$user" -v s="$sys" -v r="$rss" -v p="$per_step" 'BEGIN {
  printf "metric: ugs-import-eclipse.wall %.2f s\nmetric: ugs-import-eclipse.cpu %.2f s\n", w, u + s
  printf "metric: ugs-import-eclipse.rss %.0f MB\n", r / 1024
  if (p != "") printf "metric: ugs-import-eclipse.per_step %s s\n", p }'
