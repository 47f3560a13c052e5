#!/usr/bin/env bash
# Import speed of ugs-import-eclipse on a synthetic case (tests/eclipse/make_bench_case.cpp):
#   tests/eclipse/bench_import.sh [BUILD_DIR] [NX NY NZ STEPS HX HY HZ]
# Default: the issue's target, 100 x 100 x 100 cells (980,000 active), 100 report steps after the
# first, 80 x 80 x 78 hexahedra = 2,995,200 tetrahedra. Prints the tool's timing line (-v): reading,
# locating the points, and the time per step.
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
shift || true
args=("${@:-100 100 100 100 80 80 78}")
work=$(mktemp -d "${TMPDIR:-/tmp}/ugs-bench-eclipse.XXXXXX")
trap 'rm -rf "$work"' EXIT
"$build/tests/eclipse/eclipse_make_bench_case" "$work" ${args[*]}
/usr/bin/time -f "wall %e s, cpu %U+%S s, peak %M KB" "$build/tools/ugs-import-eclipse/ugs-import-eclipse" -v "$work/BENCH.EGRID" \
  --mesh "$work/mesh.msh" -o "$work/dp.h5"
ls -la "$work/BENCH.UNRST" "$work/dp.h5" | awk '{print $5, $9}'
