#!/usr/bin/env python3
"""Checks an isotropic element test run against physics: usage check_isotropic.py OUT_DIR."""
import csv, json, math, sys

out = sys.argv[1]
summary = json.load(open(f"{out}/summary.json"))
rows = list(csv.DictReader(open(f"{out}/history.csv")))
failures = []
def check(ok, what):
    if not ok:
        failures.append(what)

for key in ("wall_seconds", "dem_particle_steps", "engine"):
    check(key in summary, f"summary.json lacks {key}")
check(summary["engine"] == "liggghts", "engine is not liggghts")
check(summary["dem_particle_steps"] > 0, "no particle steps counted")
for c in ["e_xx", "e_yy", "e_zz", "e_xy", "e_xz", "e_yz", "s_xx", "s_yy", "s_zz", "s_xy",
          "s_xz", "s_yz", "p", "q", "void_ratio", "coordination_number"]:
    check(c in rows[0], f"history.csv lacks column {c}")
p = [float(r["p"]) for r in rows]
e = [float(r["void_ratio"]) for r in rows]
# Starts consolidated at the target; p is the in-plane mean of -s_xx, -s_yy.
check(abs(p[0] - 1e5) <= 0.02e5, f"initial p {p[0]} not within 2 % of 1e5")
check(abs(p[0] + 0.5 * (float(rows[0]["s_xx"]) + float(rows[0]["s_yy"]))) < 1e-6 * p[0],
      "p is not -(s_xx + s_yy)/2")
# Compression: p grows, void ratio shrinks consistently with the imposed strain.
check(p[-1] > 1.05 * p[0], f"p did not grow under compression ({p[0]} -> {p[-1]})")
strain = float(rows[-1]["e_xx"])
check(abs(strain + 0.002) < 1e-9 and abs(float(rows[-1]["e_yy"]) - strain) < 1e-12,
      f"final strain {strain} is not the imposed -0.002 per axis")
expected_e = (1 + e[0]) * math.exp(2 * strain) - 1  # area scales with exp(e_xx + e_yy)
check(abs(e[-1] - expected_e) < 1e-9, f"void ratio {e[-1]} != {expected_e} from the strain")
if failures:
    print("\n".join(failures))
    sys.exit(1)
print(f"ok: p {p[0]:.0f} -> {p[-1]:.0f} Pa, e {e[0]:.4f} -> {e[-1]:.4f}")
