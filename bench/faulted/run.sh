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
set -eu
B=$(cd "${1:?usage: run.sh BUILD_DIR [WORK_DIR] [NPROC]}" && pwd)  # absolute: the runs cd into WORK_DIR
W=${2:-$B/bench-faulted}
NP=${3:-2}
shift $(( $# < 3 ? $# : 3 ))
[ "${1:-}" = "--" ] && shift
TOOL=$B/tools/ugs-solve/ugs-solve
GEN=$B/bench/make_faulted_bench
mkdir -p "$W"
[ -f "$W/faulted.msh" ] && [ -f "$W/plain.msh" ] && [ -f "$W/flow.h5" ] || "$GEN" "$W"

MPI="mpirun --allow-run-as-root --oversubscribe -n $NP"
now() { date +%s.%N; }
cd "$W"

t0=$(now)
$MPI "$TOOL" faulted.msh --case case.toml --pressure flow.h5 -o faulted.h5 --top none -vv "$@" 2>faulted.log || {
  tail -5 faulted.log; echo "FAIL: the faulted run failed"; exit 1; }
t1=$(now)
$MPI "$TOOL" plain.msh --case case_plain.toml --pressure flow_plain.h5 -o plain.h5 --top none -vv "$@" 2>plain.log || {
  tail -5 plain.log; echo "FAIL: the continuous run failed"; exit 1; }
t2=$(now)

grep -E "interface elements|node pairs|faults:" faulted.log | sed 's/^ugs-solve: //' | head -12
echo "per step (faulted): Newton iterations, linear iterations (saddle point), contact state changes, seconds, fault state"
grep -E "^ugs-solve: step [0-9]+/[0-9]+ \(" faulted.log | sed 's/^ugs-solve: /  /'
echo "per step (continuous peer):"
grep -E "^ugs-solve: step [0-9]+/[0-9]+ \(" plain.log | sed 's/^ugs-solve: /  /'
grep -E "Newton iterations, .* linear iterations|saddle-point solves" faulted.log | sed 's/^ugs-solve: /faulted: /'
tail -n +2 faulted_faults.csv | grep -v '^#' | awk -F, '$1 == "2015-11-01"' | sed 's/^/  /'
awk -v a="$t0" -v b="$t1" -v c="$t2" -v np="$NP" 'BEGIN {
  f = b - a; p = c - b
  printf "faulted ugs-solve, %d processes:      %.1f s (target < 600 s)\n", np, f
  printf "peer: continuous ugs-solve, same mesh: %.1f s\n", p
  printf "ratio faulted / continuous: %.2f\n", f / p
  printf "metric: ugs-solve.faulted.wall %.1f s\nmetric: ugs-solve.continuous.wall %.1f s\n", f, p
  printf "metric: faulted.ratio_to_continuous %.2f 1\n", f / p
  exit !(f < 600) }' || { echo "FAIL: over 10 minutes"; exit 1; }
