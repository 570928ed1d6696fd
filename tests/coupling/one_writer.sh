#!/bin/sh
# One writer per output folder. While a run lives, a second run of the same case, a run of
# another case into the same --output, a --replace and a --resume of the folder are all refused
# (exit 2, the holder named) and change nothing: the run ends with every step in history.csv.
# A stopped run's folder refuses a new run (its results and checkpoint would be lost) unless
# --replace; a partial checkpoint folder is removed by the resume; a lock left by a killed run
# (SIGKILL) is found stale and taken over.
# The run is asked for far more steps than it can make before the checks (no race with a fast
# machine), then stopped by SIGTERM and resumed to an end a few steps later.
# usage: one_writer.sh MPM_LIG CASE.json OTHER_CASE.json WORK_DIR
set -e
exe=$1 case=$2 other=$3 work=$4
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
set_end() {  # set_end IN OUT STEPS
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": int(sys.argv[3])}
c.setdefault("output", {})["checkpoint_every"] = 3
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
}
fail() { echo "FAILED: $*"; exit 1; }
wait_rows() {  # wait_rows DIR N: until DIR/history.csv has N rows
  tries=0
  until [ -f "$1/history.csv" ] && [ "$(wc -l < "$1/history.csv")" -gt "$2" ]; do
    tries=$((tries + 1))
    [ $tries -le 1200 ] || fail "the run in $1 made no progress"
    sleep 0.1
  done
}
# expect CODE REGEX LOG -- command...: the command's exit code and a line of its output.
expect() {
  code=$1 regex=$2 log=$3
  shift 4
  status=0
  "$@" > "$log" 2>&1 || status=$?
  [ $status -eq "$code" ] || { cat "$log"; fail "'$*' exited $status, not $code"; }
  grep -Eq "$regex" "$log" || { cat "$log"; fail "'$*' did not say /$regex/"; }
}
set_end "$case" "$work/long.json" 100000
run=$work/run
"$exe" "$work/long.json" --output "$run" > "$work/first.log" 2>&1 &
pid=$!
wait_rows "$run" 4
[ -f "$run/mpm_lig.lock" ] || fail "no lock file while the run lives"
busy="is in use by another mpm_lig run \(pid $pid on host "
expect 2 "$busy" "$work/same.log" -- "$exe" "$work/long.json" --output "$run"
expect 2 "$busy" "$work/other.log" -- "$exe" "$other" --output "$run"
expect 2 "$busy" "$work/replace.log" -- "$exe" "$work/long.json" --output "$run" --replace
expect 2 "$busy" "$work/resume.log" -- "$exe" "$work/long.json" --resume "$run"
kill -TERM $pid
status=0
wait $pid || status=$?
[ $status -eq 4 ] || { cat "$work/first.log"; fail "the first run exited $status, not 4"; }
[ ! -e "$run/mpm_lig.lock" ] || fail "the stopped run left its lock file"
step=$(sed 's/step_//' "$run/checkpoints/latest")
rows=$(($(wc -l < "$run/history.csv") - 1))
[ "$rows" -eq $((step + 1)) ] || fail "history.csv holds $rows rows, the checkpoint step $step"
# The stopped run's results and checkpoint are kept from a new run.
before=$(cat "$run/history.csv" "$run/checkpoints/latest" | md5sum)
expect 2 "holds an earlier run's results \(history.csv\): continue that run with --resume" \
  "$work/new_into_stopped.log" -- "$exe" "$other" --output "$run"
[ "$(cat "$run/history.csv" "$run/checkpoints/latest" | md5sum)" = "$before" ] ||
  fail "the refused run changed the folder"
# A checkpoint write killed before its commit leaves a step folder: the resume removes it.
mkdir -p "$run/checkpoints/step_99999/m3" && echo partial > "$run/checkpoints/step_99999/mpm.h5"
end=$((step + 4))
set_end "$case" "$work/end.json" $end
expect 0 "removed .*step_99999: a checkpoint write that did not finish" "$work/resumed.log" -- \
  "$exe" "$work/end.json" --resume "$run"
[ ! -e "$run/checkpoints/step_99999" ] || fail "the partial checkpoint folder is still there"
[ -f "$run/summary.json" ] || fail "the resumed run wrote no summary.json"
[ "$(($(wc -l < "$run/history.csv") - 1))" -eq $((end + 1)) ] || fail "history rows after resume"
# A finished run's folder: a new run is refused without --replace, accepted with it.
before=$(md5sum < "$run/summary.json")
expect 2 "holds an earlier run's results \(summary.json\)" "$work/new_into_done.log" -- \
  "$exe" "$work/end.json" --output "$run"
[ "$(md5sum < "$run/summary.json")" = "$before" ] || fail "the refused run changed summary.json"
# A lock left by a killed run is stale: the next run takes the folder over.
killed=$work/killed
"$exe" "$work/long.json" --output "$killed" > "$work/killed.log" 2>&1 &
pid=$!
wait_rows "$killed" 2
kill -KILL $pid
wait $pid || true
[ -f "$killed/mpm_lig.lock" ] || fail "the killed run left no lock file (the stale case is not tested)"
expect 0 "" "$work/after_kill.log" -- "$exe" "$work/end.json" --output "$killed" --replace
[ ! -e "$killed/mpm_lig.lock" ] || fail "the run after the kill left its lock file"
rows=$(($(wc -l < "$killed/history.csv") - 1))
[ "$rows" -eq $((end + 1)) ] || fail "the replacing run wrote $rows rows, not $((end + 1))"
echo "one writer per folder: 4 refusals while running, 2 refusals of a new run, stale lock taken over"
