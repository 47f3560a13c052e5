#!/bin/bash
# The thesis' study at the thesis' scale (issue 43, docs/end-to-end.md "Thesis scale"): `make demo
# SCALE=full` from a clean output folder, every stage timed (wall, CPU, peak RSS of its largest
# process), then, in the same run, one linear elastic solve of the same mesh (the elastic law in
# every unit, one production month): the ratio study / linear solve is what carries over to
# other machines (target: at most 150; the study at most 60 min and 16 GB on 2 cores).
#   bench/study/run.sh BUILD_DIR [OUT]      (OUT default BUILD_DIR/study; it is emptied first)
# Environment: JOBS (default 2), NPROC (default 1) as for make demo; SCALE (default full; tiny checks
# this script in minutes).
set -euo pipefail
build=$(cd "${1:?build dir}" && pwd); out=${2:-$build/study}
here=$(cd "$(dirname "$0")" && pwd); src=$(cd "$here/../.." && pwd); po=$src/data-samples/po-plain
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
rm -rf "$out"; mkdir -p "$out"
export STUDY_TIMES=$out/times.tsv
: > "$STUDY_TIMES"
echo "machine: $(nproc --all) cores, $(awk '/MemTotal/ {printf "%.0f GiB", $2 / 1048576}' /proc/meminfo), load $(cut -d' ' -f1-3 /proc/loadavg)"
# Memory of the whole study: the sum over its processes, sampled every 2 s.
( peak=0; while sleep 2; do
    s=$(ps -e -o rss=,comm= | awk '$2 ~ /^ugs-/ {t += $1} END {print t + 0}')
    (( s > peak )) && peak=$s && echo "$peak" > "$out/rss_peak_kB"
  done ) &
sampler=$!
trap 'kill $sampler 2>/dev/null || true' EXIT
t0=$(date +%s.%N)
make -C "$po" demo SCALE="${SCALE:-full}" OUT="$out" UGS_BIN="$build/tools" JOBS="${JOBS:-2}" NPROC="${NPROC:-1}" -j "${JOBS:-2}" \
  SHELL="$here/timed-shell" > "$out/make.log" 2>&1 || { tail -20 "$out/make.log"; exit 1; }
t1=$(date +%s.%N)
kill $sampler 2>/dev/null || true
study=$(echo "$t1 - $t0" | bc)

# One linear elastic solve of the same mesh: every unit elastic, Pool C's production to its lowest
# pressure in one step (monotonic: the turning points are the first and the last date).
lin=$out/linear; mkdir -p "$lin"
sed -e 's/^law = "hypoplastic"/law = "elastic"/' -e "s|^schedule = \"|schedule = \"$po/|" "$po/case.toml" > "$lin/case.toml"
/usr/bin/time -o "$lin/time" -f "%e %M" "$build/tools/ugs-solve/ugs-solve" "$out/model.msh" --case "$lin/case.toml" \
  --pressure "$out/pool_a_dp.h5" --pressure "$out/pool_c_dp.h5" --until 1964-04-01 --steps turning-points -o "$lin/linear.h5" --top none --state none -v \
  2> "$lin/solve.log"
read -r lin_wall lin_rss < "$lin/time"

/usr/bin/python3 "$here/summarize.py" "$STUDY_TIMES" --study-wall "$study" --rss-peak-kB "$(cat "$out/rss_peak_kB" 2>/dev/null || echo 0)" \
  --linear-wall "$lin_wall" --linear-rss-kB "$lin_rss" --linear-log "$lin/solve.log" --out "$out" --scale "${SCALE:-full}"
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)"
