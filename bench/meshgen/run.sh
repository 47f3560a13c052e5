#!/usr/bin/env bash
# Benchmark of ugs-mesh2d and ugs-meshgen at thesis scale (issue 4), with the peer measured in the
# same run: the gmsh 4.8 SDK extruding the same plan into 41 flat layers of tetrahedra.
#
#   bench/meshgen/run.sh [BUILD_DIR]        (default BUILD_DIR: build)
#
# 1. The thesis-scale plan: ugs-mesh2d on the po-plain sample (42 x 30 km, 50 m in the reservoir
#    refinement, 2,000 m far field; about 13,500 nodes). The sample is data-samples/po-plain when it
#    has been generated there, else it is generated into the scratch folder.
# 2. ugs-meshgen: that plan, 11 raster surfaces + the model bottom, 41 sub-layers, 7 materials,
#    6 vertical faults: about 530,000 nodes and 3.1 million tetrahedra, written to a file.
# 3. The peer: bench/meshgen/gmsh_extrude.cpp (compiled here against libgmsh) on the same plan.
# Wall time, CPU time and peak RSS come from /usr/bin/time -v; ugs-mesh2d and ugs-meshgen are run
# three times and the fastest run is kept (the peer, ~30-100 s, once). Targets: meshgen < 3 s,
# < 1.5 GB, >= 10x faster than the peer; mesh2d < 5 s.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build}" && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/ugs-bench-meshgen.XXXXXX")
trap 'rm -rf "$work"' EXIT

for t in ugs-mesh2d ugs-meshgen; do
  [[ -x $build/tools/$t/$t ]] || { echo "run.sh: error: $build/tools/$t/$t not built" >&2; exit 2; }
done
[[ -x /usr/bin/time ]] || { echo "run.sh: error: /usr/bin/time missing (apt-get install time)" >&2; exit 2; }

sample=$root/data-samples/po-plain
if [[ ! -f $sample/strata.toml || ! -f $sample/surfaces/01_dem.tif ]]; then
  echo "run.sh: generating the full po-plain twin into $work/po-plain" >&2
  /usr/bin/python3 "$sample/generate.py" --out "$work/po-plain" -q
  sample=$work/po-plain
fi
# Depth ranges of the faults from faults.geojson, added when the sample's strata.toml lacks them
# (in a linked copy of the sample, so nothing is written into the source tree).
strata=$sample/strata.toml
if ! grep -q '^faults *=' "$strata"; then
  mkdir -p "$work/sample"
  cp -as "$sample/." "$work/sample/"
  rm "$work/sample/strata.toml"
  { echo 'faults = "faults.geojson"'; cat "$sample/strata.toml"; } > "$work/sample/strata.toml"
  sample=$work/sample
  strata=$sample/strata.toml
fi

measure() {  # name, command...: runs it under /usr/bin/time -v, prints "wall cpu rss_MB"
  local name=$1; shift
  /usr/bin/time -v -o "$work/$name.time" "$@" > "$work/$name.out" 2> "$work/$name.err" || {
    echo "run.sh: error: $name failed:" >&2; cat "$work/$name.err" >&2; exit 1; }
  awk -F': ' '/Elapsed \(wall clock\)/ { n = split($2, p, ":"); w = 0; for (i = 1; i <= n; ++i) w = w * 60 + p[i] }
              /User time/ { u = $2 } /System time/ { s = $2 } /Maximum resident/ { r = $2 }
              END { printf "%.2f %.2f %.0f\n", w, u + s, r / 1024 }' "$work/$name.time"
}
best_of_3() {  # name, command...: the run with the smallest wall time
  local name=$1; shift
  for i in 1 2 3; do measure "$name" "$@"; done | sort -n -k1,1 | head -1
}

echo "== ugs-mesh2d: thesis-scale plan" >&2
read -r m2_wall m2_cpu m2_rss < <(best_of_3 mesh2d "$build/tools/ugs-mesh2d/ugs-mesh2d" \
  --domain "$sample/domain.geojson" --refine "$sample/refinement.geojson" --trace "$sample/reservoir_traces.geojson" \
  --fault "$sample/faults.geojson" --section "$sample/sections.geojson" -o "$work/plan.msh")
grep -h "plan:" "$work/mesh2d.err" >&2

echo "== ugs-meshgen: 41 sub-layers, 11 raster surfaces" >&2
read -r mg_wall mg_cpu mg_rss < <(best_of_3 meshgen "$build/tools/ugs-meshgen/ugs-meshgen" "$work/plan.msh" \
  --strata "$strata" -o "$work/model.msh")
cat "$work/meshgen.err" >&2

echo "== peer: gmsh $(gmsh -version 2>&1 | tail -1) SDK extrusion into 41 flat layers" >&2
g++ -O2 -o "$work/gmsh_extrude" "$here/gmsh_extrude.cpp" -lgmsh
read -r gm_wall gm_cpu gm_rss < <(measure gmsh "$work/gmsh_extrude" "$work/plan.msh" 41 -10050 "$work/peer.msh")
cat "$work/gmsh.out" >&2

echo
echo "| step | wall s | CPU s | peak RSS MB | output |"
echo "|---|---|---|---|---|"
echo "| ugs-mesh2d (plan) | $m2_wall | $m2_cpu | $m2_rss | $(grep -ho '[0-9]* nodes, [0-9]* triangles' "$work/mesh2d.err") |"
echo "| ugs-meshgen | $mg_wall | $mg_cpu | $mg_rss | $(grep -h 'nodes .*, tetrahedra' "$work/meshgen.err" | sed 's/ugs-meshgen: //') |"
echo "| gmsh SDK extrusion (peer) | $gm_wall | $gm_cpu | $gm_rss | $(sed 's/gmsh_extrude: //' "$work/gmsh.out") |"
echo
awk -v a="$gm_wall" -v b="$mg_wall" -v c="$gm_cpu" -v d="$mg_cpu" \
  'BEGIN { printf "ugs-meshgen vs gmsh: %.1fx faster (wall), %.1fx (CPU)\n", a / b, c / d }'
echo "load average: $(cut -d' ' -f1-3 /proc/loadavg) on $(nproc) cores"
# Key metrics for bench/run-all (RESULTS.md, history.csv).
for m in "ugs-mesh2d $m2_wall $m2_cpu $m2_rss" "ugs-meshgen $mg_wall $mg_cpu $mg_rss" "gmsh-extrusion $gm_wall $gm_cpu $gm_rss"; do
  read -r tool w c r <<< "$m"
  printf 'metric: %s.wall %s s\nmetric: %s.cpu %s s\nmetric: %s.rss %s MB\n' "$tool" "$w" "$tool" "$c" "$tool" "$r"
done
awk -v a="$gm_wall" -v b="$mg_wall" 'BEGIN { printf "metric: meshgen.speedup_wall %.2f 1\n", a / b }'
