"""Checks of tools/native_twin.py.

usage: check_native_twin.py CASE WORK_DIR [MPM_LIG]   (CASE: real | bad)

real: a 100-disc drained biaxial test to 0.6 % axial strain through mpm_lig and its native
LIGGGHTS twin: the twin starts from the same packing (its first state holds the library run's
prepared pressure within 1 %), ends at the same axial strain, keeps the lateral stress at the
confining pressure (servo within 5 %), and in this nearly elastic range gives the same
deviator as the library path within 15 % at 0.3 % and 0.6 % axial strain.
bad: a case that is not an element test, and an element test without a twin, exit 2 naming it.
"""
import json
import os
import shutil
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "native_twin.py")


def expect(condition, message):
    if not condition:
        raise SystemExit(f"FAILED: {message}")


def real(work, mpm_lig):
    from mpm_lig_post.quantities import principal_series
    from mpm_lig_post.tables import read_history
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    case = json.load(open(os.path.join(HERE, "..", "element", "biaxial.json")))
    case["rve"]["substeps"] = {"inertial_number": 1e-3, "min": 10}
    case["analysis"].update({"axial_strain": 0.006, "strain_increment": 0.0005})
    path = os.path.join(work, "biaxial.json")
    json.dump(case, open(path, "w"), indent=1)
    r = subprocess.run([sys.executable, TOOL, path, "--output", os.path.join(work, "twin"),
                        "--mpm-lig", mpm_lig], capture_output=True, text=True)
    sys.stdout.write(r.stdout)
    expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr[-2000:]}")
    summary = json.load(open(os.path.join(work, "twin", "library", "summary.json")))
    native = read_history(os.path.join(work, "twin", "native", "history.csv"))
    library = read_history(os.path.join(work, "twin", "library", "history.csv"))
    p0 = summary["preparation"]["pressure"]
    first = -(native["s_xx"][0] + native["s_yy"][0]) / 2
    expect(abs(first / p0 - 1) < 0.01, f"twin starts at {first:.0f} Pa, packing at {p0:.0f} Pa")
    expect(abs(-native["e_yy"][-1] - 0.006) < 2e-4, f"axial strain {-native['e_yy'][-1]}")
    lateral = -native["s_xx"][len(native["s_xx"]) // 2:]
    target = summary["confining_pressure"]
    expect(np.max(np.abs(lateral / target - 1)) < 0.05, f"lateral stress {lateral} vs {target}")
    curves = {}
    for name, table in (("library", library), ("native", native)):
        s1, s3, e1, _ = principal_series(table, 2)
        curves[name] = (e1, s1 - s3)
    for strain in (0.003, 0.006):
        q = {n: np.interp(strain, *c) for n, c in curves.items()}
        expect(abs(q["native"] / q["library"] - 1) < 0.15, f"deviator at {strain}: {q}")
    expect(os.path.isfile(os.path.join(work, "twin", "twin.png")), "picture")
    expect("peak phi" in r.stdout, "table printed")


def bad(work):
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    for name, case, word in (
            ("mpm", os.path.join(HERE, "footing_tiny.json"), "analysis.type"),
            ("cyclic", os.path.join(HERE, "..", "element", "cyclic.json"), "analysis.test")):
        r = subprocess.run([sys.executable, TOOL, case, "--output", os.path.join(work, name)],
                           capture_output=True, text=True)
        expect(r.returncode == 2 and word in r.stderr, f"{name}: exit {r.returncode} {r.stderr}")
        expect(not os.path.exists(os.path.join(work, name)), f"{name}: output created")


if __name__ == "__main__":
    case, work = sys.argv[1], os.path.join(sys.argv[2], sys.argv[1])
    {"real": real, "bad": bad}[case](work, *sys.argv[3:])
    print(f"{case}: ok")
