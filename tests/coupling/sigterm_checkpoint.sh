#!/bin/sh
# SIGTERM (a batch job's wall time ends) mid-run: the run writes a checkpoint between two steps
# and exits 4 (stopped, not complete) at once; --resume then continues it to the end with every
# step in history.csv.
# With a launcher (mpirun -np 2 ...) the signal goes to the launcher, as `kill` or a batch
# system without srun sends it: the launcher must forward it to every rank. Open MPI's mpirun
# then exits 1 whatever the ranks' codes (measured, Open MPI 4.1): its exit code is not
# checked, the stop message and the checkpoint are.
# SIGNAL=HUP (default TERM) sends another stop signal.
# The run is asked for far more steps than it can make before the signal arrives (no race with
# a fast machine); the resume is then asked to end RESUME_STEPS (default 300) steps after the
# stop (`end` is a key a resume may change).
# With IDENTITY=1 the resumed run is compared with an uninterrupted run that writes no
# checkpoint: writing one must not change the arithmetic (chaotic DEM: any round-off difference
# grows to percents over hundreds of steps), so they must be bit-identical.
# usage: [SIGNAL=HUP] [IDENTITY=1] [RESUME_STEPS=n] sigterm_checkpoint.sh MPM_LIG CASE.json WORK_DIR [LAUNCHER ...]
set -e
signal=${SIGNAL:-TERM}
exe=$1 case=$2 work=$3
shift 3
rm -rf "$work" && mkdir -p "$work"
/usr/bin/python3 - "$case" "$work/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 100000}
c.setdefault("output", {})["every"] = 250
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
run="$work/run"
"$@" "$exe" "$work/case.json" --output "$run" > "$work/stopped.log" 2>&1 &
pid=$!
# Wait for a few main-stage steps, then ask the run to stop.
tries=0
until [ -f "$run/history.csv" ] && [ "$(wc -l < "$run/history.csv")" -ge 4 ]; do
  tries=$((tries + 1))
  [ $tries -le 600 ] || { kill -9 $pid; echo "the run made no progress"; exit 1; }
  sleep 0.1
done
kill -"$signal" $pid
start=$(date +%s.%N)
status=0
wait $pid || status=$?
if [ $# -eq 0 ] && [ $status -ne 4 ] && grep -q "stopped by a signal" "$work/stopped.log"; then
  echo "the stopped run exited $status, not 4:"; cat "$work/stopped.log"; exit 1
fi
end=$(date +%s.%N)
if ! grep -q "stopped by a signal after step" "$work/stopped.log"; then
  echo "no stop message:"; cat "$work/stopped.log"; exit 1
fi
latest=$(cat "$run/checkpoints/latest")
step=${latest#step_}
rows=$(($(wc -l < "$run/history.csv") - 1))
echo "stopped at step $step, $rows history rows, exit $status $(echo "$end - $start" | bc) s after SIG$signal"
[ "$rows" -eq $((step + 1)) ] || { echo "history rows do not match the checkpoint"; exit 1; }
[ -f "$run/summary.json" ] && { echo "the run ended before the signal"; exit 1; }
end=$((step + ${RESUME_STEPS:-300}))
/usr/bin/python3 - "$work/case.json" "$work/resume.json" "$end" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": int(sys.argv[3])}
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
"$@" "$exe" "$work/resume.json" --resume "$run" > "$work/resumed.log" 2>&1
/usr/bin/python3 - "$run/history.csv" "$end" <<'PY'
import sys
end = int(sys.argv[2])
rows = [line.split(",")[0] for line in open(sys.argv[1]).read().splitlines()[1:]]
steps = [int(float(s)) for s in rows]
if steps != list(range(end + 1)):
    sys.exit("history.csv steps are not 0..%d once each: %s" % (end, steps[:5]))
print("resumed to the end: %d history rows, steps 0..%d" % (end + 1, end))
PY
if [ "${IDENTITY:-0}" = 1 ]; then
  "$@" "$exe" "$work/resume.json" --output "$work/uninterrupted" > "$work/uninterrupted.log" 2>&1
  /usr/bin/python3 "$(dirname "$0")/../../tools/compare_outputs.py" --results-only "$work/uninterrupted" "$run"
fi
