#!/usr/bin/env bash
# ugs-flow benchmark (issue 7): Pool C's flow mesh at the thesis' scale, 1950-2033 monthly (1,007
# steps, the fields of every date written to HDF5). Target: under 60 s on this machine. Peer: the
# same scheme in SciPy (SuperLU, bench/flow/peer_scipy.py), run on the same mesh in the same run.
#
#   bench/flow/run.sh [BUILD_DIR] [WORK_DIR]          (SKIP_PEER=1 skips the peer, SKIP_BOX=1 the box case,
#                                                     REAL_MODEL=model.msh uses that thesis-scale mesh)
#
# Cases:
#  1. real: the po-plain sample's thesis-scale mesh (ugs-mesh2d + ugs-meshgen, as bench/meshgen does),
#     cut by ugs-submesh to pool_c + aquifer_pool_c, with the sample's case.toml and
#     pressure_pool_c.csv. Skipped when the mesh tools are not built.
#  2. box: a structured mesh of the Pool C flow layers at the size the issue names (114 x 114 plan
#     nodes x (8 + 2) layers = 142,956 nodes; make_bench_case), all but the pool being aquifer: the
#     stress case (2.7x the free unknowns of case 1).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build}
work=${2:-/tmp/ugs-bench-flow}
sample=$root/data-samples/po-plain
mkdir -p "$work"
cmake --build "$build" --target ugs-flow ugs-submesh flow_bench_case >/dev/null
have_meshgen=0
cmake --build "$build" --target ugs-mesh2d ugs-meshgen >/dev/null 2>&1 && have_meshgen=1

echo "machine: $(nproc) cores, load $(cut -d' ' -f1-3 /proc/loadavg), BLAS $(readlink -f /usr/lib/x86_64-linux-gnu/libblas.so.3)"
timed() {  # label, command...: prints the tool's summary lines, "label: wall, user, sys, RSS" and its metric lines
  local label=$1; shift
  local rc=0
  /usr/bin/time -f "$label: wall %e s, user %U s, sys %S s, max RSS %M kB" "$@" 2>&1 | grep -v " flow [0-9]*/" | tee "$work/timed.out" || rc=$?
  # "ugs-flow (real, one output date)" -> metric names ugs-flow.real_one_output_date.wall etc.
  local key
  key=$(sed -E 's/ \((.*)\)$/.\1/; s/[^A-Za-z0-9.-]+/_/g' <<< "$label")
  sed -nE "s/^.*: wall ([0-9.]+) s, user ([0-9.]+) s, sys ([0-9.]+) s, max RSS ([0-9]+) kB\$/\1 \2 \3 \4/p" "$work/timed.out" | tail -1 |
    awk -v k="$key" '{ printf "metric: %s.wall %s s\nmetric: %s.cpu %.2f s\nmetric: %s.rss %.0f MB\n", k, $1, k, $2 + $3, k, $4 / 1024 }'
  return $rc
}

if [[ $have_meshgen == 1 ]]; then
  echo "== real: po-plain thesis-scale mesh, Pool C sub-mesh"
  real=$work/real
  mkdir -p "$real"
  cp "$sample/case.toml" "$sample/pressure_pool_a.csv" "$sample/pressure_pool_c.csv" "$real/"
  [[ -n ${REAL_MODEL:-} ]] && cp "$REAL_MODEL" "$real/model.msh"
  [[ -f $real/model.msh ]] || {
    "$build/tools/ugs-mesh2d/ugs-mesh2d" --domain "$sample/domain.geojson" --refine "$sample/refinement.geojson" \
      --trace "$sample/reservoir_traces.geojson" --fault "$sample/faults.geojson" --section "$sample/sections.geojson" \
      -o "$real/plan.msh" -q
    "$build/tools/ugs-meshgen/ugs-meshgen" "$real/plan.msh" --strata "$sample/strata.toml" -o "$real/model.msh" -q
  }
  timed "ugs-submesh" "$build/tools/ugs-submesh/ugs-submesh" "$real/model.msh" --materials pool_c,aquifer_pool_c \
    -o "$real/pool_c.msh"
  rm -f "$real"/dp.* "$real"/one.*
  timed "ugs-flow (real)" "$build/tools/ugs-flow/ugs-flow" "$real/pool_c.msh" --case "$real/case.toml" -o "$real/dp.h5" -v \
    || echo "ugs-flow (real) failed"
  # The same computation with fields at one date only: what the peer does (it writes no fields).
  timed "ugs-flow (real, one output date)" "$build/tools/ugs-flow/ugs-flow" "$real/pool_c.msh" --case "$real/case.toml" \
    -o "$real/one.h5" --output-dates 1964-01-01 -v || true
  if [[ ${SKIP_PEER:-0} != 1 ]]; then
    "$build/bench/flow_bench_case" --raw "$real/pool_c.msh" pool_c "$real"
    timed "peer scipy (real)" /usr/bin/python3 "$here/peer_scipy.py" "$real"
  fi
fi

if [[ ${SKIP_BOX:-0} != 1 ]]; then
  echo "== box: 114 x 114 x 11 nodes"
  box=$work/box
  "$build/bench/flow_bench_case" "$box" 114 "$sample/pressure_pool_c.csv"
  cp "$sample/pressure_pool_c.csv" "$box/"
  rm -f "$box"/dp.*
  timed "ugs-flow (box)" "$build/tools/ugs-flow/ugs-flow" "$box/mesh.msh" --case "$box/case.toml" -o "$box/dp.h5" -v
  [[ ${SKIP_PEER:-0} == 1 ]] || timed "peer scipy (box)" /usr/bin/python3 "$here/peer_scipy.py" "$box"
fi
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
