#!/bin/bash
# Damaged engine restart files end a run with a message and a non-zero exit, never a hang or
# an abort without a word: a checkpoint's point restart (a member of its bundle) emptied or
# filled with random bytes (index and checksums made to match, as if written so) on rank 1 of 2, and a packing given as
# rve.restart_file that is empty or random (refused by --validate, exit 2).
# usage: restart_damage.sh MPM_LIG CASE.json WORK_DIR MPIRUN...
set -u
exe=$1 case=$2 work=$3
shift 3
rm -rf "$work" && mkdir -p "$work"
failures=0
fail() { echo "FAIL [$scenario]: $*"; failures=$((failures + 1)); }
/usr/bin/python3 - "$case" "$work" <<'PY'
import json, os, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 4}
c.setdefault("output", {})["checkpoint_every"] = 2
json.dump(c, open(os.path.join(sys.argv[2], "case.json"), "w"), indent=1)
rve = c["materials"][0]["rve"]
del rve["preparation"]
c["materials"][0].pop("packings", None)
for name in ("empty", "noise"):
    rve["restart_file"] = name + ".restart"
    json.dump(c, open(os.path.join(sys.argv[2], "packing_" + name + ".json"), "w"), indent=1)
PY
: > "$work/empty.restart"
head -c 20000 /dev/urandom > "$work/noise.restart"
for name in empty noise; do
  scenario="rve.restart_file $name"
  "$exe" --validate "$work/packing_$name.json" > /dev/null 2> "$work/err.log"
  status=$?
  [ $status -eq 2 ] || fail "exit $status"
  grep -Eq "materials\[0\]\.rve\.restart_file: '.*$name\.restart': (empty|not a LIGGGHTS)" "$work/err.log" ||
    fail "$(cat "$work/err.log")"
done

"$@" "$exe" "$work/case.json" --output "$work/base" > /dev/null 2>&1 || { echo "base run failed"; exit 1; }
[ "$(cat "$work/base/checkpoints/latest")" = step_2 ] || { echo "no step-2 checkpoint"; exit 1; }
for damage in empty noise; do
  scenario="checkpoint point 1 restart $damage, rank 1 of 2"
  rm -rf "$work/run" && cp -a "$work/base" "$work/run"
  step="$work/run/checkpoints/step_2"
  /usr/bin/python3 "$(dirname "$0")/bundle_checkpoint.py" replace "$step" 1 "$work/$damage.restart"
  (cd "$step" && find . -type f ! -name MANIFEST.sha256 -printf '%P\n' | sort | xargs sha256sum > MANIFEST.sha256)
  timeout "${RESUME_TIMEOUT:-120}" "$@" "$exe" "$work/case.json" --resume "$work/run" > "$work/out.log" 2> "$work/err.log"
  status=$?
  [ $status -ne 0 ] && [ $status -ne 124 ] || fail "exit $status (124: hang)"
  grep -Eq "point 1 .*point\.restart': (empty|not a LIGGGHTS)" "$work/err.log" ||
    fail "no message naming the file: $(head -c 400 "$work/err.log")"
  grep -q "double free" "$work/err.log" && fail "double free"
done
echo "4 damaged restart scenarios, $failures failures"
[ $failures -eq 0 ]
