#!/usr/bin/python3
"""Points started as their packing's continuum and switched to DEM: summary.json's
start_as_continuum block of RUN (a run of CASE) has consistent counts and finite jumps; with --exceeded, the
jump bound was passed and the thresholds were halved, without, no jump passed it; every OTHER
run reports the same block (the decisions do not depend on the rank count).

usage: check_continuum_start.py CASE.json [--exceeded] RUN [OTHER...]
"""
import json
import math
import sys


def block(run):
    return json.load(open(run + "/summary.json"))["start_as_continuum"]


def main():
    case = json.load(open(sys.argv[1]))
    args = sys.argv[2:]
    exceeded = "--exceeded" in args
    runs = [a for a in args if a != "--exceeded"]
    s = block(runs[0])
    bound = case["materials"][0]["start_as_continuum"]["max_jump"]
    problems = []
    if not s["continuum_updates"] > 0:
        problems.append("no point was ever continuum")
    if not s["switched_points"] > 0:
        problems.append("no point switched to DEM")
    if not (math.isfinite(s["max_jump"]) and 0 < s["mean_jump"] <= s["max_jump"]):
        problems.append(f"jumps mean {s['mean_jump']} max {s['max_jump']}")
    if exceeded:
        if not (s["jumps_above_max_jump"] > 0 and s["max_jump"] > bound):
            problems.append(f"no jump above the bound {bound}")
        halved = max(0.5 ** s["jumps_above_max_jump"], 1.0 / 64.0)  # the scale stops at 1/64
        if not abs(s["threshold_scale"] - halved) <= 1e-12:
            problems.append(f"threshold_scale {s['threshold_scale']} not halved per jump")
    elif s["jumps_above_max_jump"] != 0 or s["max_jump"] > bound or s["threshold_scale"] != 1:
        problems.append(f"a jump passed the bound {bound}: {s}")
    for other in runs[1:]:
        if block(other) != s:
            problems.append(f"{other}: start_as_continuum {block(other)} differs from {s}")
    print(json.dumps(s))
    if problems:
        print("\n".join(problems))
        sys.exit(1)


main()
