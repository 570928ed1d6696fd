#!/usr/bin/python3
"""The sheared pace took over where the case says and only there: RUN (the case CASE, with
rve.substeps.sheared) and OFF (the same case without it) have bit-identical history rows until
the net shear strain the RVEs have run nears sheared.shear_strain (the column shears at the rate its top
row's velocity over its height sets), rows that differ soon after, and RUN did less DEM work.

usage: check_sheared_pace.py CASE RUN OFF
"""
import csv
import json
import math
import sys


def rows(run):
    with open(run + "/history.csv") as f:
        return list(csv.reader(f))


def main():
    case, run, off = sys.argv[1:4]
    c = json.load(open(case))
    sheared = c["materials"][0]["rve"]["substeps"]["sheared"]["shear_strain"]
    # v_x = rate * y (the case's _setup): γ = rate * dt a step. A point's own γ is the
    # column's to within the MPM's noise: 10 % either side of the step the column reaches it.
    top = max(b["velocity"] for b in c["boundary_conditions"] if b["type"] == "velocity")
    per_step = top / c["mesh"]["size"][1] * c["analysis"]["time_step"]["fixed"]
    switch = sheared / per_step
    before, after = math.floor(0.9 * switch), math.ceil(1.1 * switch)
    a, b = rows(run), rows(off)  # row k + 1 is step k
    problems = []
    if a[: before + 2] != b[: before + 2]:
        problems.append(f"history rows differ by step {before}")
    if a[after + 1] == b[after + 1]:
        problems.append(f"history row of step {after} is that without the pace")
    work = [json.load(open(r + "/summary.json"))["dem_particle_steps"] for r in (run, off)]
    if not work[0] < work[1]:
        problems.append(f"DEM work {work[0]:.4g} not below {work[1]:.4g} without the pace")
    print(f"identical through step {before}, not at {after} (γ {sheared} at {per_step:g} a step); "
          f"particle-steps {work[0]:.4g} against {work[1]:.4g} ({work[0] / work[1]:.3f})")
    if problems:
        print("\n".join(problems))
        sys.exit(1)


main()
