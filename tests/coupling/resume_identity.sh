#!/bin/sh
# Resume identity: a run killed with SIGKILL after a checkpoint and resumed from it ends
# bit-identical (history.csv, results.h5) to an uninterrupted run of the same case.
# usage: [END_STEPS=n] resume_identity.sh MPM_LIG CASE.json WORK_DIR KILL_STEP MPIRUN...
# (checkpoints every 2 steps; END_STEPS replaces the case's end)
set -e
exe=$1 case=$2 work=$3 kill_step=$4
shift 4
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 - "$case" "$work/case.json" "${END_STEPS:-}" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c.setdefault("output", {})["checkpoint_every"] = 2
if sys.argv[3]:
    c["analysis"]["end"] = {"steps": int(sys.argv[3])}
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
"$@" "$exe" "$work/case.json" --output "$work/reference"
if MPM_LIG_KILL_AT_STEP=$kill_step "$@" "$exe" "$work/case.json" --output "$work/resumed" \
    > "$work/killed.log" 2>&1; then
  echo "the run was expected to be killed at step $kill_step"; exit 1
fi
echo "killed run: checkpoint $(cat "$work/resumed/checkpoints/latest"), \
$(($(wc -l < "$work/resumed/history.csv") - 1)) history rows"
"$@" "$exe" "$work/case.json" --resume "$work/resumed"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/reference" "$work/resumed"
# ParaView sees every output step of the resumed run, those before the checkpoint included.
steps() { grep -o '<Grid Name="step_[0-9]*"' "$1/results.xdmf" | sort; }
if [ "$(steps "$work/reference")" != "$(steps "$work/resumed")" ]; then
  echo "results.xdmf of the resumed run lists other steps than the reference:"
  steps "$work/resumed"; exit 1
fi
echo "results.xdmf lists the same $(steps "$work/reference" | wc -l) steps"
