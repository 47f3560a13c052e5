#!/usr/bin/env bash
# bench/run-all's bookkeeping with two fake benchmarks in a temporary bench folder (BENCH_DIR):
# RESULTS.md gets one section per benchmark with its metrics, date and commit; history.csv one row per
# metric per run; BENCH_ONLY reruns one section and keeps the other byte for byte; a failed benchmark
# is recorded as failed with its metrics; a BENCH_ONLY naming nothing is bad input (exit 2).
#   test_run_all.sh SOURCE_DIR BUILD_DIR
set -uo pipefail
src=${1:?source dir}; build=${2:?build dir}
work=$(mktemp -d "${TMPDIR:-/tmp}/ugs-test-run-all.XXXXXX")
trap 'rm -rf "$work"' EXIT
fails=0 passes=0
check() {  # description, command...
  if "${@:2}"; then echo "ok: $1"; passes=$((passes + 1)); else echo "FAIL: $1"; fails=$((fails + 1)); fi
}
# The settings run-all records come from the environment: start from none.
for v in $(compgen -e | grep -E '^(BENCH_[A-Z_]+|SCALE|SKIP_[A-Z_]+|EVERY_DATE|HISTORY_[A-Z_]+|TURNING_TOLERANCE|FAULT_[A-Z_]+|NO_SCALE|CORNER_M|REAL_MODEL)$'); do
  unset "$v"
done
section() { sed -n "/^<!-- bench: $1 -->\$/,/^<!-- end bench: $1 -->\$/p" "$work/RESULTS.md"; }

mkdir -p "$work/benches/alpha" "$work/benches/beta"
cat > "$work/benches/alpha/run.sh" <<'SH'
echo "| step | wall s |"
echo "|---|---|"
echo "| alpha | 1.25 |"
echo "metric: alpha.wall 1.25 s"
echo "metric: alpha.rss 364 MB"
SH
cat > "$work/benches/beta/run.sh" <<'SH'
echo "beta: speed-up ${BENCH_BETA:-2.0}"
echo "metric: beta.speedup ${BENCH_BETA:-2.0} 1"
exit ${BETA_EXIT:-0}
SH
commit=$(git -C "$src" rev-parse --short=12 HEAD 2>/dev/null || echo unknown)
run_all() { BENCH_DIR="$work/benches" "$src/bench/run-all" "$build" "$work/RESULTS.md" 2> "$work/stderr"; }

# 1. both benchmarks
run_all; rc=$?
check "first run exits 0" test "$rc" = 0
check "RESULTS.md has both sections in order" \
  test "$(grep -c '^<!-- bench: ' "$work/RESULTS.md")-$(grep -o '^## .*' "$work/RESULTS.md" | tr '\n' ' ')" = "2-## alpha ## beta "
check "alpha's metric table" grep -qx '| alpha.wall | 1.25 | s |' "$work/RESULTS.md"
check "alpha's rss metric" grep -qx '| alpha.rss | 364 | MB |' "$work/RESULTS.md"
check "alpha's own output kept, metric lines taken out" \
  test "$(section alpha | grep -c '^| alpha | 1.25 |$')-$(section alpha | grep -c '^metric:')" = "1-0"
check "the section names the commit $commit" grep -q "^ok, [0-9]* s; [0-9-]*T[0-9:]*Z; commit $commit" <(section beta)
check "history: header and 3 rows" test "$(wc -l < "$work/history.csv")" = 4
check "history header" test "$(head -1 "$work/history.csv")" = "date,commit,dirty,load,benchmark,status,metric,value,unit,settings"
check "history row of beta" grep -Eq "^[0-9-]+T[0-9:]+Z,$commit,(yes|no|unknown),[0-9.]+,beta,ok,beta.speedup,2.0,1,\$" "$work/history.csv"
alpha_before=$(section alpha)
head_before=$(head -4 "$work/history.csv")

# 2. beta alone, slower and failing: alpha kept as it was, beta replaced, one history row appended
sleep 1
BENCH_BETA=3.5 BETA_EXIT=1 BENCH_ONLY=beta run_all; rc=$?
check "a failed benchmark makes run-all exit 1" test "$rc" = 1
check "alpha's section kept byte for byte" test "$alpha_before" = "$(section alpha)"
check "beta's section replaced" test "$(section beta | grep -c '^| beta.speedup | 3.5 | 1 |$')-$(section beta | grep -cF '| 2.0 |')" = "1-0"
check "beta recorded as failed" grep -q '^failed (exit 1), ' <(section beta)
check "still two sections" test "$(grep -c '^<!-- bench: ' "$work/RESULTS.md")" = 2
check "history: old rows kept, one appended" test "$(head -4 "$work/history.csv")" = "$head_before" -a "$(wc -l < "$work/history.csv")" = 5
check "appended row: beta failed at 3.5, with its setting" grep -Eq ",beta,failed,beta.speedup,3.5,1,BENCH_BETA=3.5\$" <(tail -1 "$work/history.csv")
check "the section names its setting" grep -qx 'Settings: `BENCH_BETA=3.5`.' <(section beta)

# 3. a BENCH_ONLY that names no benchmark: exit 2, files untouched
cp "$work/RESULTS.md" "$work/before.md"
BENCH_ONLY=nonesuch run_all; rc=$?
check "BENCH_ONLY naming nothing exits 2 with one error line" \
  test "$rc-$(grep -c '^run-all: error: BENCH_ONLY="nonesuch" names no benchmark' "$work/stderr")" = "2-1"
check "RESULTS.md untouched" cmp -s "$work/before.md" "$work/RESULTS.md"
check "no temporary files left" test -z "$(find "$work" -name '*.tmp.*')"

echo "$passes passed, $fails failed"
exit $(( fails > 0 ))
