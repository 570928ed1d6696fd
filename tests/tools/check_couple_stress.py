#!/usr/bin/python3
"""Checks of tools/couple_stress.py on a synthetic direct-DEM snapshot of known couple stress.

usage: check_couple_stress.py WORK

Pairs of equal discs (radius r) side by side along x, each pair's contact carrying a normal
force N and a tangential force T on the left disc: the Love-Weber stress of a pair is
[[-2 N r, 0], [2 T r, 0]] / V, so every window has |a| / p = T / N and
|a| / q = T / sqrt(N^2 + T^2) (p, q of the symmetric part). Without tangential forces a = 0.
Bad input: a snapshot without its contact forces, a contact between no grains' centres.
"""
import json
import math
import os
import shutil
import subprocess
import sys

import numpy as np

from checking import check, finish

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "tools", "couple_stress.py")
R = 0.005


def fake_run(folder, normal, tangential, stray=False):
    """A 1 x 1 m direct-DEM output folder with one snapshot at s/B = 0.1 of 400 pairs."""
    os.makedirs(os.path.join(folder, "snapshots"))
    summary = {"B": 0.2, "B_over_d": 20.0, "block": [1.0, 1.0], "footing_speed": 0.1,
               "time_step": 1e-4, "thickness": 0.01}
    json.dump(summary, open(os.path.join(folder, "summary.json"), "w"))
    step = int(round(0.1 * summary["B"] / (summary["footing_speed"] * summary["time_step"])))
    centres = (np.arange(20) + 0.5) * 0.05
    cx, cy = [c.ravel() for c in np.meshgrid(centres, centres)]
    left = np.column_stack([cx - R, cy])
    right = np.column_stack([cx + R, cy])
    xy = np.vstack([left, right])
    prefix = os.path.join(folder, "snapshots", f"grains_{step:09d}")
    with open(prefix + "_grains.vtk", "w") as f:
        f.write(f"# vtk DataFile Version 3.0\ngrains\nASCII\nDATASET POLYDATA\n"
                f"POINTS {len(xy)} double\n")
        np.savetxt(f, np.column_stack([xy, np.zeros(len(xy))]), fmt="%.9g")
        f.write(f"POINT_DATA {len(xy)}\nSCALARS radius double 1\nLOOKUP_TABLE default\n")
        np.savetxt(f, np.full(len(xy), R), fmt="%.9g")
    n = len(left)
    ends = np.zeros((2 * n, 3))
    ends[0::2, :2], ends[1::2, :2] = left, right
    if stray:
        ends[0, 0] += 1e-3
    with open(prefix + "_contacts.vtk", "w") as f:
        f.write(f"# vtk DataFile Version 3.0\ncontacts\nASCII\nDATASET POLYDATA\n"
                f"POINTS {2 * n} double\n")
        np.savetxt(f, ends, fmt="%.9g")
        f.write(f"LINES {n} {3 * n}\n")
        np.savetxt(f, np.column_stack([np.full(n, 2), 2 * np.arange(n), 2 * np.arange(n) + 1]),
                   fmt="%d")
    np.savez(prefix + "_contacts.npz", id1=np.arange(n), id2=np.arange(n) + n,
             fx=np.full(n, -normal), fy=np.full(n, tangential), footing_force=0.0)
    return prefix


def run(folder, *extra):
    out = folder + ".json"
    p = subprocess.run([sys.executable, TOOL, folder, "--at", "0.1", "--min-grains", "10",
                        "--json", out] + list(extra), capture_output=True, text=True)
    return p, (json.load(open(out)) if p.returncode == 0 else None)


def main():
    work = sys.argv[1]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    normal, tangential = 100.0, 10.0
    fake_run(os.path.join(work, "couple"), normal, tangential)
    p, result = run(os.path.join(work, "couple"))
    check(p.returncode == 0, f"couple: exit {p.returncode} {p.stderr.strip()[-200:]}")
    if result:
        want_q = tangential / math.hypot(normal, tangential)
        check(len(result["windows"]) == 25, f"25 windows of 20 d: {len(result['windows'])}")
        for name, want in (("a_over_p", tangential / normal), ("a_over_q", want_q)):
            check(all(abs(v / want - 1) < 1e-6 for v in result[name]),
                  f"{name}: median, 95th, largest {result[name]} against {want:.6g}")
        whole = result["whole_block"]
        check(abs(whole["a"] / whole["p"] / (tangential / normal) - 1) < 1e-6,
              f"whole block |a|/p {whole['a'] / whole['p']:.6g}")
    fake_run(os.path.join(work, "none"), normal, 0.0)
    p, result = run(os.path.join(work, "none"))
    check(p.returncode == 0 and result and max(result["a_over_q"]) < 1e-12,
          f"no tangential force, no couple stress: {result and result['a_over_q']}")
    prefix = fake_run(os.path.join(work, "no_forces"), normal, tangential)
    os.remove(prefix + "_contacts.npz")
    p, _ = run(os.path.join(work, "no_forces"))
    check(p.returncode == 2 and "contacts.npz: missing" in p.stderr,
          f"no contact forces: exit {p.returncode} {p.stderr.strip()[-160:]}")
    fake_run(os.path.join(work, "stray"), normal, tangential, stray=True)
    p, _ = run(os.path.join(work, "stray"))
    check(p.returncode == 2 and "no grain's centre" in p.stderr,
          f"a contact off the grains: exit {p.returncode} {p.stderr.strip()[-160:]}")
    p, _ = run(os.path.join(work, "couple"), "--window", "500")
    check(p.returncode == 2 and "no window" in p.stderr,
          f"windows larger than the block: exit {p.returncode} {p.stderr.strip()[-160:]}")


if __name__ == "__main__":
    main()
    finish()
