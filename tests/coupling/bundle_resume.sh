#!/bin/bash
# Checkpoint bundles (docs/hpc.md §3): a checkpoint holds one bundle per rank group whose
# members match the index and the manifest; a run killed after its step-4 checkpoint resumes
# bit-identical to an uninterrupted run on the same and on another rank count (1 -> 1, 2 -> 2,
# 1 -> 2 and 2 -> 1) and when carried to another folder as an archive without its packings
# (docs/running.md §2: how a run moves to another machine); a checkpoint converted to format 4
# (a file per point) resumes bit-identical too; a flipped byte in a member, a cut or a
# lengthened bundle is refused (exit 2, naming the point and the bundle) with history.csv
# untouched.
# usage: bundle_resume.sh MPM_LIG CASE.json WORK_DIR MPIRUN...
set -u
exe=$1 case=$2 work=$3
shift 3
here=$(dirname "$0")
tool="/usr/bin/python3 $here/bundle_checkpoint.py"
. "$here/checkpoint_scenarios.sh"
rm -rf "$work" && mkdir -p "$work"
short_case "$case" "$work/case.json"
"$@" -np 1 "$exe" "$work/case.json" --output "$work/reference" > "$work/reference.log" 2>&1 ||
  { cat "$work/reference.log"; exit 1; }
for np in 1 2; do
  if MPM_LIG_KILL_AT_STEP=5 "$@" -np $np "$exe" "$work/case.json" --output "$work/killed$np" \
      > "$work/killed$np.log" 2>&1; then
    echo "the run on $np ranks was expected to be killed at step 5"; exit 1
  fi
  [ "$(cat "$work/killed$np/checkpoints/latest")" = step_4 ] || { echo "no step-4 checkpoint"; exit 1; }
  scenario="layout, written on $np"
  $tool check "$work/killed$np/checkpoints/step_4" $np || fail "layout"
  (cd "$work/killed$np/checkpoints/step_4" && sha256sum --quiet -c MANIFEST.sha256) || fail "sha256sum -c"
done

for pair in "1 1" "2 2" "1 2" "2 1"; do
  written=${pair% *} resumed=${pair#* }
  scenario="written on $written, resumed on $resumed"
  resume_matches "$work/killed$written" $resumed "$@"
done

scenario="carried as an archive without packings/, resumed on 2"
rm -rf "$work/run" && mkdir "$work/run"
tar -C "$work/killed1" -cJf "$work/carried.tar.xz" --exclude=./packings \
    --exclude=./mpm_lig.lock . && tar -C "$work/run" -xJf "$work/carried.tar.xz" || fail "archive"
[ ! -e "$work/run/packings" ] || fail "the archive holds packings/"
"$@" -np 2 "$exe" "$work/case.json" --resume "$work/run" > "$work/run.log" 2>&1 ||
  fail "resume failed: $(tail -c 400 "$work/run.log")"
$compare "$work/reference" "$work/run" > "$work/compare.log" 2>&1 || fail "$(cat "$work/compare.log")"

scenario="format 4, resumed on 2"
rm -rf "$work/run" && cp -a "$work/killed1" "$work/run"
$tool to_format4 "$work/run/checkpoints/step_4" || fail "conversion"
"$@" -np 2 "$exe" "$work/case.json" --resume "$work/run" > "$work/run.log" 2>&1 ||
  fail "resume failed: $(tail -c 400 "$work/run.log")"
$compare "$work/reference" "$work/run" > "$work/compare.log" 2>&1 || fail "$(cat "$work/compare.log")"

for damage in flip cut lengthen; do
  scenario="bundle member $damage"
  rm -rf "$work/run" && cp -a "$work/killed2" "$work/run"
  step="$work/run/checkpoints/step_4"
  case $damage in
    flip) bundle=$($tool corrupt "$step" 3)
          pattern="material point 3, member 0: bytes [0-9]+-[0-9]+ of '.*/m3/$bundle' have changed" ;;
    cut) truncate -s -1 "$step/m3/rank_1.bundle"
         pattern="'rank_1\.bundle' holds [0-9]+ bytes, its members [0-9]+ \(cut" ;;
    lengthen) printf x >> "$step/m3/rank_0.bundle"
              pattern="'rank_0\.bundle' holds [0-9]+ bytes" ;;
  esac
  before=$(sha256sum < "$work/run/history.csv")
  "$@" -np 2 "$exe" "$work/case.json" --resume "$work/run" > /dev/null 2> "$work/err.log"
  status=$?
  [ $status -eq 2 ] || fail "exit $status: $(tail -c 400 "$work/err.log")"
  grep -Eq "is damaged: .*$pattern" "$work/err.log" || fail "message: $(head -c 400 "$work/err.log")"
  [ "$(sha256sum < "$work/run/history.csv")" = "$before" ] || fail "history.csv changed"
done
echo "bundle scenarios: $failures failures"
[ $failures -eq 0 ]
