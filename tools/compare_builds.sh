#!/usr/bin/env bash
# Runs shipped cases with two builds of mpm_lig and checks that their results are bit-identical:
# history.csv byte for byte, every dataset and attribute of results.h5 (when written), and every
# number of summary.json except the timings (wall time, its split, rates).
#
#   tools/compare_builds.sh REFERENCE_MPM_LIG NEW_MPM_LIG WORK_DIR [NP:CASE.json ...]
#
# Default cases: the quick start (np 2), the quick-start element test and the Prandtl footing
# (Tresca continuum). Example, before/after a refactoring:
#   tools/compare_builds.sh /work/baseline/mpm_lig build/mpm_lig /tmp/compare
# REUSE_REFERENCE=1 keeps reference runs already in WORK_DIR (the reference build's results do
# not change between two comparisons). ALLOW_ADDED=1 lets the new build write outputs the
# reference lacks (listed), as long as every shared value is bit-identical.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
reference=$(realpath "$1") new=$(realpath "$2") work=$3
shift 3
cases=("$@")
if [ ${#cases[@]} -eq 0 ]; then
  cases=("2:$here/../cases/quickstart.json" "1:$here/../cases/element_quickstart.json"
         "1:$here/../cases/mpm/prandtl_tresca.json")
fi
mpirun=(mpirun --allow-run-as-root --oversubscribe)
status=0
for entry in "${cases[@]}"; do
  np=${entry%%:*} case_file=${entry#*:}
  name=$(basename "$case_file" .json)
  for side in reference new; do
    binary=$reference
    [ "$side" = new ] && binary=$new
    if [ "$side" = reference ] && [ "${REUSE_REFERENCE:-0}" = 1 ] &&
       [ -s "$work/$name/reference/summary.json" ]; then
      continue
    fi
    rm -rf "$work/$name/$side"
    mkdir -p "$work/$name"
    "${mpirun[@]}" -np "$np" "$binary" "$case_file" --output "$work/$name/$side" \
      > "$work/$name/$side.log" 2>&1
  done
  added=()
  [ "${ALLOW_ADDED:-0}" = 1 ] && added=(--allow-added)
  if /usr/bin/python3 "$here/compare_outputs.py" "$work/$name/reference" "$work/$name/new" \
       ${added[@]+"${added[@]}"}; then
    echo "$name: bit-identical"
  else
    echo "$name: DIFFERS" >&2
    status=1
  fi
done
exit $status
