#!/usr/bin/python3
"""A footing driven into damped soil says so once; undamped, or standing still, it does not.

usage: check_damped_footing_warning.py MPM_LIG CASE WORK_DIR [LAUNCHER ...]

CASE is a footing case with analysis.damping > 0 (cases/mpm/prandtl_tresca_penalty.json),
run for a few steps as it is (with LAUNCHER, e.g. `mpirun -np 2`, once only on rank 0), with
analysis.damping 0, and with its footing standing still.
"""
import json
import os
import subprocess
import sys

WARNING = "the local damping resists the soil's steady flow"


def stderr_of(exe, case, work, name, launcher=()):
    path = os.path.join(work, name + ".json")
    json.dump(case, open(path, "w"))
    r = subprocess.run([*launcher, exe, path, "--output", os.path.join(work, name), "--replace"],
                       stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if r.returncode != 0:
        sys.exit(f"FAIL: {name} ended with exit {r.returncode}: {r.stderr[-500:]}")
    return r.stderr


def main():
    exe, case_path, work, launcher = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]
    os.makedirs(work, exist_ok=True)
    case = json.load(open(case_path))
    case["analysis"]["end"] = {"steps": 5}
    failures = []
    damped = stderr_of(exe, case, work, "damped", launcher)
    if damped.count(WARNING) != 1 or "rigid_bodies[0]" not in damped:
        failures.append(f"the damped footing did not warn once naming rigid_bodies[0]: {damped!r}")
    still = json.loads(json.dumps(case))
    still["rigid_bodies"][0]["velocity"] = 0.0
    if WARNING in stderr_of(exe, still, work, "still"):
        failures.append("a footing standing still warned")
    case["analysis"]["damping"] = 0.0
    if WARNING in stderr_of(exe, case, work, "undamped"):
        failures.append("the undamped footing warned")
    for f in failures:
        print("FAIL:", f)
    if not failures:
        print("ok: warned once on the damped footing, not undamped nor standing still")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
