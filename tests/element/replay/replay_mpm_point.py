#!/usr/bin/python3
"""A material point of an MPM x DEM run, replayed as an element test, gives that point's
stresses bit for bit.

usage: replay_mpm_point.py MPM_LIG CASE WORK_DIR

1. Runs CASE (fields and output.deformation_gradient every step) into WORK_DIR/mpm.
2. For points 0 and 3 (one of each packing) writes an element test whose RVE is the run's
   `rve` node on the point's packing file (packings/m<id>/packing_<k>.restart, k = point mod
   packings: one body, one material) and whose path is the point in results.h5 with the
   run's own sub-step counts ("substeps": "recorded"); runs it.
3. history.csv against the point in results.h5, every step: the normal stresses and the DEM
   sub-steps (dem_substeps_m<id>) bit for bit, the shear stresses to one unit in the last
   place (results.h5 holds the symmetric part), path_time = the step's time, strain e_* to
   1e-15.
4. The same point from a CSV of its F and sub-steps alone (ΔF = F_{k+1} F_k^-1 instead of
   the recorded increments): stresses within REPLAY_FROM_F_TOLERANCE of p0 (see there).
5. The same point with the sub-step rule of the element test ("substeps": "rule", the
   default): the first update differs (see FIRST_UPDATE), the stresses stay within
   RULE_TOLERANCE of p0 of the run's.
"""
import csv
import json
import os
import shutil
import sys

import h5py
import numpy as np

from element_runs import run

# A replay from F alone applies increments that differ from the run's by round-off (F_{k+1}
# was rounded when the run computed dF F_k, so F_{k+1} F_k^-1 is not dF bit for bit: about
# 1e-16 relative); the DEM packing amplifies such differences. Measured on this case over 12
# steps: 6.1e-14 and 9.3e-14 p0 (points 0 and 3); the bound leaves a factor 10 for other
# compilers' round-off.
REPLAY_FROM_F_TOLERANCE = 1e-12
# FIRST_UPDATE: the coupling clones a point's RVE and deforms it without reading its stress
# first, so the rule counts the first update at substeps.pressure_floor (1 kPa: about 10 times
# the steps at p0 = 100 kPa); an element test reads the prepared packing first, so with its
# own rule the first update runs at p0's count. The same strain at another rate: measured
# here 1.2 % and 2.7 % of p0 at most over 12 steps; the bound says the path is the same.
RULE_TOLERANCE = 0.05

VOIGT = ["xx", "yy", "zz", "xy", "xz", "yz"]


def history(out):
    with open(os.path.join(out, "history.csv")) as f:
        return list(csv.DictReader(f))


def replay(mpm_lig, case, material, point, work, path):
    """Runs the element test of `point` along `path` (the analysis.path node) on its packing."""
    rve = dict(material["rve"])
    del rve["preparation"]
    packing = point % material.get("packings", 1)
    rve["restart_file"] = os.path.join(work, "mpm", "packings", f"m{material['id']}",
                                       f"packing_{packing}.restart")
    name = f"replay_{point}_" + ("csv" if "csv" in path else path.get("substeps", "rule"))
    replay_case = {"title": f"replay of point {point}", "rve": rve,
                   "analysis": {"type": "element_test", "test": "recorded_path", "path": path}}
    case_file = os.path.join(work, name + ".json")
    with open(case_file, "w") as f:
        json.dump(replay_case, f, indent=1)
    out = os.path.join(work, name)
    run([mpm_lig, case_file, "--output", out], out + ".log")
    return history(out)


def main():
    mpm_lig, case_file, work = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = json.load(open(case_file))
    material = case["materials"][0]
    run([mpm_lig, case_file, "--output", os.path.join(work, "mpm")], os.path.join(work, "mpm.log"))
    results = h5py.File(os.path.join(work, "mpm", "results.h5"), "r")
    steps = sorted(results, key=lambda g: results[g].attrs["step"])
    substeps_field = f"dem_substeps_m{material['id']}"
    failures = []
    for point in (0, 3):
        found = len(failures)
        rows = replay(mpm_lig, case, material, point, work,
                      {"results": os.path.join(work, "mpm", "results.h5"), "point": point,
                       "substeps": "recorded"})
        if len(rows) != len(steps):
            failures.append(f"point {point}: {len(rows)} history rows for {len(steps)} steps")
            continue
        p0 = -0.5 * (results[steps[0]]["stress"][point][0] + results[steps[0]]["stress"][point][1])
        for k, (row, group) in enumerate(zip(rows, steps)):
            g = results[group]
            stress = g["stress"][point]
            replayed = np.array([float(row["s_" + c]) for c in VOIGT])
            # results.h5 stores the symmetric part of σ, history.csv σ itself: σ = Q σ_rve Qᵀ
            # is symmetric only to round-off, so a shear component may differ in its last bit
            # (measured: one unit in the last place at 7 of 24 steps, the normal components
            # never). The RVEs are the same bit for bit: any difference in their state would
            # grow in the steps after, and the normal components stay equal.
            ulps = np.abs(replayed - stress) / np.spacing(np.abs(stress))
            if not np.array_equal(replayed[:3], stress[:3]) or ulps[3:].max() > 1:
                failures.append(f"point {point} {group}: stress {replayed!r} != run's {stress!r}")
            strain = np.array([float(row["e_" + c]) for c in VOIGT])
            # results.h5 writes the symmetric part of ln V, history.csv ln V itself: its shear
            # components may differ in the last bit.
            if np.abs(strain - g["strain"][point]).max() > 1e-15:
                failures.append(f"point {point} {group}: strain {strain} != {g['strain'][point]}")
            if float(row["path_time"]) != g.attrs["time"]:
                failures.append(f"point {point} {group}: path_time {row['path_time']}")
            if k > 0 and float(row["substeps"]) != g[substeps_field][point]:
                failures.append(f"point {point} {group}: {row['substeps']} DEM steps, the run "
                                f"{g[substeps_field][point]}")
        loaded = max(abs(float(r["p"]) - p0) for r in rows)
        if loaded < 0.01 * p0:
            failures.append(f"point {point}: p changed by {loaded} only: the path loads nothing")

        # From F alone (and the run's sub-steps), through a CSV file.
        table = os.path.join(work, f"point_{point}.csv")
        with open(table, "w") as f:
            f.write("time,F11,F12,F21,F22,substeps\n")
            for group in steps:
                F = results[group]["deformation_gradient"][point]
                values = [results[group].attrs["time"], F[0], F[1], F[3], F[4]]
                f.write(",".join(repr(float(v)) for v in values) +
                        f",{int(results[group][substeps_field][point])}\n")
        from_f = replay(mpm_lig, case, material, point, work, {"csv": table})
        from_f_error = max(abs(float(a["s_" + c]) - float(b["s_" + c]))
                           for a, b in zip(from_f, rows) for c in VOIGT) / p0
        if from_f_error > REPLAY_FROM_F_TOLERANCE:
            failures.append(f"point {point}: replay from F strays {from_f_error:.3g} p0")

        # The element test's own sub-step rule.
        ruled = replay(mpm_lig, case, material, point, work,
                       {"results": os.path.join(work, "mpm", "results.h5"), "point": point})
        rule_error = max(abs(float(a["s_" + c]) - float(b["s_" + c]))
                         for a, b in zip(ruled, rows) for c in VOIGT) / p0
        first = (ruled[1]["substeps"], rows[1]["substeps"])
        if rule_error > RULE_TOLERANCE:
            failures.append(f"point {point}: with the rule the stress strays {rule_error:.3g} p0")
        if len(failures) == found:
            print(f"point {point}: {len(rows) - 1} steps bit-identical (p {p0:.0f} -> "
                  f"{float(rows[-1]['p']):.0f} Pa); from F alone within {from_f_error:.3g} p0; "
                  f"with the rule within {rule_error:.3g} p0 (first update {first[0]} DEM "
                  f"steps, the run {first[1]})")
    if failures:
        print("\n".join(failures))
        sys.exit(1)


main()
