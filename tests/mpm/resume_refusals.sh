#!/bin/bash
# Checkpoints and resumes never lose results nor continue from something else than they claim.
# One small continuum run (killed after its step-16 checkpoint) is the starting point of every
# scenario; each scenario works on a fresh copy of it and checks, besides the exit code and the
# message, that no file of the copy changed (sha256 of everything) when a resume is refused.
# usage: resume_refusals.sh MPM_LIG CASE.json WORK_DIR
set -u
exe=$1 case=$2 work=$3
here=$(dirname "$0")
rm -rf "$work" && mkdir -p "$work"
failures=0 scenarios=0
fail() { echo "FAIL [$scenario]: $*"; failures=$((failures + 1)); }

/usr/bin/python3 - "$case" "$work/case.json" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c["analysis"]["end"] = {"steps": 40}
c["output"] = {"every": 5, "checkpoint_every": 8}
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
# Variants of the case: (file, JSON edit as Python on `c`).
variant() {
  /usr/bin/python3 - "$work/case.json" "$work/$1.json" "$2" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
exec(sys.argv[3])
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
}
variant stiffer 'c["materials"][0]["youngs_modulus"] *= 2; c["gravity"][1] = -9.8'
variant longer 'c["analysis"]["end"]["steps"] = 48; c["output"]["every"] = 4; c["title"] = "x"'
variant shorter 'c["analysis"]["end"]["steps"] = 12'
variant commented 'c["_see [3"] = "x"; c["materials"][0]["_note"] = "changed"'

"$exe" "$work/case.json" --output "$work/reference" > /dev/null || { echo "reference run failed"; exit 1; }
(MPM_LIG_KILL_AT_STEP=18 "$exe" "$work/case.json" --output "$work/base" > /dev/null 2>&1) 2> /dev/null
[ "$(cat "$work/base/checkpoints/latest")" = step_16 ] || { echo "no step-16 checkpoint"; exit 1; }

# Every file but the folder's lock (mpm_lig.lock: who holds the folder, not a result; the
# killed base run left it, each resume takes it over).
digest() { (cd "$1" && find . -type f ! -name mpm_lig.lock -print0 | sort -z | xargs -0 sha256sum); }
fresh() { rm -rf "$work/run" && cp -a "$work/base" "$work/run" && digest "$work/run" > "$work/before"; }
unchanged() {
  digest "$work/run" > "$work/after"
  diff -q "$work/before" "$work/after" > /dev/null || { fail "files changed:"; diff "$work/before" "$work/after" | head -5; }
}
# expect CODE REGEX ARGS...: run mpm_lig, check its exit code and that stderr matches.
expect() {
  local code=$1 regex=$2; shift 2
  scenarios=$((scenarios + 1))
  timeout 60 "$exe" "$@" > "$work/out.log" 2> "$work/err.log"
  local status=$?
  [ $status -eq "$code" ] || fail "exit $status, expected $code: $(head -c 300 "$work/err.log")"
  [ -z "$regex" ] || grep -Eq -- "$regex" "$work/err.log" || fail "no '$regex' in: $(head -c 300 "$work/err.log")"
}
resume_refused() { expect 2 "$1" "${2:-$work/case.json}" --resume "$work/run"; unchanged; }

scenario="latest names a folder outside (resume)"
fresh; mkdir -p "$work/victim" && echo keep > "$work/victim/data"
echo "../../victim" > "$work/run/checkpoints/latest"; digest "$work/run" > "$work/before"
resume_refused "does not name a checkpoint of this folder"
scenario="latest names a folder outside (new run)"
expect 0 "" "$work/case.json" --output "$work/run" --replace
[ "$(cat "$work/victim/data" 2>/dev/null)" = keep ] || fail "victim/ was touched"
scenario="latest is .. (new run)"
fresh; echo keep > "$work/run/user_notes.txt"; echo ".." > "$work/run/checkpoints/latest"
expect 0 "" "$work/case.json" --output "$work/run" --replace
[ -f "$work/run/user_notes.txt" ] || fail "the user's file in the output folder is gone"

scenario="flipped byte in mpm.h5"
fresh; printf '\x5a' | dd of="$work/run/checkpoints/step_16/mpm.h5" bs=1 seek=3000 conv=notrunc 2> /dev/null
digest "$work/run" > "$work/before"
resume_refused "damaged: 'mpm.h5' has changed"
scenario="checkpoint without manifest"
fresh; rm "$work/run/checkpoints/step_16/MANIFEST.sha256"; digest "$work/run" > "$work/before"
resume_refused "has no MANIFEST.sha256"
scenario="changed case"
fresh; resume_refused "case has changed.*gravity\[1\], materials\[0\]\.youngs_modulus \(only" "$work/stiffer.json"
scenario="changed case, --validate --resume"
fresh; expect 2 "case has changed.*gravity\[1\]" --validate "$work/stiffer.json" --resume "$work/run"
unchanged
scenario="end before the checkpoint"
fresh; resume_refused "analysis\.end\.steps = 12 lies before the checkpoint's step 16" "$work/shorter.json"
scenario="history.csv deleted"
fresh; rm "$work/run/history.csv"; digest "$work/run" > "$work/before"
resume_refused "history\.csv' is missing"
scenario="history.csv cut"
fresh; head -n 5 "$work/base/history.csv" > "$work/run/history.csv"; digest "$work/run" > "$work/before"
resume_refused "history\.csv' holds 4 rows, the checkpoint needs"
scenario="history.csv written by a build with other columns"
fresh; sed -i '1s/$/,gradient_energy/' "$work/run/history.csv"; digest "$work/run" > "$work/before"
resume_refused "history\.csv' has the columns .*gradient_energy; this build writes"
scenario="results.h5 truncated"
fresh; truncate -s 2000 "$work/run/results.h5"; digest "$work/run" > "$work/before"
resume_refused "results\.h5' cannot be read.*left as it is"
scenario="NaN stress (checksums made to match)"
fresh; /usr/bin/python3 - "$work/run/checkpoints/step_16/mpm.h5" <<'PY'
import h5py, sys
with h5py.File(sys.argv[1], "r+") as f:
    s = f["stress"][()]; s[4] = float("nan"); f["stress"][...] = s
PY
(cd "$work/run/checkpoints/step_16" && find . -type f ! -name MANIFEST.sha256 -printf '%P\n' | sort | xargs sha256sum > MANIFEST.sha256)
digest "$work/run" > "$work/before"
resume_refused "not finite in 'stress'"

scenario="checkpoint of an older layout (no format, checksums made to match)"
fresh; /usr/bin/python3 - "$work/run/checkpoints/step_16/mpm.h5" <<'PY'
import h5py, sys
with h5py.File(sys.argv[1], "r+") as f:
    del f.attrs["format"]
PY
(cd "$work/run/checkpoints/step_16" && find . -type f ! -name MANIFEST.sha256 -printf '%P\n' | sort | xargs sha256sum > MANIFEST.sha256)
digest "$work/run" > "$work/before"
resume_refused "has layout 1 \(an older mpm_lig wrote it\); this build reads layouts 4 to 5"

scenario="checkpoint of another build (checksums made to match): resumed with a warning"
fresh; echo "other-build" > "$work/run/checkpoints/step_16/build"
(cd "$work/run/checkpoints/step_16" && find . -type f ! -name MANIFEST.sha256 -printf '%P\n' | sort | xargs sha256sum > MANIFEST.sha256)
expect 0 "checkpoint .* was written by build other-build, this is build " "$work/case.json" --resume "$work/run"

scenario="--resume of a missing folder"
expect 2 "--resume $work/no_such_dir: no such folder" "$work/case.json" --resume "$work/no_such_dir"
[ ! -e "$work/no_such_dir" ] || fail "the folder was created"
scenario="--output empty"
expect 2 "--output: the folder name is empty" "$work/case.json" --output ""
scenario="--resume A --output B"
fresh; expect 2 "name different folders" "$work/case.json" --resume "$work/run" --output "$work/elsewhere"
[ ! -e "$work/elsewhere" ] || fail "--output folder was created"; unchanged

scenario="failed resumes keep every earlier step, then one succeeds"
fresh; mkdir "$work/run/results.h5.resume_tmp"  # cannot be written, as on a full disk
for attempt in 1 2; do
  expect 1 "run failed" "$work/case.json" --resume "$work/run"
  cmp -s "$work/base/results.h5" "$work/run/results.h5" || fail "results.h5 changed by failed resume $attempt"
  cmp -s "$work/base/history.csv" "$work/run/history.csv" || fail "history.csv changed by failed resume $attempt"
done
rmdir "$work/run/results.h5.resume_tmp"
expect 0 "" "$work/case.json" --resume "$work/run"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/reference" "$work/run" > /dev/null || fail "resumed run differs from the uninterrupted one"

scenario="--output name the system cannot resolve"
fresh; expect 2 "--output .*: File name too long" "$work/case.json" --resume "$work/run" \
  --output "$work/run/$(printf 'x%.0s' {1..300})"
unchanged

scenario="comment keys (one with an unmatched '[') added on resume"
fresh; expect 0 "" "$work/commented.json" --resume "$work/run"

scenario="new run into a stopped run's folder without --replace"
fresh; expect 2 "holds an earlier run's results \(history.csv\): continue that run with --resume" \
  "$work/case.json" --output "$work/run"
unchanged

scenario="foreign files in checkpoints/ (new run)"
fresh; mkdir "$work/run/checkpoints/mine" && echo keep > "$work/run/checkpoints/mine/data"
echo keep > "$work/run/checkpoints/notes.txt"
expect 0 "" "$work/case.json" --output "$work/run" --replace
[ -f "$work/run/checkpoints/mine/data" ] && [ -f "$work/run/checkpoints/notes.txt" ] ||
  fail "the user's files in checkpoints/ are gone"

scenario="SIGTERM during the last step: the run completes"
scenarios=$((scenarios + 1)); rm -rf "$work/last"
MPM_LIG_TERM_AT_STEP=40 timeout 60 "$exe" "$work/case.json" --output "$work/last" > "$work/out.log" 2>&1 ||
  fail "exit $?: $(tail -c 300 "$work/out.log")"
! grep -q "stopped by a signal" "$work/out.log" || fail "stopped after its last step"
[ -f "$work/last/summary.json" ] || fail "no summary.json: the run did not complete"
/usr/bin/python3 "$here/../../tools/compare_outputs.py" --results-only "$work/reference" "$work/last" > /dev/null ||
  fail "differs from the uninterrupted run"

scenario="safe keys changed: end, output.every, title"
fresh; expect 0 "" "$work/longer.json" --resume "$work/run"
[ "$(($(wc -l < "$work/run/history.csv") - 1))" -eq 49 ] || fail "history.csv does not reach step 48"

echo "$scenarios scenarios, $failures failures"
[ $failures -eq 0 ]
