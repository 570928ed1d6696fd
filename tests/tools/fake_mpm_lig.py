#!/usr/bin/python3
"""A stand-in for mpm_lig with known answers, for check_accuracy_cost.py.

    fake_mpm_lig.py --validate CASE      exit 2 naming rve.grains when it is not positive
    fake_mpm_lig.py CASE --output DIR    a footing history and summary from the case's knobs

With I = rve.substeps.inertial_number, g = rve.grains and s = rve.seed:
    q/q_s = 10 (1 + 10 I) + 0.1 (s - 2) + (0.05 if g == 200), constant over s/B in [0, 0.5]
    particle-steps = g x 100 / I; stepping takes particle-steps / 1e6 s (8e5 when g == 200),
    plus 1 s of packing preparation. Each run appends the case path to $FAKE_MPM_LIG_LOG.

An element test (analysis.type element_test) is a drained biaxial test to 5 % axial strain
(51 rows) at s3 = 100 kPa whose friction angle phi = 25 + 100 I + 0.5 (s - 2) deg and dilatancy
angle psi = 10 I + 0.02 (s - 2) deg hold from the start (near zero: a relative error of psi
means nothing).

With $FAKE_MPM_LIG_BLOCK set, a run writes its pid to that file and then waits for a signal
(at most 120 s, then exit 3): a run that Ctrl-C must stop.
"""
import json
import math
import os
import signal
import sys
import time


def element_history(case, out, s3=1e5):
    inertial = case["rve"]["substeps"]["inertial_number"]
    seed = case["rve"]["seed"]
    phi = math.radians(25 + 100 * inertial + 0.5 * (seed - 2))
    sin_psi = math.sin(math.radians(10 * inertial + 0.02 * (seed - 2)))
    slope = -2 * sin_psi / (1 - sin_psi)  # d e_v / d e_1, compression positive
    s1 = s3 * (1 + math.sin(phi)) / (1 - math.sin(phi))
    with open(os.path.join(out, "history.csv"), "w") as f:
        f.write("step,time,e_xx,e_yy,e_zz,e_xy,e_xz,e_yz,e_vol,s_xx,s_yy,s_zz,s_xy,s_xz,s_yz,"
                "p,q,void_ratio\n")
        for k in range(51):
            e1 = 0.001 * k
            ev = slope * e1
            f.write(",".join(f"{v!r}" for v in (k, 0.01 * k, e1 - ev, -e1, 0.0, 0.0, 0.0, 0.0,
                                                 -ev, -s3, -s1, 0.0, 0.0, 0.0, 0.0,
                                                 (s1 + s3) / 2, s1 - s3, 0.2)) + "\n")


def main():
    args = sys.argv[1:]
    if args[0] == "--validate":
        case = json.load(open(args[1]))
        if case["rve"]["grains"] <= 0:
            print(f"mpm_lig: {args[1]}: rve.grains: must be > 0", file=sys.stderr)
            return 2
        print("valid")
        return 0
    case_path, out = args[0], args[args.index("--output") + 1]
    case = json.load(open(case_path))
    if os.environ.get("FAKE_MPM_LIG_LOG"):
        with open(os.environ["FAKE_MPM_LIG_LOG"], "a") as log:
            log.write(case_path + "\n")
    if os.environ.get("FAKE_MPM_LIG_BLOCK"):
        signal.signal(signal.SIGINT, signal.SIG_DFL)
        # A temporary of its own: two runs started together must not rename each other's.
        temporary = f"{os.environ['FAKE_MPM_LIG_BLOCK']}.{os.getpid()}.tmp"
        with open(temporary, "w") as marker:
            marker.write(f"{os.getpid()}\n")
        os.replace(temporary, os.environ["FAKE_MPM_LIG_BLOCK"])
        time.sleep(120)
        return 3
    rve = case["rve"]
    os.makedirs(out, exist_ok=True)
    if case.get("analysis", {}).get("type") == "element_test":
        element_history(case, out)
        particle_steps = rve["grains"] * 100 / rve["substeps"]["inertial_number"]
        with open(os.path.join(out, "summary.json"), "w") as f:
            json.dump({"wall_seconds": 1.0 + particle_steps / 1e6, "ranks": 1, "rve_count": 1,
                       "mpm_steps": 50, "dem_particle_steps": particle_steps,
                       "time_split": {"preparation": 1.0}}, f)
        return 0
    rate = 8e5 if rve["grains"] == 200 else 1e6
    inertial = rve["substeps"]["inertial_number"]
    ratio = (10 * (1 + 10 * inertial) + 0.1 * (rve["seed"] - 2)
             + (0.05 if rve["grains"] == 200 else 0))
    surcharge = abs(case["boundary_conditions"][0]["traction"][-1])
    width = case["rigid_bodies"][0]["width"][0]
    with open(os.path.join(out, "history.csv"), "w") as f:
        f.write("step,settlement,q\n")
        for k in range(51):
            f.write(f"{k},{0.01 * k * width:.17g},{ratio * surcharge:.17g}\n")
    particle_steps = rve["grains"] * 100 / inertial
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump({"wall_seconds": 1.0 + particle_steps / rate, "ranks": 1, "rve_count": 1,
                   "mpm_steps": 50, "dem_particle_steps": particle_steps,
                   "time_split": {"preparation": 1.0, "output": 0.0}}, f)
    return 0


if __name__ == "__main__":
    sys.exit(main())
