#!/usr/bin/env python3
"""Checks of tools/footing_contact_study.py --quick: Prandtl on B/4 and B/8 with both contacts
at CFL 0.5 and 0.25. The penalty rows (edges inset, and the whole footprint) must give the
same q_u at both steps (ratio within 0.002), the whole footprint's above the inset one's; the
JSON holds every run with its history; a second call reuses the runs; a missing mpm_lig is named.

usage: check_footing_contact_study.py MPM_LIG WORK
"""
import json
import os
import shutil
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "footing_contact_study.py")


def fail(message):
    print("FAIL:", message)
    sys.exit(1)


def study(mpm_lig, work, *extra):
    return subprocess.run([sys.executable, TOOL, work, "--mpm-lig", mpm_lig, "--quick", *extra],
                          capture_output=True, text=True, timeout=600)


def main():
    mpm_lig, work = sys.argv[1], sys.argv[2]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    out = os.path.join(work, "study.json")
    r = study(mpm_lig, os.path.join(work, "runs"), "--json", out)
    if r.returncode != 0:
        fail(f"exit {r.returncode}: {r.stderr}")
    print(r.stdout)
    rows = [line.split("|")[1:-1] for line in r.stdout.splitlines() if line.startswith("| prandtl")]
    if len(rows) != 6:
        fail(f"expected 6 rows (B/4, B/8 x three contacts), got {len(rows)}")
    by = {(m.strip(), c.strip()): (float(h), float(q), float(ratio))
          for _, m, c, h, q, ratio in rows}
    for mesh in ("B/4", "B/8"):
        for contact in ("penalty", "penalty, whole footprint"):
            half, _, ratio = by[(mesh, contact)]
            if abs(ratio - 1.0) > 0.002:
                fail(f"{mesh}, {contact}: q_u moved by {ratio - 1:+.4f} with the step")
        # Pressing the whole footprint acts as a footing a cell wider: above the inset one.
        if by[(mesh, "penalty, whole footprint")][0] <= by[(mesh, "penalty")][0]:
            fail(f"{mesh}: the whole footprint's q_u is not above the inset one's")
    with open(out) as f:
        runs = json.load(f)["runs"]
    if len(runs) != 12 or any(len(r["history_s_q"]) < 20 for r in runs):
        fail(f"the JSON holds {len(runs)} runs or short histories")
    again = study(mpm_lig, os.path.join(work, "runs"))
    if again.returncode != 0 or again.stdout != r.stdout:
        fail("a second call over the same runs did not give the same table")
    missing = study(os.path.join(work, "no_such_mpm_lig"), os.path.join(work, "other"))
    if missing.returncode != 2 or "mpm_lig executable not found" not in missing.stderr:
        fail(f"a missing mpm_lig: exit {missing.returncode}, {missing.stderr!r}")
    if os.path.exists(os.path.join(work, "other")):
        fail("a refused call created its work folder")
    print("footing_contact_study: penalty step-independent, whole footprint above inset, runs reused")


if __name__ == "__main__":
    main()
