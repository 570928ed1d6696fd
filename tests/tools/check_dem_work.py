"""Checks of the per-point DEM work (results.h5 dem_particle_steps_m<ID>, summary.json
dem_work_shares) and of tools/plot_dem_work.py.

usage: check_dem_work.py CASE WORK_DIR [MPM_LIG]   (CASE: real | bad | below | stages | net)

real: the quick-start block with 50-disc RVEs for 10 steps at exactly 10 sub-steps: every
point's field is 40 x 10 x 10 particle-steps and the fields sum to the summary's total; with the
sub-steps capped at 10 all the work is at substeps.max, with "fixed": 10 none of it is (no cap);
the block, compressed at 0.3 m/s and confined at the preparation pressure, does no work at low
mean stress nor quiet. (The classes' closed forms: tests/coupling/test_dem_work.cpp.)
below: --below-strain on three synthetic points whose strain passes 1e-4 at known output steps
(one of them by shear alone): the work done before is 50 % of the total, all of it below 1e-3.
stages: --stages on a synthetic footing run whose work grows linearly with its settlement: the
work between two settlements is their share of it; a stage past the run's end, or --stages
without --case, is refused (exit 2).
net: --by-net-strain on a synthetic point that strains back and forth and one that shears on:
their shares of the work, the seen path over the net change and the work per unit of path.
"""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "plot_dem_work.py")
STEPS, GRAINS, SUBSTEPS = 10, 50, 10


def expect(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def run_case(work, mpm_lig, name, substeps):
    case = json.load(open(os.path.join(HERE, "..", "..", "cases", "quickstart.json")))
    case["analysis"]["end"] = {"steps": STEPS}
    case["output"] = {"every": 5, "history_every": 5}
    rve = case["materials"][0]["rve"]
    rve["grains"] = GRAINS
    rve["substeps"] = substeps
    path = os.path.join(work, f"{name}.json")
    json.dump(case, open(path, "w"), indent=1)
    out = os.path.join(work, name)
    r = subprocess.run([mpm_lig, path, "--output", out], capture_output=True, text=True)
    expect(r.returncode == 0, f"{name}: mpm_lig exit {r.returncode}: {r.stderr[-2000:]}")
    return out


def point_work(out):
    import h5py
    with h5py.File(os.path.join(out, "results.h5"), "r") as f:
        last = sorted(g for g in f if g.startswith("step_"))[-1]
        return f[last]["dem_particle_steps_m1"][()]


def real(work, mpm_lig):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    capped = run_case(work, mpm_lig, "capped", {"inertial_number": 1e-3, "min": SUBSTEPS,
                                                "max": SUBSTEPS})
    summary = json.load(open(os.path.join(capped, "summary.json")))
    work_per_point = point_work(capped)
    expect(len(work_per_point) == summary["rve_count"] == 32, "one value per point")
    expect(np.all(work_per_point == GRAINS * SUBSTEPS * STEPS),
           f"each point {GRAINS * SUBSTEPS * STEPS} particle-steps: {work_per_point}")
    expect(math.isclose(work_per_point.sum(), summary["dem_particle_steps"]), "sum = total")
    shares = summary["dem_work_shares"]
    expect(shares["at_substeps_max"] == 1.0, f"capped: all at substeps.max: {shares}")
    fixed = run_case(work, mpm_lig, "fixed", {"fixed": SUBSTEPS})
    shares = json.load(open(os.path.join(fixed, "summary.json")))["dem_work_shares"]
    expect(shares == {"at_substeps_max": 0.0, "strain_per_step_below_1e-5": 0.0,
                      "mean_stress_below_10_percent_of_preparation": 0.0},
           f"fixed sub-steps have no cap; the block is loaded: {shares}")
    expect(np.array_equal(point_work(fixed), work_per_point), "same steps, same work")
    r = subprocess.run([sys.executable, TOOL, capped, "-o", os.path.join(work, "map.png")],
                       capture_output=True, text=True)
    expect(r.returncode == 0, f"plot_dem_work exit {r.returncode}: {r.stderr}")
    expect("32 points" in r.stdout and "at substeps max: 100.0 %" in r.stdout, r.stdout)
    expect(os.path.getsize(os.path.join(work, "map.png")) > 5000, "picture written")


def bad(work):
    from synthetic import write_fields
    shutil.rmtree(work, ignore_errors=True)
    write_fields(work, [(0, 0.0, {"positions": np.zeros((3, 3)), "dem_substeps_m1": np.ones(3)})])
    r = subprocess.run([sys.executable, TOOL, work], capture_output=True, text=True)
    expect(r.returncode == 2 and "dem_particle_steps_m" in r.stderr, f"no field: {r.stderr}")
    r = subprocess.run([sys.executable, TOOL, os.path.join(work, "nowhere")], capture_output=True,
                       text=True)
    expect(r.returncode == 2 and "nowhere" in r.stderr, f"no folder: {r.stderr}")


def below(work):
    from synthetic import write_fields
    shutil.rmtree(work, ignore_errors=True)

    def voigt(*rows):
        return np.array(rows, dtype=float)

    positions = np.zeros((3, 3))
    shear = 1.2e-4 / math.sqrt(2.0)  # |ε| = 1.2e-4 from xy alone (0.85e-4 without the 2)
    steps = [
        (0, 0.0, {"positions": positions, "dem_particle_steps_m1": np.zeros(3),
                  "strain": np.zeros((3, 6))}),
        (10, 1.0, {"positions": positions, "dem_particle_steps_m1": np.array([10.0, 20.0, 30.0]),
                   "strain": voigt([5e-5, 0, 0, 0, 0, 0], [0, 0, 0, shear, 0, 0],
                                   [0, -5e-5, 0, 0, 0, 0])}),
        (20, 2.0, {"positions": positions, "dem_particle_steps_m1": np.array([30.0, 40.0, 50.0]),
                   "strain": voigt([2e-4, 0, 0, 0, 0, 0], [3e-4, 0, 0, 0, 0, 0],
                                   [0, -5e-5, 0, 0, 0, 0])}),
    ]
    write_fields(work, steps)
    r = subprocess.run([sys.executable, TOOL, work, "-o", os.path.join(work, "map.png"),
                        "--below-strain", "1e-4", "1e-3"], capture_output=True, text=True)
    expect(r.returncode == 0, f"plot_dem_work exit {r.returncode}: {r.stderr}")
    expect("|strain| < 0.0001: 50.0 % of the work" in r.stdout, r.stdout)
    expect("|strain| < 0.001: 100.0 % of the work" in r.stdout, r.stdout)


def stages(work):
    from synthetic import write_fields
    shutil.rmtree(work, ignore_errors=True)
    positions = np.zeros((2, 3))
    write_fields(work, [(k, 0.01 * k, {"positions": positions,
                                       "dem_particle_steps_m1": np.array([2.0, 4.0]) * k})
                        for k in (0, 10, 20)])
    with open(os.path.join(work, "history.csv"), "w") as f:  # s/B = step / 100 (B = 0.2 m)
        f.write("step,time,settlement\n" + "".join(f"{k},{0.01 * k},{0.002 * k}\n"
                                                   for k in range(21)))
    case = os.path.join(work, "case.json")
    with open(case, "w") as f:
        json.dump({"rigid_bodies": [{"type": "footing", "center": [0.0], "width": [0.2],
                                     "base": 1.0}]}, f)
    tool = [sys.executable, TOOL, work, "-o", os.path.join(work, "map.png")]
    r = subprocess.run(tool + ["--stages", "0", "0.05", "0.2", "--case", case],
                       capture_output=True, text=True)
    expect(r.returncode == 0, f"plot_dem_work exit {r.returncode}: {r.stderr}")
    expect("s/B 0 to 0.05: 30 particle-steps (25.0 % of the work)" in r.stdout, r.stdout)
    expect("s/B 0.05 to 0.2: 90 particle-steps (75.0 % of the work)" in r.stdout, r.stdout)
    r = subprocess.run(tool + ["--stages", "0", "0.3", "--case", case], capture_output=True,
                       text=True)
    expect(r.returncode == 2 and "before 0.3" in r.stderr, f"past the end: {r.stderr}")
    r = subprocess.run(tool + ["--stages", "0", "0.1"], capture_output=True, text=True)
    expect(r.returncode == 2 and "--case" in r.stderr, f"no case: {r.stderr}")


def net(work):
    from synthetic import write_fields
    shutil.rmtree(work, ignore_errors=True)
    positions = np.zeros((2, 3))
    # Point 0 strains back and forth (net 0.002 over a seen path of 0.006); point 1 shears on
    # (0.1 per output step): 600 and 300 particle-steps from step 10 on, 50 each before.
    swing, shear = (0.0, 0.0, 0.002, 0.0, 0.002), (0.0, 0.0, 0.1, 0.2, 0.3)
    frames = []
    for k, (a, b) in enumerate(zip(swing, shear)):
        strain = np.zeros((2, 6))
        strain[0, 0], strain[1, 3] = a, b / math.sqrt(2.0)
        done = np.array([50.0, 50.0]) + (np.array([200.0, 100.0]) * (k - 1) if k else -50.0)
        frames.append((10 * k, 0.01 * k, {"positions": positions, "strain": strain,
                                          "dem_particle_steps_m1": done}))
    write_fields(work, frames)
    tool = [sys.executable, TOOL, work, "-o", os.path.join(work, "map.png")]
    r = subprocess.run(tool + ["--by-net-strain", "10"], capture_output=True, text=True)
    expect(r.returncode == 0, f"plot_dem_work exit {r.returncode}: {r.stderr}")
    expect("0 to 0.01: 1 points, 66.7 % of the work, path / net 3, 1e+05 particle-steps per "
           "unit path" in r.stdout, r.stdout)
    expect("0.2 to inf: 1 points, 33.3 % of the work, path / net 1, 1e+03 particle-steps per "
           "unit path" in r.stdout, r.stdout)
    r = subprocess.run(tool + ["--by-net-strain", "40"], capture_output=True, text=True)
    expect(r.returncode == 2 and "--by-net-strain 40" in r.stderr, f"one step: {r.stderr}")


if __name__ == "__main__":
    case, work = sys.argv[1], os.path.join(sys.argv[2], sys.argv[1])
    {"real": real, "bad": bad, "below": below, "stages": stages, "net": net}[case](work, *sys.argv[3:])
    print(f"{case}: ok")
