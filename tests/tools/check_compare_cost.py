"""Checks of tools/compare_cost.py on footing runs of known load curves: the particle-steps ratio
and the plateau / peak errors against the reference; with --sets, each setting's signed errors
against its own set's reference, the sets' scatter and the verdicts; bad input (exit 2, named).

usage: check_compare_cost.py WORK_DIR"""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "compare_cost.py")
CASE = {"analysis": {"type": "mpm"}, "rigid_bodies": [{"type": "footing", "width": [0.2]}],
        "boundary_conditions": [{"type": "traction", "traction": [0, -1e5]}]}


def expect(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def footing_run(d, level, peak, particle_steps, rows=51):
    """q/q_s = level at s/B = 0.005, 0.015, ... (`rows` of them: to 0.505 by default) except
    `peak` at s/B = 0.205 (no row on the plateau window's ends: 30 rows inside it)."""
    os.makedirs(d)
    with open(os.path.join(d, "history.csv"), "w") as f:
        f.write("step,settlement,q\n")
        for k in range(rows):
            s_over_b = 0.005 + 0.01 * k
            ratio = peak if k == 20 else level
            f.write(f"{k},{s_over_b * 0.2!r},{ratio * 1e5!r}\n")
    with open(os.path.join(d, "summary.json"), "w") as f:
        json.dump({"dem_particle_steps": particle_steps, "wall_seconds": 1.0}, f)


def main():
    work = sys.argv[1]
    shutil.rmtree(work, ignore_errors=True)
    footing_run(os.path.join(work, "ref"), 10.0, 12.0, 1e9)
    footing_run(os.path.join(work, "cheap"), 10.3, 12.6, 2e8)
    with open(os.path.join(work, "ref", "case.json"), "w") as f:
        json.dump(CASE, f)
    out = os.path.join(work, "out.json")
    r = subprocess.run(["/usr/bin/python3", TOOL, os.path.join(work, "ref"),
                        os.path.join(work, "cheap"), "--json", out], capture_output=True, text=True)
    expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    rows = json.load(open(out))
    cheap = rows[1]
    expect(abs(cheap["particle_steps_ratio"] - 0.2) < 1e-12, f"ratio {cheap['particle_steps_ratio']}")
    ref_plateau = (29 * 10.0 + 12.0) / 30
    expect(abs(rows[0]["values"]["plateau q/q_s"] - ref_plateau) < 1e-9, "reference plateau")
    expect(abs(cheap["errors"]["peak q/q_s"] - 0.05) < 1e-9, f"peak error {cheap['errors']}")
    expect(abs(cheap["errors"]["plateau q/q_s"] - ((29 * 10.3 + 12.6) / 30 / ref_plateau - 1))
           < 1e-9, f"plateau error {cheap['errors']}")
    # footing_to_1: the peak to s/B 1.0, the plateau and the mean over s/B 0.4-1.0 (60 rows)
    footing_run(os.path.join(work, "ref1"), 10.0, 12.0, 1e9, rows=101)
    footing_run(os.path.join(work, "cheap1"), 10.3, 12.6, 2e8, rows=101)
    r = subprocess.run(["/usr/bin/python3", TOOL, os.path.join(work, "ref1"),
                        os.path.join(work, "cheap1"),
                        "--case", os.path.join(work, "ref", "case.json"),
                        "--quantities", "footing_to_1", "--json", out],
                       capture_output=True, text=True)
    expect(r.returncode == 0, f"footing_to_1: exit {r.returncode}: {r.stderr}")
    errors = json.load(open(out))[1]["errors"]
    expect(abs(errors["peak q/q_s"] - 0.05) < 1e-9 and
           abs(errors["q/q_s, s/B 0.4-1.0"] - 0.03) < 1e-9, f"footing_to_1 errors {errors}")
    r = subprocess.run(["/usr/bin/python3", TOOL, os.path.join(work, "cheap"),
                        os.path.join(work, "ref")], capture_output=True, text=True)
    expect(r.returncode == 2 and "case.json: no such case file" in r.stderr, f"no case: {r.stderr}")
    r = subprocess.run(["/usr/bin/python3", TOOL, os.path.join(work, "ref"),
                        os.path.join(work, "nowhere")], capture_output=True, text=True)
    expect(r.returncode == 2 and "nowhere: no such output directory" in r.stderr, r.stderr)
    check_sets(work, out)
    print("compare_cost: ok")


def check_sets(work, out):
    """Three packing sets whose reference plateaus are 10, 11 and 12 (scatter 1/11 = 9.09 %):
    a setting off by +2, +3, +4 % on them is within and biased (mean 3 % against t 4.303 times
    its standard error 0.577 %), one off by +20, -20, +1 % is outside and not biased."""
    case = os.path.join(work, "ref", "case.json")
    levels = (10.0, 11.0, 12.0)
    dirs = []
    for name, factors in (("ref", (1.0, 1.0, 1.0)), ("close", (1.02, 1.03, 1.04)),
                          ("wild", (1.2, 0.8, 1.01))):
        for k, (level, f) in enumerate(zip(levels, factors)):
            d = os.path.join(work, "sets", f"{name}_{k}")
            footing_run(d, level * f, level * f, 1e9 * (k + 1) * (0.5 if name != "ref" else 1))
            dirs.append(d)
    r = subprocess.run(["/usr/bin/python3", TOOL, *dirs, "--case", case, "--sets", "3",
                        "--json", out], capture_output=True, text=True)
    expect(r.returncode == 0, f"--sets: exit {r.returncode}: {r.stderr}")
    result = json.load(open(out))
    plateau = "plateau q/q_s"
    expect(abs(result["scatter"][plateau] - 1.0 / 11.0) < 1e-12,
           f"scatter {result['scatter'][plateau]}")
    close, wild = result["settings"]
    work_ratio = close["particle_steps_ratio"]
    expect(abs(work_ratio - 0.5) < 1e-12, f"work {work_ratio}")
    errors = [s["errors"][plateau] for s in close["sets"]]
    expect(all(abs(e - x) < 1e-9 for e, x in zip(errors, (0.02, 0.03, 0.04))), f"errors {errors}")
    v = close["verdicts"][plateau]
    expect(v["within"] is True and v["bias"] is True and abs(v["mean"] - 0.03) < 1e-9 and
           abs(v["standard_error"] - 0.01 / 3 ** 0.5) < 1e-9, f"close verdict {v}")
    v = wild["verdicts"][plateau]
    expect(v["within"] is False and v["bias"] is False, f"wild verdict {v}")
    expect("outside (9.09 %)" in r.stdout and "within (9.09 %), bias" in r.stdout,
           f"the table's verdicts: {r.stdout}")
    r = subprocess.run(["/usr/bin/python3", TOOL, *dirs[:4], "--case", case, "--sets", "3"],
                       capture_output=True, text=True)
    expect(r.returncode == 2 and "--sets 3: 4 folders" in r.stderr, f"4 folders: {r.stderr}")
    r = subprocess.run(["/usr/bin/python3", TOOL, *dirs[:3], "--case", case, "--sets", "3"],
                       capture_output=True, text=True)
    expect(r.returncode == 2 and "at least one setting" in r.stderr, f"no setting: {r.stderr}")


main()
