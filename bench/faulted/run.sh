#!/bin/sh
# ugs-solve with faults at the thesis' scale (chapter 4: 508,495 nodes, 26,598 interface elements)
# over one storage half-cycle (7 monthly steps, 2015-05-01 to 2015-11-01): target under 10 minutes
# on this 2-core machine. The peer is the continuous ugs-solve on the same mesh without faults,
# measured in the same run: the ratio says what the fault mechanics cost on top of it.
#
#   sh bench/faulted/run.sh BUILD_DIR [WORK_DIR] [NPROC] [-- PETSc options for both runs]
#
# The case (make_faulted_bench.cpp: 511,653 nodes, 2,878,848 tetrahedra, 26,496 interface elements
# in six crossing faults, a hypo-plastic pool and aquifer) is written once into WORK_DIR. Prints the
# Newton and linear iterations of every step, the fault statistics and both wall times.
#
# FAULTED_HISTORY=1: the whole history instead (make_faulted_bench --history: monthly 1950-01-01 ..
# 2034-01-01, 1,008 steps, production to 1964 then seasonal storage), target under 30 minutes.
# It runs in legs of HISTORY_LEG months (default 504: two legs, the restart exercised once; a restart
# costs ~80 s at the thesis scale, the preconditioner set up again and the saddle point's first
# iterates without their basis for two months), each one a --restart of the previous leg's state
# (WORK_DIR/history/leg_<end date>_state.h5): a rerun resumes after the last finished leg.
# HISTORY_MONTHS=N stops after N months and projects the 1,008 steps from the time per step
# (production months only while N <= 168: their virgin loading costs more Newton iterations than
# storage months). Prints metric: lines ugs-solve.faulted_history.* and the ratio of the time per step
# to the half-cycle's before the saddle-point predictor (30 s per monthly step, bench/RESULTS.md,
# 8dbfe9c: 305.8 s for 7 steps, steps 2-7 about 30 s each).
# HISTORY_STEPPING=turning-points steps on the pressure history's turning points instead of every
# month ([solver] steps = "turning-points", docs/mechanics.md): the per-month figures then count
# months of history, not steps.
# COARSEN=K (2 or 4) runs the coarsened case (make_faulted_bench --coarsen K) for a busy machine.
set -eu
B=$(cd "${1:?usage: run.sh BUILD_DIR [WORK_DIR] [NPROC]}" && pwd)  # absolute: the runs cd into WORK_DIR
W=${2:-$B/bench-faulted}
NP=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
[ "${1:-}" = "--" ] && shift
TOOL=$B/tools/ugs-solve/ugs-solve
GEN=$B/bench/make_faulted_bench
mkdir -p "$W"
GEN_ARGS=""
[ "${COARSEN:-1}" = 1 ] || GEN_ARGS="--coarsen $COARSEN"
if [ "${FAULTED_HISTORY:-0}" = 1 ]; then
  [ -f "$W/faulted.msh" ] && [ -f "$W/flow_history.h5" ] || "$GEN" "$W" $GEN_ARGS --history
else
  [ -f "$W/faulted.msh" ] && [ -f "$W/plain.msh" ] && [ -f "$W/flow.h5" ] || "$GEN" "$W" $GEN_ARGS
fi

MPI="mpirun --allow-run-as-root --oversubscribe -n $NP"
now() { date +%s.%N; }
cd "$W"

if [ "${FAULTED_HISTORY:-0}" = 1 ]; then
  TOTAL=1008
  MONTHS=${HISTORY_MONTHS:-$TOTAL}
  LEG=${HISTORY_LEG:-504}
  mkdir -p history
  CASE=case_history.toml
  if [ "${HISTORY_STEPPING:-monthly}" = turning-points ]; then
    CASE=case_history_tp.toml
    { cat case_history.toml; printf '\n[solver]\nsteps = "turning-points"\n'; } > "$CASE"
  fi
  done_m=0 state="" spent=0 steps=0
  # Resume: the legs already finished (state and wall time kept beside each; the same HISTORY_LEG).
  m=0
  while [ "$m" -lt "$MONTHS" ]; do
    m=$((m + LEG)); [ "$m" -gt "$MONTHS" ] && m=$MONTHS
    end=$(date -u -d "1950-01-01 + $m months" +%Y-%m-%d)
    [ -f "history/leg_$end.wall" ] && [ -f "history/leg_${end}_state.h5" ] || break
    done_m=$m state="history/leg_${end}_state.h5" spent=$(awk -v a="$spent" -v b="$(cat "history/leg_$end.wall")" 'BEGIN { print a + b }')
  done
  [ "$done_m" -gt 0 ] && echo "resuming after $done_m months ($state, $spent s spent)"
  while [ "$done_m" -lt "$MONTHS" ]; do
    m=$((done_m + LEG)); [ "$m" -gt "$MONTHS" ] && m=$MONTHS
    end=$(date -u -d "1950-01-01 + $m months" +%Y-%m-%d)
    restart=""; [ -n "$state" ] && restart="--restart $state"
    t0=$(now)
    # shellcheck disable=SC2086
    /usr/bin/time -f "%M" -o "history/leg_$end.rss" $MPI "$TOOL" faulted.msh --case "$CASE" --pressure flow_history.h5 -o "history/leg_$end.h5" --top none \
      --state "history/leg_${end}_state.h5" --until "$end" $restart -v "$@" 2>"history/leg_$end.log" || {
      tail -5 "history/leg_$end.log"; echo "FAIL: the faulted history failed in the leg to $end"; exit 1; }
    t=$(awk -v a="$t0" -v b="$(now)" 'BEGIN { printf "%.1f", b - a }')
    echo "$t" > "history/leg_$end.wall"
    spent=$(awk -v a="$spent" -v b="$t" 'BEGIN { print a + b }')
    echo "leg to $end ($((m - done_m)) months): $t s, largest process $(awk 'END { printf "%.0f MB", $1 / 1024 }' "history/leg_$end.rss"); $(grep -E '[0-9]+ steps: ' "history/leg_$end.log" | sed 's/^ugs-solve: //')"
    grep -E "max chi" "history/leg_$end.log" | tail -1 | sed 's/^ugs-solve: /  last step: /'
    done_m=$m state="history/leg_${end}_state.h5"
  done
  # Steps computed (the legs' "N steps:" lines; a restarted leg counts its own steps only).
  steps=$(cat history/leg_*.log | sed -n 's/^ugs-solve: \([0-9]*\) steps: .*/\1/p' | awk '{ n += $1 } END { print n + 0 }')
  awk -v s="$spent" -v n="$MONTHS" -v tot="$TOTAL" -v k="$steps" -v how="${HISTORY_STEPPING:-monthly}" 'BEGIN {
    per = s / n; proj = per * tot; ps = k > 0 ? s / k : 0
    printf "faulted history (%s): %d of %d months in %.1f s, %d steps, %.2f s per step, %.2f s per month; the whole history %s %.0f s (target < 1800 s)\n",
      how, n, tot, s, k, ps, per, n < tot ? "projected" : "took", proj
    printf "ratio of the time per step to a monthly step before the saddle-point predictor (30 s): %.3f\n", ps / 30
    printf "metric: ugs-solve.faulted_history.per_step %.2f s\n", ps
    printf "metric: ugs-solve.faulted_history.per_month %.2f s\n", per
    printf "metric: ugs-solve.faulted_history.%s %.0f s\n", n < tot ? "projected_wall" : "wall", proj
    printf "metric: ugs-solve.faulted_history.step_ratio_to_before %.3f 1\n", ps / 30
    exit !(proj < 1800) }' || { echo "FAIL: over 30 minutes"; exit 1; }
  exit 0
fi

# Peak memory: GNU time's maximum resident set over mpirun's process tree, i.e. the largest process.
t0=$(now)
/usr/bin/time -f "%M" -o faulted.rss $MPI "$TOOL" faulted.msh --case case.toml --pressure flow.h5 -o faulted.h5 --top none -vv "$@" 2>faulted.log || {
  tail -5 faulted.log; echo "FAIL: the faulted run failed"; exit 1; }
t1=$(now)
/usr/bin/time -f "%M" -o plain.rss $MPI "$TOOL" plain.msh --case case_plain.toml --pressure flow_plain.h5 -o plain.h5 --top none -vv "$@" 2>plain.log || {
  tail -5 plain.log; echo "FAIL: the continuous run failed"; exit 1; }
t2=$(now)

grep -E "interface elements|node pairs|faults:" faulted.log | sed 's/^ugs-solve: //' | head -12
echo "per step (faulted): Newton iterations, linear iterations (saddle point), contact state changes, seconds, fault state"
grep -E "^ugs-solve: step [0-9]+/[0-9]+ \(" faulted.log | sed 's/^ugs-solve: /  /'
echo "per step (continuous peer):"
grep -E "^ugs-solve: step [0-9]+/[0-9]+ \(" plain.log | sed 's/^ugs-solve: /  /'
grep -E "Newton iterations, .* linear iterations|saddle-point solves" faulted.log | sed 's/^ugs-solve: /faulted: /'
tail -n +2 faulted_faults.csv | grep -v '^#' | awk -F, '$1 == "2015-11-01"' | sed 's/^/  /'
awk -v a="$t0" -v b="$t1" -v c="$t2" -v np="$NP" -v fm="$(tail -1 faulted.rss)" -v pm="$(tail -1 plain.rss)" 'BEGIN {
  f = b - a; p = c - b
  printf "faulted ugs-solve, %d processes:      %.1f s (target < 600 s), largest process %.0f MB\n", np, f, fm / 1024
  printf "peer: continuous ugs-solve, same mesh: %.1f s, largest process %.0f MB\n", p, pm / 1024
  printf "ratio faulted / continuous: %.2f in time, %.2f in memory\n", f / p, fm / pm
  printf "metric: ugs-solve.faulted.wall %.1f s\nmetric: ugs-solve.continuous.wall %.1f s\n", f, p
  printf "metric: ugs-solve.faulted.rss_largest %.0f MB\nmetric: ugs-solve.continuous.rss_largest %.0f MB\n", fm / 1024, pm / 1024
  printf "metric: faulted.ratio_to_continuous %.2f 1\n", f / p
  printf "metric: faulted.memory_ratio_to_continuous %.2f 1\n", fm / pm
  exit !(f < 600) }' || { echo "FAIL: over 10 minutes"; exit 1; }
