#!/usr/bin/env python3
"""Checks an element test run against physics: usage check_element.py OUT_DIR TARGET_P.

Common: summary.json keys, history.csv columns, start consolidated at TARGET_P (2 %).
isotropic_compression: p grows, strain as imposed, void ratio follows the strain exactly.
drained_biaxial: lateral stress within the servo tolerance at every increment, deviator
  mobilised, axial strain as imposed.
undrained_cyclic_simple_shear: volume constant, γ follows the cycles, shear stress follows γ.
"""
import csv
import json
import math
import sys

out, target = sys.argv[1], float(sys.argv[2])
summary = json.load(open(f"{out}/summary.json"))
rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(f"{out}/history.csv"))]
failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


for key in ("wall_seconds", "dem_particle_steps", "engine"):
    check(key in summary, f"summary.json lacks {key}")
check(summary["dem_particle_steps"] > 0, "no particle steps counted")
# These cases give the preparation no step of its own: it is the RVE's.
check(summary["preparation"]["time_step"] == summary["time_step"],
      f"preparation step {summary['preparation']['time_step']} is not the RVE's "
      f"{summary['time_step']}")
for c in ["e_xx", "e_yy", "e_zz", "e_xy", "e_xz", "e_yz", "s_xx", "s_yy", "s_zz", "s_xy",
          "s_xz", "s_yz", "p", "q", "void_ratio", "coordination_number"]:
    check(c in rows[0], f"history.csv lacks column {c}")
p = [r["p"] for r in rows]
e = [r["void_ratio"] for r in rows]
check(abs(p[0] - target) <= 0.02 * target, f"initial p {p[0]} not within 2 % of {target}")
check(abs(p[0] + 0.5 * (rows[0]["s_xx"] + rows[0]["s_yy"])) < 1e-6 * p[0],
      "p is not -(s_xx + s_yy)/2 (2D)")
test = summary["test"]
last = rows[-1]
if test == "isotropic_compression":
    strain = last["e_xx"]
    check(p[-1] > 1.05 * p[0], f"p did not grow under compression ({p[0]} -> {p[-1]})")
    check(abs(strain + 0.002) < 1e-9 and abs(last["e_yy"] - strain) < 1e-12,
          f"final strain {strain} is not the imposed -0.002 per axis")
    expected_e = (1 + e[0]) * math.exp(2 * strain) - 1  # area scales with exp(e_xx + e_yy)
    check(abs(e[-1] - expected_e) < 1e-9, f"void ratio {e[-1]} != {expected_e} from the strain")
elif test == "drained_biaxial":
    check(abs(last["e_yy"] + 0.02) < 1e-9, f"axial strain {last['e_yy']} is not -0.02")
    # The servo corrects every increment until the lateral stress is within the tolerance
    # (default 0.5 %) of the confining stress (the pressure after preparation by default).
    confining = summary["confining_pressure"]
    tolerance = summary["lateral_stress"]["tolerance"]
    check(abs(confining - target) <= 0.02 * target, f"confining stress {confining} is not {target}")
    worst = max(abs(-r["s_xx"] - confining) for r in rows[1:]) / confining
    check(worst <= tolerance, f"lateral stress strays {100 * worst:.2f} % from the confining "
          f"stress (tolerance {100 * tolerance:.2f} %)")
    check(worst <= summary["lateral_stress"]["max_relative_error"] + 1e-12,
          "summary.json lateral_stress.max_relative_error is below what history.csv shows")
    check(max(-r["s_yy"] for r in rows) > 1.3 * target, "no deviator mobilised")
elif test == "undrained_cyclic_simple_shear":
    check(max(abs(r["e_vol"]) for r in rows) < 1e-12, "volume changed in undrained shear")
    check(max(abs(x - e[0]) for x in e) < 1e-9, "void ratio changed in undrained shear")
    gammas = [r["gamma_xy"] for r in rows]
    check(abs(max(gammas) - 0.002) < 1e-9 and abs(min(gammas) + 0.002) < 1e-9,
          f"shear strain range {min(gammas)} .. {max(gammas)} is not ±0.002")
    check(abs(gammas[-1]) < 1e-12, "the cycle does not return to zero shear")
    # The shear stress follows the shear strain (a small packing starts with some s_xy of
    # its own fabric): higher at +γa than at -γa.
    at = lambda g: [r["s_xy"] for r in rows if abs(r["gamma_xy"] - g) < 1e-12]
    check(min(at(0.002)) - max(at(-0.002)) > 0.05 * target,
          "shear stress does not follow the shear strain")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"ok ({test}): p {p[0]:.0f} -> {p[-1]:.0f} Pa, e {e[0]:.4f} -> {e[-1]:.4f}")
