#!/bin/sh
# Writing checkpoints and resuming leave the arithmetic untouched (docs/DESIGN.md §10): a chaotic
# DEM run of 1000 MPM steps, where any round-off difference grows to percents, must end
# bit-identical (history.csv, every dataset of results.h5)
#   - with a checkpoint every 37 steps, to the same run without checkpoints;
#   - stopped by SIGTERM in step 300 (a checkpoint written there) and resumed, here on NP ranks
#     (the stop and the resume need no timing: the run signals itself, MPM_LIG_TERM_AT_STEP).
# usage: checkpoint_identity.sh MPM_LIG CASE.json WORK_DIR ENGINE NP [LAUNCHER ...]
set -e
exe=$1 case=$2 work=$3 engine=$4 np=$5
shift 5
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
write_case() {  # write_case FILE CHECKPOINT_EVERY
  /usr/bin/python3 - "$case" "$1" "$engine" "$2" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 1000}
output = c.setdefault("output", {})
output["every"] = 250
if int(sys.argv[4]):
    output["checkpoint_every"] = int(sys.argv[4])
for m in c["materials"]:
    m["rve"]["engine"] = sys.argv[3]
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
}
write_case "$work/plain.json" 0
write_case "$work/checkpointed.json" 37
"$exe" "$work/plain.json" --output "$work/plain" > "$work/plain.log" 2>&1 ||
  { echo "uninterrupted run failed:"; tail -5 "$work/plain.log"; exit 1; }
"$exe" "$work/checkpointed.json" --output "$work/checkpointed" > "$work/checkpointed.log" 2>&1 ||
  { echo "checkpointed run failed:"; tail -5 "$work/checkpointed.log"; exit 1; }
status=0
MPM_LIG_TERM_AT_STEP=300 "$exe" "$work/plain.json" --output "$work/resumed" \
  > "$work/stopped.log" 2>&1 || status=$?
grep -q "stopped by a signal after step 300" "$work/stopped.log" && [ $status -eq 4 ] ||
  { echo "the run did not stop at step 300 with exit 4 (exit $status):"; tail -5 "$work/stopped.log"
    exit 1; }
"$@" "$exe" "$work/plain.json" --resume "$work/resumed" > "$work/resumed.log" 2>&1 ||
  { echo "resume on $np rank(s) failed:"; tail -5 "$work/resumed.log"; exit 1; }
echo "checkpoint every 37 steps vs none:"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/plain" "$work/checkpointed"
echo "stopped at step 300 and resumed on $np rank(s) vs uninterrupted:"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/plain" "$work/resumed"
