#!/bin/bash
# RVEs spread over two ranks each (ranks_per_rve 2): a run killed after its step-4 checkpoint
# resumes bit-identical to an uninterrupted run, on as many ranks (one group of two) and on
# twice as many (two groups: the bundles are read by other groups than wrote them), and an
# uninterrupted run on two groups is bit-identical to the one on one group.
# usage: group_resume.sh MPM_LIG CASE.json WORK_DIR MPIRUN...
set -u
exe=$1 case=$2 work=$3
shift 3
here=$(dirname "$0")
. "$here/checkpoint_scenarios.sh"
rm -rf "$work" && mkdir -p "$work"
short_case "$case" "$work/case.json" 2
"$@" -np 2 "$exe" "$work/case.json" --output "$work/reference" > "$work/reference.log" 2>&1 ||
  { cat "$work/reference.log"; exit 1; }
scenario="two groups, uninterrupted"
"$@" -np 4 "$exe" "$work/case.json" --output "$work/four" > "$work/four.log" 2>&1 ||
  fail "run failed: $(tail -c 400 "$work/four.log")"
$compare "$work/reference" "$work/four" > "$work/compare.log" 2>&1 || fail "$(cat "$work/compare.log")"
if MPM_LIG_KILL_AT_STEP=5 "$@" -np 2 "$exe" "$work/case.json" --output "$work/killed" \
    > "$work/killed.log" 2>&1; then
  echo "the run was expected to be killed at step 5"; exit 1
fi
[ "$(cat "$work/killed/checkpoints/latest")" = step_4 ] || { echo "no step-4 checkpoint"; exit 1; }
for np in 2 4; do
  scenario="written on 2, resumed on $np"
  resume_matches "$work/killed" $np "$@"
done
echo "group scenarios: $failures failures"
[ $failures -eq 0 ]
