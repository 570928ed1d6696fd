#!/usr/bin/python3
"""Steady flow did answer flowing points and checked them: summary.json's steady_flow block of
RUN has flows begun, predicted updates, checks and finite errors; the DEM work of RUN is below
that of OFF, the same case without steady flow; every OTHER run reports the same block (decisions independent of the rank count).

usage: check_steady_flow.py RUN OFF [OTHER...]
"""
import json
import math
import sys


def summary(run):
    return json.load(open(run + "/summary.json"))


def main():
    run, off = summary(sys.argv[1]), summary(sys.argv[2])
    f = run["steady_flow"]
    problems = []
    if not f["flows_begun"] >= 1:
        problems.append("no flow began")
    if not f["predicted_updates"] > 0:
        problems.append("no stress was answered from a flow")
    if not f["checks"] > 0:
        problems.append("no flow was checked against a DEM update")
    if not f["skipped_shear_strain"] > 0:
        problems.append("no shear strain was skipped")
    if not (math.isfinite(f["max_error"]) and 0 <= f["mean_error"] <= f["max_error"]):
        problems.append(f"errors mean {f['mean_error']} max {f['max_error']}")
    if "steady_flow" in off:
        problems.append(f"{sys.argv[2]} is not a run without steady flow")
    if not run["dem_particle_steps"] < off["dem_particle_steps"]:
        problems.append(f"DEM work {run['dem_particle_steps']:.4g} not below "
                        f"{off['dem_particle_steps']:.4g} without steady flow")
    for other in sys.argv[3:]:
        if summary(other)["steady_flow"] != f:
            problems.append(f"{other}: steady_flow {summary(other)['steady_flow']} differs")
    print(json.dumps(f), f"particle-steps {run['dem_particle_steps']:.4g} "
          f"(without: {off['dem_particle_steps']:.4g})")
    if problems:
        print("\n".join(problems))
        sys.exit(1)


main()
