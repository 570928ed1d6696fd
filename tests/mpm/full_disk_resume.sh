#!/bin/bash
# A resume on a full disk fails with a message and changes nothing; repeated, the same; once
# space is free again it succeeds with every earlier step and ends bit-identical to an
# uninterrupted run. Needs a small tmpfs (mount -t tmpfs): skipped (exit 77) where the machine
# does not allow mounting.
# usage: full_disk_resume.sh MPM_LIG CASE.json WORK_DIR
set -u
exe=$1 case=$2 work=$3
here=$(dirname "$0")
disk="$work/disk"
cleanup() { umount "$disk" 2> /dev/null; }
trap cleanup EXIT
umount "$disk" 2> /dev/null
rm -rf "$work" && mkdir -p "$disk"
if ! mount -t tmpfs -o size=4m tmpfs "$disk" 2> "$work/mount.log"; then
  echo "skipped: cannot mount a tmpfs here ($(cat "$work/mount.log"))"; exit 77
fi
/usr/bin/python3 - "$case" "$work/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 40}
c["output"] = {"every": 5, "checkpoint_every": 8}
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
"$exe" "$work/case.json" --output "$work/reference" > /dev/null || { echo "reference failed"; exit 1; }
(MPM_LIG_KILL_AT_STEP=18 "$exe" "$work/case.json" --output "$disk/run" > /dev/null 2>&1) 2> /dev/null
[ "$(cat "$disk/run/checkpoints/latest")" = step_16 ] || { echo "no step-16 checkpoint"; exit 1; }
# Every file but the folder's lock (mpm_lig.lock: who holds the folder, not a result; the
# killed run left it, each resume takes it over).
digest() { (cd "$disk/run" && find . -type f ! -name mpm_lig.lock -print0 | sort -z | xargs -0 sha256sum); }
digest > "$work/before"
dd if=/dev/zero of="$disk/filler" bs=4k 2> /dev/null  # until the disk is full
failures=0
for attempt in 1 2 3; do
  timeout 60 "$exe" "$work/case.json" --resume "$disk/run" > /dev/null 2> "$work/err.log"
  status=$?
  [ $status -eq 1 ] && grep -q "run failed" "$work/err.log" ||
    { echo "full-disk resume $attempt: exit $status, $(head -c 300 "$work/err.log")"; failures=$((failures + 1)); }
  digest > "$work/after"
  diff -q "$work/before" "$work/after" > /dev/null ||
    { echo "full-disk resume $attempt changed files:"; diff "$work/before" "$work/after" | head; failures=$((failures + 1)); }
done
echo "3 resumes on a full disk: $(head -c 200 "$work/err.log")"
rm "$disk/filler"
"$exe" "$work/case.json" --resume "$disk/run" > /dev/null || { echo "resume with space failed"; exit 1; }
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/reference" "$disk/run" || failures=$((failures + 1))
[ $failures -eq 0 ]
