"""Checks of tools/calibrate_continuum.py on drained biaxial histories of known form: a linear
elastic (E, nu, plane strain) then perfectly plastic Mohr-Coulomb (phi, c = 0, dilatancy psi)
material at two confining pressures must give back E, nu, phi, psi and the density; bad input
ends with exit 2 and the problem named.

usage: check_calibrate_continuum.py synthetic|bad WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "calibrate_continuum.py")
E, NU, PHI, PSI, E0 = 80e6, 0.28, 31.0, 6.0, 0.2


def expect(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def biaxial(directory, p0, steps=400, increment=1e-4):
    """History of a plane-strain drained biaxial test on the elastic-plastic material."""
    os.makedirs(directory, exist_ok=True)
    sin_phi, sin_psi = math.sin(math.radians(PHI)), math.sin(math.radians(PSI))
    s1_peak = p0 * (1 + sin_phi) / (1 - sin_phi)
    stiffness = E / (1 - NU * NU)
    s1, e1, e3 = p0, 0.0, 0.0
    rows = []
    for k in range(steps + 1):
        rows.append((k, -e3, -e1, -(e1 + e3), -p0, -s1))
        if s1 + stiffness * increment <= s1_peak:
            s1 += stiffness * increment
            e3 += -NU / (1 - NU) * increment
        else:
            dev = -2 * sin_psi * increment / (1 - sin_psi)
            e3 += dev - increment
            s1 = s1_peak
        e1 += increment
    with open(os.path.join(directory, "history.csv"), "w") as f:
        f.write("increment,e_xx,e_yy,e_zz,e_vol,s_xx,s_yy,s_zz,s_xy,s_xz,s_yz\n")
        for k, exx, eyy, ev, sxx, syy in rows:
            f.write(f"{k},{exx!r},{eyy!r},0,{ev!r},{sxx!r},{syy!r},0,0,0,0\n")
    with open(os.path.join(directory, "summary.json"), "w") as f:
        json.dump({"dimension": 2, "test": "drained_biaxial", "confining_pressure": p0,
                   "preparation": {"void_ratio": E0}}, f)


def run(*args):
    return subprocess.run(["/usr/bin/python3", TOOL, *args], capture_output=True, text=True)


def synthetic(work):
    runs = [os.path.join(work, f"p{p}") for p in (50, 100, 200)]
    for r, p in zip(runs, (50e3, 100e3, 200e3)):
        biaxial(r, p)
    out = os.path.join(work, "calibration.json")
    r = run(*runs, "--json", out, "--id", "5")
    expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    m = json.load(open(out))["material"]
    expect(m["id"] == 5 and m["type"] == "mohr_coulomb", f"material block {m}")
    expect(abs(m["youngs_modulus"] / E - 1) < 1e-3, f"E {m['youngs_modulus']} != {E}")
    expect(abs(m["poisson_ratio"] - NU) < 1e-3, f"nu {m['poisson_ratio']} != {NU}")
    expect(abs(m["friction_deg"] - PHI) < 0.01, f"phi {m['friction_deg']} != {PHI}")
    expect(abs(m["dilatancy_deg"] - PSI) < 0.05, f"psi {m['dilatancy_deg']} != {PSI}")
    expect(m["cohesion"] == 0.0, f"cohesion {m['cohesion']}")
    expect(abs(m["density"] - 2650 / (1 + E0)) < 0.1, f"density {m['density']}")
    expect('"type": "mohr_coulomb"' in r.stdout, "the block is printed")


def bad(work):
    biaxial(os.path.join(work, "p100"), 100e3)
    biaxial(os.path.join(work, "p105"), 105e3)
    cases = [((os.path.join(work, "p100"),), "two or more confining pressures"),
             ((os.path.join(work, "p100"), os.path.join(work, "missing")), "missing: no such"),
             ((os.path.join(work, "p100"), os.path.join(work, "p105")), "differ by less than")]
    for args, message in cases:
        r = run(*args)
        expect(r.returncode == 2 and message in r.stderr, f"{args}: exit {r.returncode}, "
               f"stderr {r.stderr!r} (expected {message!r})")


if __name__ == "__main__":
    case, work = sys.argv[1], os.path.join(sys.argv[2], sys.argv[1])
    shutil.rmtree(work, ignore_errors=True)
    {"synthetic": synthetic, "bad": bad}[case](work)
    print(f"{case}: ok")
