#!/bin/sh
# Hard case: a material point carried out of the mesh. The run must stop with exit 1 and a
# message naming the point; its last checkpoint must be intact: --resume from it loads, runs
# and stops the same way at the same step, and the results file of the run opens.
# usage: leaves_mesh.sh MPM_LIG CASE.json WORK_DIR
exe=$1 case=$2 work=$3
fail() { echo "FAIL: $*"; exit 1; }
rm -rf "$work" "$work.log" "$work.resume.log"
"$exe" "$case" --output "$work" > "$work.log" 2>&1
code=$?
[ $code -eq 1 ] || fail "exit code $code, expected 1: $(cat "$work.log")"
message=$(grep -o "material point [0-9]* left the mesh at ([^)]*)" "$work.log") ||
  fail "no message naming the point: $(cat "$work.log")"
latest=$(cat "$work/checkpoints/latest") || fail "no checkpoint"
"$exe" "$case" --resume "$work" > "$work.resume.log" 2>&1
code=$?
[ $code -eq 1 ] || fail "resumed run: exit code $code, expected 1: $(cat "$work.resume.log")"
again=$(grep -o "material point [0-9]* left the mesh at ([^)]*)" "$work.resume.log") ||
  fail "resumed run: no message naming the point"
[ "$message" = "$again" ] || fail "resumed run stopped otherwise: '$again' vs '$message'"
/usr/bin/python3 -c "import h5py, sys; h5py.File(sys.argv[1]).keys()" "$work/results.h5" ||
  fail "results.h5 does not open"
echo "point leaving the mesh | exit 1 naming the point, checkpoint resumes to the same stop | $message; resumed from $latest"
