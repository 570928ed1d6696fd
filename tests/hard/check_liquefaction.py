#!/usr/bin/python3
"""Hard case: liquefaction and beyond. Reads a history.csv (element test or MPM simple-shear
history) and checks that the mean effective stress fell below FRACTION of its initial value and
that the run then went on for at least CYCLES more loading cycles with finite, bounded stress.

usage: check_liquefaction.py HISTORY_CSV --fraction 0.01 --cycles 2 --period-strain 4*gamma_a
Prints one table row: case | criterion | measured margin."""
import argparse
import csv
import math
import sys


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("history", nargs="?")
    ap.add_argument("--history-in", help="output folder holding history.csv (given last)")
    ap.add_argument("--fraction", type=float, default=0.01)
    ap.add_argument("--cycles", type=float, default=2.0)
    ap.add_argument("--increments-per-cycle", type=int, help="element test: rows per cycle")
    ap.add_argument("--mean", default="p", help="column of the mean effective stress")
    ap.add_argument("--shear", default="q", help="column of the shear stress")
    ap.add_argument("--cycle-column", help="MPM history: column holding the cycle number")
    ap.add_argument("--max-substeps", type=float, help="bound on the substeps column")
    a = ap.parse_args()
    if a.history_in:
        a.history = a.history_in + "/history.csv"
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(a.history))]
    failures = []
    p0 = rows[0][a.mean]
    for r in rows:
        if not all(math.isfinite(v) for k, v in r.items() if k not in ("kinetic_ratio", "flow_ratio", "health_ratio")):
            failures.append("non-finite value in a history row")
            break
    below = next((i for i, r in enumerate(rows) if r[a.mean] < a.fraction * p0), None)
    if below is None:
        failures.append("p' never fell below %g p0' (min %.3g p0')"
                        % (a.fraction, min(r[a.mean] for r in rows) / p0))
        after = 0.0
    elif a.cycle_column:
        after = rows[-1][a.cycle_column] - rows[below][a.cycle_column]
    else:
        after = (rows[-1]["increment"] - rows[below]["increment"]) / a.increments_per_cycle
    if after < a.cycles:
        failures.append("only %.2f cycles after p' < %g p0' (asked %g)" % (after, a.fraction, a.cycles))
    peak = max(abs(r[a.shear]) for r in rows)
    after_rows = rows[below:] if below is not None else []
    max_after = max((abs(r[a.mean]) + abs(r[a.shear]) for r in after_rows), default=0.0)
    if max_after > 2.0 * p0:
        failures.append("stress after liquefaction %.3g exceeds 2 p0'" % max_after)
    if a.max_substeps and "substeps" in rows[0]:
        most = max(r["substeps"] for r in rows)
        if most > a.max_substeps:
            failures.append("DEM sub-steps %d above %d" % (most, a.max_substeps))
    print("liquefaction | p' < %g p0' then >= %g cycles, stress <= 2 p0' | %.2f cycles after, "
          "min p'/p0' %.2e, max stress after %.2f p0', peak shear %.2f p0'"
          % (a.fraction, a.cycles, after, min(r[a.mean] for r in rows) / p0, max_after / p0, peak / p0))
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


main()
