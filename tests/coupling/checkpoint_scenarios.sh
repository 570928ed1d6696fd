# Sourced by the checkpoint scenario scripts (bundle_resume.sh, group_resume.sh): a failure
# count, the output comparison and the short case they run.
compare="/usr/bin/python3 $(dirname "${BASH_SOURCE[0]}")/../../tools/compare_outputs.py --results-only"
failures=0
fail() { echo "FAIL [$scenario]: $*"; failures=$((failures + 1)); }
# short_case CASE OUT [RANKS_PER_RVE]: CASE ending at step 6 with a checkpoint every 2 steps.
short_case() {
  /usr/bin/python3 - "$@" <<'PY'
import json, sys
c = json.load(open(sys.argv[1]))
c.setdefault("output", {})["checkpoint_every"] = 2
c["analysis"]["end"] = {"steps": 6}
if len(sys.argv) > 3:
    c["materials"][0]["ranks_per_rve"] = int(sys.argv[3])
json.dump(c, open(sys.argv[2], "w"), indent=1)
PY
}
# resume_matches KILLED NP MPIRUN...: a copy of the run folder KILLED, resumed on NP ranks, ends
# bit-identical to $work/reference (uses $exe and $work of the calling script).
resume_matches() {
  local killed=$1 np=$2
  shift 2
  rm -rf "$work/run" && cp -a "$killed" "$work/run"
  "$@" -np "$np" "$exe" "$work/case.json" --resume "$work/run" > "$work/run.log" 2>&1 ||
    fail "resume failed: $(tail -c 400 "$work/run.log")"
  $compare "$work/reference" "$work/run" > "$work/compare.log" 2>&1 || fail "$(cat "$work/compare.log")"
}
