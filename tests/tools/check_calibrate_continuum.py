"""Checks of tools/calibrate_continuum.py on drained biaxial histories of known form: a linear
elastic (E, nu, plane strain) then perfectly plastic Mohr-Coulomb (phi, c = 0, dilatancy psi)
material at two confining pressures must give back E, nu, phi, psi and the density; one whose
angle then softens linearly with the deviatoric strain to phi_r at kappa_r (no volume change)
must give back phi_r and kappa_r with --residual; bad input ends with exit 2 and the problem
named.

usage: check_calibrate_continuum.py synthetic|softening|bad WORK_DIR"""
import json
import math
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "calibrate_continuum.py")
E, NU, PHI, PSI, E0 = 80e6, 0.28, 31.0, 6.0, 0.2
PHI_R, KAPPA_R = 20.0, 0.02


def expect(condition, message):
    if not condition:
        sys.exit("FAILED: " + message)


def biaxial(directory, p0, steps=400, increment=1e-4, soften=False):
    """History of a plane-strain drained biaxial test on the elastic-plastic material (with
    `soften`, after the peak: no volume change, the angle falling linearly with the deviatoric
    strain sqrt(2/3 de:de) = 2 de_1 / sqrt 3 to PHI_R at KAPPA_R)."""
    os.makedirs(directory, exist_ok=True)
    sin_phi, sin_psi = math.sin(math.radians(PHI)), math.sin(math.radians(PSI))
    s1_peak = p0 * (1 + sin_phi) / (1 - sin_phi)
    stiffness = E / (1 - NU * NU)
    s1, e1, e3, kappa = p0, 0.0, 0.0, 0.0
    rows = []
    for k in range(steps + 1):
        rows.append((k, -e3, -e1, -(e1 + e3), -p0, -s1))
        if s1 + stiffness * increment <= s1_peak and kappa == 0.0:
            s1 += stiffness * increment
            e3 += -NU / (1 - NU) * increment
        elif soften:
            phi = PHI + (PHI_R - PHI) * min(kappa / KAPPA_R, 1.0)  # the first: the peak
            sin_now = math.sin(math.radians(phi))
            s1 = p0 * (1 + sin_now) / (1 - sin_now)
            kappa += 2.0 * increment / math.sqrt(3.0)
            e3 -= increment
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


def softening(work):
    runs = [os.path.join(work, f"p{p}") for p in (50, 100, 200)]
    for r, p in zip(runs, (50e3, 100e3, 200e3)):
        biaxial(r, p, steps=800, soften=True)
    out = os.path.join(work, "calibration.json")
    r = run(*runs, "--json", out, "--residual", "0.05", "0.08")
    expect(r.returncode == 0, f"exit {r.returncode}: {r.stderr}")
    m = json.load(open(out))["material"]
    expect(abs(m["friction_deg"] - PHI) < 0.05, f"phi {m['friction_deg']} != {PHI}")
    soft = m.get("softening", {})
    expect(abs(soft.get("residual_friction_deg", 0) - PHI_R) < 0.01, f"phi_r {soft}")
    step = 2e-4 / math.sqrt(3.0)  # one increment's deviatoric strain
    expect(abs(soft.get("plastic_strain", 0) - KAPPA_R) <= 1.01 * step,
           f"kappa_r {soft} != {KAPPA_R}")
    expect(soft.get("residual_dilatancy_deg") == 0.0, f"psi_r {soft}")
    r = run(*runs, "--residual", "0.2", "0.3")
    expect(r.returncode == 2 and "before the residual window" in r.stderr,
           f"a window past the run's end: exit {r.returncode}, {r.stderr!r}")
    r = run(*runs, "--residual", "0.08", "0.05")
    expect(r.returncode == 2 and "LO < HI" in r.stderr,
           f"a reversed window: exit {r.returncode}, {r.stderr!r}")


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
    {"synthetic": synthetic, "softening": softening, "bad": bad}[case](work)
    print(f"{case}: ok")
