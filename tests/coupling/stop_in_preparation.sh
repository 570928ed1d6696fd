#!/bin/sh
# A stop signal while the packings are prepared: exit 4 and a message saying what was written
# (k of N packings, no results, no checkpoint); no partial packing file; a --resume is refused
# (nothing to resume); a new run in the folder needs no --replace (no results there) and ends
# bit-identical to a run in a fresh folder, so a partial preparation is never taken for a
# complete one. Moments: at the start of packing 0 and of packing 1 (a test hook), and SIGTERM
# sent from outside at two moments, wherever the run is then (any phase must stop cleanly).
# usage: stop_in_preparation.sh MPM_LIG CASE.json WORK_DIR
set -e
exe=$1 case=$2 work=$3
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAILED: $*"; exit 1; }
check_clean_stop() {  # check_clean_stop DIR LOG STATUS
  [ "$3" -eq 4 ] || { cat "$2"; fail "exit $3, not 4"; }
  grep -q "stopped by a signal" "$2" || { cat "$2"; fail "no stop message"; }
  ! ls "$1"/packings/*/*.partial > /dev/null 2>&1 || fail "a partial packing file is left"
  [ ! -e "$1/mpm_lig.lock" ] || fail "the lock file is left"
}
"$exe" "$case" --output "$work/fresh" > "$work/fresh.log" 2>&1 || { cat "$work/fresh.log"; fail "reference run"; }
for k in 0 1; do
  out=$work/at_packing_$k
  status=0
  MPM_LIG_TERM_AT_PACKING=$k "$exe" "$case" --output "$out" > "$out.log" 2>&1 || status=$?
  check_clean_stop "$out" "$out.log" $status
  grep -q "while preparing materials\[0\]: $k of 2 packings saved in .*packings.*; no results and no checkpoint were written" "$out.log" ||
    { cat "$out.log"; fail "the message does not say $k of 2 packings saved"; }
  [ "$(ls "$out"/packings/*/ 2>/dev/null | grep -c "\.restart$")" -eq $k ] || fail "$k packing files expected"
  for f in history.csv results.h5 summary.json checkpoints; do
    [ ! -e "$out/$f" ] || fail "$f written by a run stopped in its preparation"
  done
  status=0
  "$exe" "$case" --resume "$out" > "$out.resume.log" 2>&1 || status=$?
  [ $status -eq 2 ] && grep -q "no checkpoint" "$out.resume.log" || { cat "$out.resume.log"; fail "resume not refused"; }
  "$exe" "$case" --output "$out" > "$out.again.log" 2>&1 || { cat "$out.again.log"; fail "new run after the stop"; }
  /usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/fresh" "$out"
done
# From outside: 0.3 s after the start (MPI start-up or validation on most machines), and as
# soon as the packings folder appears (the preparation).
for moment in 0.3 packings; do
  out=$work/at_$moment
  "$exe" "$case" --output "$out" > "$out.log" 2>&1 &
  pid=$!
  if [ $moment = packings ]; then
    tries=0
    until [ -d "$out/packings" ]; do
      tries=$((tries + 1))
      [ $tries -le 1200 ] || { kill -9 $pid; fail "no packings folder"; }
      sleep 0.05
    done
  else
    sleep $moment
  fi
  kill -TERM $pid
  status=0
  wait $pid || status=$?
  if [ $status -eq 0 ] && [ -f "$out/summary.json" ]; then
    echo "SIGTERM at $moment: the run had finished"
    continue
  fi
  check_clean_stop "$out" "$out.log" $status
  echo "SIGTERM at $moment: $(grep 'stopped by a signal' "$out.log")"
done
echo "stops in the preparation are clean"
