"""Checks of tools/cost_projection.py on synthetic run summaries with known answers.

usage: check_cost_projection.py CASE WORK_DIR   (CASE: steps | time | ranks | fixed | bad)
"""
import json
import math
import os
import shutil
import subprocess
import sys

TOOL = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools",
                    "cost_projection.py")


def expect(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def close(a, b, what):
    expect(math.isclose(a, b, rel_tol=1e-12), f"{what}: {a} != {b}")


def write(path, data):
    with open(path, "w") as f:
        json.dump(data, f)


def dem_case(size, cells, box_max, ppc, grains, end):
    return {"dimension": 2, "analysis": {"type": "mpm", "end": end},
            "mesh": {"origin": [0, 0], "size": size, "cells": cells},
            "materials": [{"id": 1, "type": "dem_rve", "rve": {"grains": grains}}],
            "bodies": [{"material": 1, "box": {"min": [0, 0], "max": box_max},
                        "points_per_cell": ppc}]}


def measured_run(work, name, ranks, wall, prep, output, rves, steps, substeps, grains, dt):
    """A run directory whose stepping took wall - prep - output seconds on `ranks` cores."""
    d = os.path.join(work, name)
    os.makedirs(d)
    write(os.path.join(d, "summary.json"),
          {"wall_seconds": wall, "ranks": ranks, "rve_count": rves, "mpm_steps": steps,
           "dem_particle_steps": float(rves * grains * substeps * steps), "time_step": dt,
           "time_split": {"preparation": prep, "output": output, "dem": 0.9 * (wall - prep),
                          "communication": 0.0, "mpm": 0.0}})
    return d


def run(*args):
    r = subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    sys.stderr.write(r.stderr)
    return r


def setup(work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    # Run A: 32 RVEs (4 x 8 cells of h = 0.1, 1 point per cell) of 100 grains, 50 sub-steps,
    # 100 steps on 2 ranks, 100 s of stepping: 1.6e7 particle-steps -> 8e4 per core and second.
    a = measured_run(work, "a", 2, 110.0, 8.0, 2.0, 32, 100, 50, 100, 1e-3)
    write(os.path.join(work, "a.json"),
          dem_case([0.4, 0.8], [4, 8], [0.4, 0.8], 1, 100, {"steps": 100}))
    # Run B: faster (4e5 per core) and fewer sub-steps (20); no case file.
    b = measured_run(work, "b", 1, 81.0, 1.0, 0.0, 20, 200, 20, 400, 1e-3)
    return a, os.path.join(work, "a.json"), b


def steps(work):
    a, a_case, b = setup(work)
    # Target: 10 x 10 cells of h = 0.1, soil 10 x 5 cells, 2 points per cell and axis:
    # 200 RVEs of 400 grains, 1000 steps.
    target = os.path.join(work, "target.json")
    write(target, dem_case([1.0, 1.0], [10, 10], [1.0, 0.5], 2, 400, {"steps": 1000}))
    out = os.path.join(work, "projection.json")
    r = run(target, "--run", a, a_case, "--run", b, "--json", out)
    expect(r.returncode == 0, f"exit code {r.returncode}")
    res = json.load(open(out))
    ma, mb = res["measured"]
    close(ma["particle_steps_per_s_per_core"], 8e4, "rate of run a")
    close(ma["core_seconds_per_mpm_step_per_rve"], 200.0 / (100 * 32), "core-s/step/RVE of a")
    close(ma["mean_substeps"], 50.0, "mean sub-steps of a")
    close(mb["particle_steps_per_s_per_core"], 20 * 400 * 20 * 200 / 80.0, "rate of run b")
    expect("mean_substeps" not in mb, "sub-steps reported without a case file")
    p = res["projection"]
    expect(p["rve_count"] == 200 and p["mpm_steps"] == 1000, f"size {p}")
    rate = min(8e4, 20 * 400 * 20 * 200 / 80.0)
    close(p["particle_steps_per_s_per_core"], rate, "slowest rate chosen")
    close(p["core_seconds_per_mpm_step"], 200 * 400 * 50 / rate, "core-s per step")
    close(p["core_hours"], 200 * 400 * 50 / rate * 1000 / 3600, "core-hours")
    expect("assumes" in r.stdout and "core-hours" in r.stdout, "assumptions printed")


def time(work):
    a, a_case, _ = setup(work)
    # End given as a time: the CFL step 1e-3 s of run a (h = 0.1) scaled to h = 0.05 is 5e-4 s,
    # so 0.5 s are 1000 steps; sub-steps and rate given explicitly.
    target = os.path.join(work, "target.json")
    write(target, dem_case([1.0, 1.0], [20, 20], [1.0, 1.0], 1, 400, {"time": 0.5}))
    out = os.path.join(work, "projection.json")
    r = run(target, "--run", a, a_case, "--substeps", "30", "--rate", "2e6", "--json", out)
    expect(r.returncode == 0, f"exit code {r.returncode}")
    p = json.load(open(out))["projection"]
    expect(p["rve_count"] == 400 and p["mpm_steps"] == 1000, f"size {p}")
    close(p["core_seconds_per_mpm_step_per_rve"], 400 * 30 / 2e6, "core-s per step per RVE")
    close(p["core_hours"], 400 * 400 * 30 / 2e6 * 1000 / 3600, "core-hours")


def ranks(work):
    a, a_case, _ = setup(work)
    # 200 RVEs (as in `steps`) on 64, 200 and 256 ranks at a stepping efficiency of 0.8: the
    # busiest rank holds ceil(200 / N) RVEs, 4, 1 and 1, so the granularity is 200 / (64 * 4),
    # 1 and 200 / 256; wall = core-hours / (N * granularity * 0.8).
    target = os.path.join(work, "target.json")
    write(target, dem_case([1.0, 1.0], [10, 10], [1.0, 0.5], 2, 400, {"steps": 1000}))
    out = os.path.join(work, "projection.json")
    r = run(target, "--run", a, a_case, "--ranks", "64", "200", "256", "--efficiency", "0.8",
            "--json", out)
    expect(r.returncode == 0, f"exit code {r.returncode}")
    res = json.load(open(out))
    core_hours = 200 * 400 * 50 / 8e4 * 1000 / 3600
    for row, n, busiest in zip(res["ranks"], (64, 200, 256), (4, 1, 1)):
        granularity = 200 / (n * busiest)
        expect(row["ranks"] == n, f"rank counts {res['ranks']}")
        close(row["granularity"], granularity, f"granularity at {n}")
        close(row["wall_hours"], core_hours / (n * granularity * 0.8), f"wall at {n}")
        close(row["charged_core_hours"], core_hours / (granularity * 0.8), f"charged at {n}")
    expect("256 ranks" in r.stdout, "rank rows printed")
    for args, word in ((["--efficiency", "1.5"], "--efficiency"), (["--ranks", "0"], "--ranks")):
        r = run(target, "--run", a, a_case, *args)
        expect(r.returncode == 2 and word in r.stderr, f"{args}: exit {r.returncode}")


def fixed(work):
    a, a_case, b = setup(work)
    # Run a did 50 sub-steps per update, one update per RVE and step, at 8e4 particle-steps per
    # core-second; with 10 DEM steps of fixed cost per update that is 8e4 * 60 / 50 step
    # equivalents. A setting measured on a smaller case: 0.4 of its shipped run's particle-steps,
    # and 0.1 of its DEM updates (quiet points predict the rest).
    shipped, quiet = os.path.join(work, "shipped"), os.path.join(work, "quiet")
    os.makedirs(shipped)
    os.makedirs(quiet)
    write(os.path.join(shipped, "summary.json"),
          {"dem_particle_steps": 5e8, "rve_count": 10, "mpm_steps": 1000})
    write(os.path.join(quiet, "summary.json"),
          {"dem_particle_steps": 2e8, "rve_count": 10, "mpm_steps": 1000,
           "quiet_points": {"dem_updates": 1000, "predicted_updates": 9000}})
    target = os.path.join(work, "target.json")
    write(target, dem_case([1.0, 1.0], [10, 10], [1.0, 0.5], 2, 400, {"steps": 1000}))
    out = os.path.join(work, "projection.json")
    r = run(target, "--run", a, a_case, "--substeps", "100", "--fixed-steps", "10", "2",
            "--setting", shipped, quiet, "--json", out)
    expect(r.returncode == 0, f"exit code {r.returncode}")
    p = json.load(open(out))["projection"]
    rate = 8e4 * 60 / 50
    close(p["particle_steps_per_s_per_core"], 8e4, "the measured rate")
    close(p["step_equivalents_per_s_per_core"], rate, "rate with the fixed cost")
    close(p["setting"]["particle_steps_ratio"], 0.4, "particle-step ratio")
    close(p["setting"]["dem_updates_ratio"], 0.1, "DEM update ratio")
    close(p["core_seconds_per_mpm_step"], 200 * 400 * (100 * 0.4 + 2 * 0.1) / rate,
          "core-s per step at the setting")
    # Without the setting and with the same fixed cost for the target: every update pays 10.
    r = run(target, "--run", a, a_case, "--substeps", "100", "--fixed-steps", "10", "--json", out)
    p = json.load(open(out))["projection"]
    close(p["core_seconds_per_mpm_step"], 200 * 400 * 110 / rate, "core-s per step, shipped")
    # Steady flow alone predicts updates too: 10000 - 2500.
    write(os.path.join(quiet, "summary.json"),
          {"dem_particle_steps": 2e8, "rve_count": 10, "mpm_steps": 1000,
           "steady_flow": {"predicted_updates": 2500}})
    r = run(target, "--run", a, a_case, "--setting", shipped, quiet, "--json", out)
    close(json.load(open(out))["projection"]["setting"]["dem_updates_ratio"], 0.75,
          "updates predicted by steady flow")
    # The rate of a run without its case file cannot be split; bad counts are refused.
    for args, word in ((["--run", b, "--fixed-steps", "10"], "case file"),
                       (["--run", a, a_case, "--fixed-steps", "1", "2", "3"], "--fixed-steps"),
                       (["--run", a, a_case, "--fixed-steps", "-1"], "--fixed-steps"),
                       (["--run", a, a_case, "--fixed-steps", "nan"], "--fixed-steps")):
        r = run(target, *args)
        expect(r.returncode == 2 and word in r.stderr, f"{args}: exit {r.returncode} {r.stderr}")


def bad(work):
    a, a_case, _ = setup(work)
    s = json.load(open(os.path.join(a, "summary.json")))
    del s["dem_particle_steps"]
    write(os.path.join(a, "summary.json"), s)
    r = run(a_case, "--run", a)
    expect(r.returncode == 2, f"exit code {r.returncode}, expected 2")
    expect("dem_particle_steps" in r.stderr, "missing key not named")


if __name__ == "__main__":
    case, work = sys.argv[1], sys.argv[2]
    {"steps": steps, "time": time, "ranks": ranks, "fixed": fixed, "bad": bad}[case](os.path.join(work, case))
    print(f"{case}: ok")
