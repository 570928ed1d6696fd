#!/usr/bin/python3
"""A uniform biaxial strain path written as CSV and replayed equals the element test that
computes the same path itself, bit for bit.

usage: replay_uniform_path.py MPM_LIG BASE_CASE PACKING WORK_DIR

BASE_CASE is an isotropic_compression test of a 2D RVE (equal compression of both in-plane
axes: a uniform biaxial strain path); its packing is taken from PACKING (a prepared.restart)
and its sub-steps from the inertial-number rule, so that the replay must reproduce the rule's
counts. The CSV holds the states F_k of that test, F_{k+1} = e F_k with e = exp(-step) its
per-increment stretch, and the replay's increments F_{k+1} / F_k must then be e itself (checked
first: where a quotient rounds to another number the comparison would prove nothing). Every
column of history.csv the two share, and the summary's final and peak states and DEM work,
must be equal.
"""
import json
import math
import os
import shutil
import sys

from element_runs import element_test


def main():
    mpm_lig, base_file, packing, work = sys.argv[1:5]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    base = json.load(open(base_file))
    rve = base["rve"]
    del rve["preparation"]
    rve["restart_file"] = os.path.abspath(packing)
    rve["substeps"] = {"inertial_number": 1e-3, "min": 10}
    analysis = base["analysis"]
    assert analysis["test"] == "isotropic_compression" and rve["dimension"] == 2

    # The path as the element test computes it (element/strain_path.cpp, IsotropicPath).
    strain, increment = analysis["strain"], analysis["strain_increment"]
    n = max(1, math.ceil(strain / increment - 1e-9))
    e = math.exp(-(strain / n))
    states = [1.0]
    for _ in range(n):
        states.append(e * states[-1])
    bad = [k for k in range(n) if states[k + 1] / states[k] != e]
    if bad:
        sys.exit(f"premise: F_(k+1) / F_k rounds to another number than e at k = {bad}")
    table = os.path.join(work, "uniform_biaxial.csv")
    with open(table, "w") as f:
        f.write("# uniform biaxial compression, F = diag(e^k, e^k)\ntime,F11,F12,F21,F22\n")
        for k, F in enumerate(states):
            f.write(f"{repr(0.5 * k)},{repr(F)},0,0,{repr(F)}\n")

    reference, ref_summary, _ = element_test(mpm_lig, base, work, "computed")
    replayed_case = dict(base, analysis={"type": "element_test", "test": "recorded_path",
                                         "path": {"csv": table}})
    replayed, summary, _ = element_test(mpm_lig, replayed_case, work, "replayed")

    failures = []
    if len(replayed) != len(reference):
        failures.append(f"{len(replayed)} rows replayed, {len(reference)} computed")
    for k, (a, b) in enumerate(zip(reference, replayed)):
        for column, value in a.items():
            if b.get(column) != value:
                failures.append(f"row {k}: {column} computed {value}, replayed {b.get(column)}")
    for key in ("final", "peak", "dem_particle_steps", "increments",
                "peak_mobilised_friction_deg"):
        if summary[key] != ref_summary[key]:
            failures.append(f"summary {key}: computed {ref_summary[key]}, replayed {summary[key]}")
    substeps = sorted({r["substeps"] for r in reference[1:]})
    if failures:
        print("\n".join(failures[:20]))
        sys.exit(1)
    print(f"{n} increments bit-identical (sub-steps {', '.join(substeps)}; p "
          f"{float(reference[0]['p']):.0f} -> {float(reference[-1]['p']):.0f} Pa)")


main()
