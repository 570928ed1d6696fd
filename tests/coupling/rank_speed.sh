#!/bin/bash
# balance.rank_speed "measured": the balancer weighs each group's load by its measured speed;
# a run on 3 groups with it (and RVEs moved) ends bit-identical to the run on one rank.
# usage: rank_speed.sh MPM_LIG CASE.json WORK_DIR MPIRUN...
set -eu
exe=$1 case=$2 work=$3
shift 3
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 - "$case" "$work/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["materials"][0]["balance"]["rank_speed"] = "measured"
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
for n in 1 3; do
  "$@" -np $n "$exe" "$work/case.json" --output "$work/np$n" > "$work/np$n.log" 2>&1 ||
    { cat "$work/np$n.log"; exit 1; }
done
/usr/bin/python3 "$here/check_balance.py" --expect-migrations "$work/np3"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/np1" "$work/np3" \
  --ranks 1 3
