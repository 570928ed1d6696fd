#!/usr/bin/python3
"""Checks of tools/rve_localisation.py on synthetic snapshot pairs of known local shear.

usage: check_rve_localisation.py WORK

A periodic cell 30 grain diameters wide holds 900 grains at random. Sheared uniformly (a pure
shear), every grain's local shear is the cell's and the half-share fraction is 0.5. Sheared in
a strip of a fifth of the cell (simple shear along the cell's first side, the rest rigid), the
strip's grains carry all of it: the cell's gamma is the strip's over five, and half of the
summed gamma sits in about a tenth of the grains. The uniform shear written with a reduced cell
basis (b - a) must read the same, and a 3D snapshot, two snapshots of different grains and a
missing cell file are refused with exit 2.
"""
import json
import os
import shutil
import sys

import numpy as np

from checking import check, finish, tool
from synthetic import write_snapshot

L = 0.3
RADIUS = 0.005


def grains():
    rng = np.random.default_rng(7)
    xy = rng.random((900, 2)) * L
    return np.column_stack([xy, np.zeros(len(xy))]), np.full(len(xy), RADIUS)


def write_run(folder, moved, sides_after, sides_before=((L, 0), (0, L))):
    """An element test's snapshot folder: increment 0 (the grains as drawn) and 10 (moved)."""
    snapshots = os.path.join(folder, "snapshots")
    os.makedirs(snapshots)
    centres, radii = grains()
    for step, points, sides in ((0, centres, sides_before), (10, moved, sides_after)):
        box = [list(sides[0]) + [0.0], list(sides[1]) + [0.0], [0.0, 0.0, 2 * RADIUS]]
        write_snapshot(os.path.join(snapshots, f"rve_{step:06d}"), points, radii, [], [], box)
    return folder


def measure(folder, extra=()):
    code, out, err = tool("rve_localisation.py", [folder, "--json", folder + ".json"] + list(extra))
    check(code == 0, f"{os.path.basename(folder)}: the tool runs (exit {code}: {err.strip()})")
    return json.load(open(folder + ".json"))[folder] if code == 0 else None


def main():
    work = sys.argv[1]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    centres, _ = grains()

    e = 0.05  # pure shear diag(1 + e, 1 / (1 + e)): gamma = sqrt(2) |dev eps|
    F = np.diag([1 + e, 1 / (1 + e), 1.0])
    expected = np.sqrt(2) * np.hypot(*(np.array([e, 1 / (1 + e) - 1]) -
                                       0.5 * (e + 1 / (1 + e) - 1)))
    uniform = write_run(os.path.join(work, "uniform"), centres @ F.T,
                        ((L * (1 + e), 0), (0, L / (1 + e))))
    r = measure(uniform)
    if r:
        check(abs(r["cell_shear"] - expected) < 1e-6 * expected,
              f"uniform: the cell's gamma {r['cell_shear']:.6f} is the pure shear's {expected:.6f}")
        check(abs(r["mean_shear"] - expected) < 1e-6,
              f"uniform: every grain's gamma is the cell's (mean {r['mean_shear']:.6f})")
        check(abs(r["half_share_fraction"] - 0.5) < 0.01,
              f"uniform: half-share fraction {r['half_share_fraction']:.3f} = 0.5")

    # The same motion, the second cell written with sides a and b - a (a reduced basis).
    a, b = np.array([L * (1 + e), 0]), np.array([0, L / (1 + e)])
    reduced = write_run(os.path.join(work, "reduced_basis"), centres @ F.T, (a, b - a))
    q = measure(reduced)
    if q and r:
        check(abs(q["cell_shear"] - r["cell_shear"]) < 1e-9 and
              abs(q["half_share_fraction"] - r["half_share_fraction"]) < 1e-9,
              "a reduced cell basis in the second snapshot reads the same")

    slip, y0, width = 0.03, 0.4 * L, 0.2 * L  # the strip's gamma: slip / width = 0.5
    ramp = np.clip((centres[:, 1] - y0) / width, 0.0, 1.0)
    banded = centres + np.column_stack([slip * ramp, 0 * ramp, 0 * ramp])
    band = write_run(os.path.join(work, "band"), banded, ((L, 0), (slip, L)))
    s = measure(band)
    if s:
        check(abs(s["cell_shear"] - slip / L) < 1e-6,
              f"band: the cell's gamma {s['cell_shear']:.4f} is the slip over the cell, {slip / L}")
        check(0.07 < s["half_share_fraction"] < 0.15,
              f"band: half of the gamma in {s['half_share_fraction']:.3f} of the grains "
              "(the strip holds 0.2)")
        check(s["top_10_percent_share"] > 0.4,
              f"band: the top 10 % carry {s['top_10_percent_share']:.2f} (uniform: 0.1)")

    flat = os.path.join(work, "three_d")
    moved = centres.copy()
    moved[:, 2] = np.linspace(0, 0.01, len(moved))
    write_run(flat, moved, ((L, 0), (0, L)))
    code, _, err = tool("rve_localisation.py", [flat])
    check(code == 2 and "3D grains" in err, f"a 3D snapshot refused (exit {code}: {err.strip()})")

    fewer = os.path.join(work, "fewer")
    write_run(fewer, centres, ((L, 0), (0, L)))
    grains_file = os.path.join(fewer, "snapshots", "rve_000010_grains.vtk")
    write_snapshot(grains_file[: -len("_grains.vtk")], centres[:-1], np.full(899, RADIUS), [], [],
                   [[L, 0, 0], [0, L, 0], [0, 0, 2 * RADIUS]])
    code, _, err = tool("rve_localisation.py", [fewer])
    check(code == 2 and "different grains" in err,
          f"snapshots of different grains refused (exit {code}: {err.strip()})")

    no_cell = os.path.join(work, "no_cell")
    write_run(no_cell, centres, ((L, 0), (0, L)))
    os.remove(os.path.join(no_cell, "snapshots", "rve_000010_cell.vtk"))
    code, _, err = tool("rve_localisation.py", [no_cell])
    check(code == 2 and "_cell.vtk: missing" in err,
          f"a missing cell file refused (exit {code}: {err.strip()})")
    finish()


if __name__ == "__main__":
    main()
