#!/usr/bin/python3
"""Quiet points did predict and check: summary.json's quiet_points block of RUN has predicted
updates, DEM updates and checks, consistent counts and finite errors; every OTHER run reports
the same block (the decisions do not depend on the rank count).

usage: check_quiet_points.py RUN [OTHER...]
"""
import json
import math
import sys


def block(run):
    return json.load(open(run + "/summary.json"))["quiet_points"]


def main():
    q = block(sys.argv[1])
    problems = []
    if not q["predicted_updates"] > 0:
        problems.append("no stress was predicted")
    if not q["checks"] > 0:
        problems.append("no prediction was checked against a DEM update")
    if q["checks"] > q["dem_updates"]:
        problems.append("more checks than DEM updates")
    share = q["predicted_updates"] / (q["predicted_updates"] + q["dem_updates"])
    if abs(share - q["predicted_share"]) > 1e-12:
        problems.append(f"predicted_share {q['predicted_share']} is not {share}")
    if not (math.isfinite(q["max_error"]) and 0 <= q["mean_error"] <= q["max_error"]):
        problems.append(f"errors mean {q['mean_error']} max {q['max_error']}")
    for other in sys.argv[2:]:
        if block(other) != q:
            problems.append(f"{other}: quiet_points {block(other)} differ from {q}")
    print(json.dumps(q))
    if problems:
        print("\n".join(problems))
        sys.exit(1)


main()
