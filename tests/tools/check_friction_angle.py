"""Checks of tools/friction_angle.py on drained biaxial histories of known form: a sample whose
mobilised angle rises to a 30° peak at 2 % axial strain and softens to 20° from 8 % on, while
its lateral strain grows past the axial one (dilation), at two confining pressures. The peak
angle, the Mohr-Coulomb fit (30°, c' = 0) and the residual angle over 10-15 % (20°) must come
back, and the volumetric strain 0.4 x the axial one at the axial strains asked (between rows:
the interpolation); an empty residual window, a volume asked beyond the last row and a
missing column end with exit 2 and the problem named.

usage: check_friction_angle.py synthetic|bad WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "friction_angle.py")
PEAK, RESIDUAL = 30.0, 20.0


def expect(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def mobilised(axial):
    """Mobilised angle [deg] at an axial strain: up to the peak, then down to the residual."""
    if axial <= 0.02:
        return PEAK * axial / 0.02
    if axial >= 0.08:
        return RESIDUAL
    return PEAK + (RESIDUAL - PEAK) * (axial - 0.02) / 0.06


def biaxial(directory, p0, steps=300, increment=5e-4):
    os.makedirs(directory, exist_ok=True)
    with open(os.path.join(directory, "history.csv"), "w") as f:
        f.write("increment,e_xx,e_yy,e_zz,e_xy,e_xz,e_yz,s_xx,s_yy,s_zz,s_xy,s_xz,s_yz\n")
        for k in range(steps + 1):
            axial = k * increment
            sin_phi = math.sin(math.radians(mobilised(axial)))
            s1 = p0 * (1 + sin_phi) / (1 - sin_phi)
            lateral = 1.4 * axial  # expands faster than the axial strain shortens
            f.write(f"{k},{lateral!r},{-axial!r},0,0,0,0,{-p0!r},{-s1!r},0,0,0,0\n")
    with open(os.path.join(directory, "summary.json"), "w") as f:
        json.dump({"dimension": 2, "test": "drained_biaxial", "confining_pressure": p0}, f)


def run(*args):
    return subprocess.run(["/usr/bin/python3", TOOL, *args], capture_output=True, text=True)


def synthetic(work):
    runs = [os.path.join(work, f"p{p}") for p in (50, 200)]
    for r, p in zip(runs, (50e3, 200e3)):
        biaxial(r, p)
    out = os.path.join(work, "angles.json")
    r = run(*runs, "--residual", "0.10", "0.15", "--volume-at", "0.05", "0.15", "0.12345",
            "--json", out)
    expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    result = json.load(open(out))
    expect(abs(result["friction_angle_deg"] - PEAK) < 1e-6, f"fit {result}")
    expect(abs(result["cohesion_pa"]) < 1e-3, f"cohesion {result}")
    for row in result["runs"]:
        expect(abs(row["mobilised_friction_deg"] - PEAK) < 1e-6, f"peak {row}")
        expect(abs(row["residual_friction_deg"] - RESIDUAL) < 1e-6, f"residual {row}")
    expect(abs(result["residual_friction_deg"] - RESIDUAL) < 1e-6, f"mean residual {result}")
    expect("mean of 2 runs: 20.00 deg" in r.stdout, r.stdout)
    for row in result["runs"] + [result]:
        for e, v in row["volumetric_strain_at"].items():
            expect(abs(v - 0.4 * float(e)) < 1e-12, f"volume at {e}: {v} in {row}")


def bad(work):
    biaxial(os.path.join(work, "short"), 100e3, steps=20)
    r = run(os.path.join(work, "short"), "--residual", "0.10", "0.15")
    expect(r.returncode == 2 and "no row with axial strain in [0.1, 0.15]" in r.stderr,
           f"empty window: {r.returncode} {r.stderr}")
    r = run(os.path.join(work, "short"), "--volume-at", "0.02")
    expect(r.returncode == 2 and "--volume-at 0.02 beyond the largest axial strain 0.01" in r.stderr,
           f"volume beyond the last row: {r.returncode} {r.stderr}")
    path = os.path.join(work, "short", "history.csv")
    lines = open(path).read().splitlines()
    with open(path, "w") as f:
        f.write("\n".join(l.rsplit(",", 6)[0] for l in lines) + "\n")
    r = run(os.path.join(work, "short"))
    expect(r.returncode == 2 and "s_xx" in r.stderr, f"missing columns: {r.returncode} {r.stderr}")


if __name__ == "__main__":
    case, work = sys.argv[1], os.path.join(sys.argv[2], sys.argv[1])
    shutil.rmtree(work, ignore_errors=True)
    {"synthetic": synthetic, "bad": bad}[case](work)
    print(f"{case}: ok")
