#!/usr/bin/python3
"""Checks of tools/shear_band.py on synthetic grain motions of known band width.

usage: check_shear_band.py WORK

A 1 x 1 m block of 10^4 grain centres (d = 10 mm) sheared along an inclined band through the
footing's edge, u = D/2 (1 + tanh(xi / lam)) along the band (xi across it): the shear strain
is D/(2 lam) sech^2(xi / lam), whose full width at half maximum is 2 acosh(sqrt 2) lam. The
tool must give that width within 15 % at a Gaussian width of d/2 (and at 2 d after removing
the smearing within 25 %), for two band widths, and a uniform shear must not be called a band
of that width.
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
TOOL = os.path.join(HERE, "..", "..", "tools", "shear_band.py")


def fake_run(folder, displacement):
    """A direct-DEM output folder with reference.npz and one snapshot at s/B = 0.1."""
    os.makedirs(os.path.join(folder, "snapshots"))
    rng = np.random.default_rng(5)
    xy = rng.random((10000, 2))
    np.savez(os.path.join(folder, "reference.npz"), ids=np.arange(1, 10001), xy=xy)
    summary = {"B": 0.2, "B_over_d": 20.0, "block": [1.0, 1.0], "footing_speed": 0.1,
               "time_step": 1e-4}
    json.dump(summary, open(os.path.join(folder, "summary.json"), "w"))
    step = int(round(0.1 * summary["B"] / (summary["footing_speed"] * summary["time_step"])))
    moved = xy + displacement(xy)
    with open(os.path.join(folder, "snapshots", f"grains_{step:09d}_grains.vtk"), "w") as f:
        f.write(f"# vtk DataFile Version 3.0\ngrains\nASCII\nDATASET POLYDATA\nPOINTS {len(xy)} "
                "double\n")
        np.savetxt(f, np.column_stack([moved, np.zeros(len(xy))]), fmt="%.12g")


def band(lam, amount=0.02):
    """A band through the footing edge (0.1, 0.98) at 45 degrees, tanh profile of scale lam."""
    t = np.array([1.0, -1.0]) / math.sqrt(2.0)
    n = np.array([1.0, 1.0]) / math.sqrt(2.0)
    x0 = np.array([0.1, 0.98])
    return lambda xy: 0.5 * amount * (1 + np.tanh(((xy - x0) @ n) / lam))[:, None] * t


def measure(work, name, displacement, widths):
    folder = os.path.join(work, name)
    fake_run(folder, displacement)
    out = os.path.join(work, name + ".json")
    p = subprocess.run([sys.executable, TOOL, folder, "--to", "0.1", "--widths"] +
                       [str(w) for w in widths] + ["--json", out], capture_output=True, text=True)
    check(p.returncode == 0, f"{name}: exit {p.returncode} {p.stderr.strip()[-200:]}")
    return json.load(open(out))["rows"] if p.returncode == 0 else []


def main():
    work = sys.argv[1]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    d = 0.01
    for fwhm_d in (6.0, 12.0):
        lam = fwhm_d * d / (2 * math.acosh(math.sqrt(2)))
        rows = measure(work, f"band_{fwhm_d:g}d", band(lam), [1.0, 2.0])
        if rows:
            fine, coarse = rows
            check(abs(fine["unsmeared_over_d"] / fwhm_d - 1) < 0.2,
                  f"a band of {fwhm_d:g} d at w = d, smearing removed: {fine['unsmeared_over_d']:.2f} d "
                  f"(measured {fine['band_width_over_d']:.2f})")
            check(abs(coarse["unsmeared_over_d"] / fwhm_d - 1) < 0.25,
                  f"a band of {fwhm_d:g} d at w = 2d, smearing removed: "
                  f"{coarse['unsmeared_over_d']:.2f} d (measured {coarse['band_width_over_d']:.2f})")
    rows = measure(work, "uniform", lambda xy: 0.02 * np.column_stack([xy[:, 1], 0 * xy[:, 1]]),
                   [2.0])
    if rows:
        check(rows[0]["band_width_over_d"] > 30,
              f"a uniform shear is no narrow band ({rows[0]['band_width_over_d']:.1f} d)")
    p = subprocess.run([sys.executable, TOOL, os.path.join(work, "uniform"), "--to", "0.5"],
                       capture_output=True, text=True)
    check(p.returncode == 2 and "no snapshot near" in p.stderr, f"no snapshot there: exit "
          f"{p.returncode} {p.stderr.strip()[:120]}")


if __name__ == "__main__":
    main()
    finish()
