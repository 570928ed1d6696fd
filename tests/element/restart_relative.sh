#!/bin/sh
# A case names its restart file relative to its own folder: it validates and runs from any
# working directory. usage: restart_relative.sh MPM_LIG PREPARED_RESTART BASE_CASE WORK_DIR
set -eu
mpm_lig=$1 restart=$2 base=$3 work=$4
rm -rf "$work"
mkdir -p "$work/cases/packings" "$work/elsewhere"
cp "$restart" "$work/cases/packings/dense.restart"
# The base case with the packing taken from the restart file instead of being prepared.
python3 - "$base" "$work/cases/from_restart.json" <<'PY'
import json, sys
case = json.load(open(sys.argv[1]))
del case["rve"]["preparation"]
case["rve"]["restart_file"] = "packings/dense.restart"
json.dump(case, open(sys.argv[2], "w"), indent=1)
PY
cd "$work/elsewhere"
"$mpm_lig" --validate ../cases/from_restart.json
"$mpm_lig" ../cases/from_restart.json --output out
test -s out/history.csv
grep -q '"restart_file": ".*cases/packings/dense.restart"' out/summary.json
echo "restart file resolved relative to the case file"
