#!/bin/bash
# Hypo-plastic history on the po-plain demo mesh (docs/mechanics.md, "Speed of the hypo-plastic
# history"): the first five monthly steps, per-step times, Newton / CG iterations and PETSc's
# -log_view (events UgsResidual, UgsAssembly, UgsPredictor). `-ugs_newton_monitor` (after --) prints every Newton
# iteration (residual, linear tolerance, branch changes).
#   bench/solve/history.sh BUILD_DIR DEMO_DIR [NPROC] [UNTIL]
# DEMO_DIR holds model.msh, pool_a_dp.h5, pool_c_dp.h5 (the lead's demo pipeline, build/demo).
set -euo pipefail
build=${1:?build dir}; demo=${2:?demo dir}; np=${3:-1}; until=${4:-1950-06-01}
src=$(cd "$(dirname "$0")/../.." && pwd)
out=$(mktemp -d)
export OMP_NUM_THREADS=1 OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
cmd=("$build/tools/ugs-solve/ugs-solve" "$demo/model.msh" --case "$src/data-samples/po-plain/case.toml"
     --pressure "$demo/pool_a_dp.h5" --pressure "$demo/pool_c_dp.h5" -o "$out/x.h5" --until "$until" -vv -- -log_view)
if [ "$np" -gt 1 ]; then mpirun -n "$np" "${cmd[@]}"; else "${cmd[@]}"; fi 2>&1 |
  grep -E "step [0-9]+/|steps:|time:|^(UgsResidual|UgsAssembly|UgsPredictor|PCSetUp|PCApply|KSPSolve|MatMult) "
rm -rf "$out"
