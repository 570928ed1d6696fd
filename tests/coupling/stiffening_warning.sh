#!/bin/sh
# The step set from the packings' moduli at p0 against their stiffened waves: a block
# compressed fast (tiny_2x2_stiffening.json, 12 steps) passes CFL 0.6 and the run says so once
# on stderr and in summary.json; the gentle tiny_2x2.json stays below and says nothing; a
# fixed step at 0.8 of the estimate warns at once.
# usage: stiffening_warning.sh MPM_LIG CASE_DIR WORK_DIR
set -u
mpm_lig=$1 cases=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
fail() { echo "FAIL: $*"; exit 1; }
"$mpm_lig" "$cases/tiny_2x2_stiffening.json" --output "$work/fast" > /dev/null 2> "$work/fast.err" ||
  fail "the fast compression ended with exit $?: $(tail -3 "$work/fast.err")"
[ "$(grep -c 'warning: at step .* as their state has stiffened them' "$work/fast.err")" = 1 ] ||
  fail "no single stiffening warning: $(cat "$work/fast.err")"
"$mpm_lig" "$cases/tiny_2x2.json" --output "$work/gentle" > /dev/null 2> "$work/gentle.err" ||
  fail "the gentle run ended with exit $?"
grep -q 'has stiffened them' "$work/gentle.err" && fail "the gentle run warned: $(cat "$work/gentle.err")"
# A fixed step at 0.8 of the packings' CFL estimate (allowed: only above 1 is refused) warns
# from the first step.
/usr/bin/python3 - "$cases/tiny_2x2.json" "$work" <<'PY' || exit 1
import json, sys
case = json.load(open(sys.argv[1]))
step = json.load(open(sys.argv[2] + "/gentle/summary.json"))["time_step"] / 0.5 * 0.8
case["analysis"]["time_step"] = {"fixed": step}
json.dump(case, open(sys.argv[2] + "/fixed.json", "w"))
PY
"$mpm_lig" "$work/fixed.json" --output "$work/fixed" > /dev/null 2> "$work/fixed.err" ||
  fail "the fixed-step run ended with exit $?"
grep -q 'warning: at step 0 the time step is CFL 0.8' "$work/fixed.err" ||
  fail "a fixed step at 0.8 of the estimate did not warn at step 0: $(cat "$work/fixed.err")"
/usr/bin/python3 - "$work" <<'PY' || exit 1
import json, sys
fast = json.load(open(sys.argv[1] + "/fast/summary.json"))["largest_stiffened_cfl"]
gentle = json.load(open(sys.argv[1] + "/gentle/summary.json"))["largest_stiffened_cfl"]
if not (fast > 0.6 and 0.5 <= gentle <= 0.6):
    sys.exit("FAIL: largest_stiffened_cfl fast %.4f (> 0.6 expected), gentle %.4f (0.5-0.6)" % (fast, gentle))
print("ok: largest_stiffened_cfl fast %.4f, gentle %.4f" % (fast, gentle))
PY
