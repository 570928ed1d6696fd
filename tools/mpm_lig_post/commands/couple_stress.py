"""The antisymmetric part of the grains' own stress in a direct-DEM footing (tools/direct_dem.py):
what a symmetric RVE stress drops where the grains carry rolling resistance.

usage: couple_stress.py RUN_DIR --at S [--window 20] [--min-grains 100] [--json FILE]

The snapshot nearest s/B = S (grains.vtk: centres and radii; contacts.vtk: the two centres of
each grain-grain contact; contacts.npz: its force on the first grain) gives the Love-Weber
stress sigma = (1/V) sum f (x) arm (mpm_lig_post.love_weber, the arm from each grain's centre
to the contact point) over square windows of --window grain diameters tiling the block (an
RVE is about 20 d wide), without the kinetic part. A grain's moment balance makes the
antisymmetric part a = (sigma_xy - sigma_yx) / 2 of a window the sum of its grains' rolling
torques and angular accelerations over V (plus the arms of the contacts its edge cuts): the
couple stress a symmetric stress leaves out. Prints, over the windows holding at least
--min-grains grains, the median, 95th percentile and largest |a| / q and |a| / p (p, q of the
symmetric part), and the same for the whole block; --json writes every window.
"""
from mpm_lig_post.requirements import require

require("numpy")

import json  # noqa: E402
from argparse import ArgumentParser  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.commands.shear_band import nearest_snapshot, snapshots  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.love_weber import invariants, window_stress  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402


def snapshot_at(run, s):
    """(summary, s/B of the snapshot, grain centres, radii, contacts (first, second, force))."""
    summary, found = snapshots(run)
    path, nearest = nearest_snapshot(run, found, s)
    prefix = path[: -len("_grains.vtk")]
    for suffix in ("_contacts.vtk", "_contacts.npz"):
        if not os.path.isfile(prefix + suffix):
            raise InputError(f"{prefix + suffix}: missing (the snapshot's contact forces)")
    grains = read_polydata(prefix + "_grains.vtk")
    xy = grains.points[:, :2]
    radii = np.asarray(grains.point_data.get("radius"), float)
    if radii.shape != (len(xy),):
        raise InputError(f"{prefix}_grains.vtk: no radius per grain")
    ends = read_polydata(prefix + "_contacts.vtk").points[:, :2]
    forces = np.load(prefix + "_contacts.npz")
    force = np.column_stack([forces["fx"], forces["fy"]])
    if len(ends) != 2 * len(force):
        raise InputError(f"{prefix}: {len(ends) // 2} contacts in the VTK file, "
                         f"{len(force)} forces in the npz file")
    # Both files print the centres with the same format: equal text is an equal position.
    index = {(x, y): k for k, (x, y) in enumerate(map(tuple, xy))}
    try:
        first = np.array([index[tuple(p)] for p in ends[0::2]], int)
        second = np.array([index[tuple(p)] for p in ends[1::2]], int)
    except KeyError as missing:
        raise InputError(f"{prefix}_contacts.vtk: a contact at {missing} is no grain's centre")
    return summary, nearest, xy, radii, (first, second, force)


def antisymmetric(sigma):
    """(|a|, p, q) of a 2 x 2 stress: a = (s_xy - s_yx) / 2, p and q of its symmetric part."""
    p, q = invariants(0.5 * (sigma + sigma.T))
    return abs(0.5 * (sigma[0, 1] - sigma[1, 0])), p, q


def windows(summary, xy, radii, contacts, side, min_grains):
    lx, ly = summary["block"]
    rows = []
    for x0 in np.arange(0.0, lx - 0.5 * side, side):
        for y0 in np.arange(0.0, ly - 0.5 * side, side):
            inside = (xy[:, 0] >= x0) & (xy[:, 0] < x0 + side) & \
                (xy[:, 1] >= y0) & (xy[:, 1] < y0 + side)
            count = int(inside.sum())
            if count < min_grains:
                continue
            sigma = window_stress(inside, xy, radii, contacts, side * side, summary["thickness"],
                                  symmetric=False)
            a, p, q = antisymmetric(sigma)
            rows.append({"x": x0 + 0.5 * side, "y": y0 + 0.5 * side,
                         "grains": count, "a": a, "p": p, "q": q})
    return rows


def spread(values):
    v = np.asarray(values, float)
    return float(np.median(v)), float(np.percentile(v, 95)), float(v.max())


def main():
    p = ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("output_dir", metavar="RUN_DIR", help="the direct-DEM run's output directory")
    p.add_argument("--at", type=cli.non_negative, required=True, help="s/B of the snapshot")
    p.add_argument("--window", type=cli.positive, default=20.0,
                   help="window side in grain diameters d (default 20)")
    p.add_argument("--min-grains", type=cli.positive_int, default=100,
                   help="skip windows with fewer grains (default 100)")
    p.add_argument("--json", help="write every window here")
    a = p.parse_args()
    run = a.output_dir
    if not os.path.isdir(run):
        raise InputError(f"{run}: no such output directory")
    cli.writable_file(a.json, "--json file")
    summary, at, xy, radii, contacts = snapshot_at(run, a.at)
    d = summary["B"] / summary["B_over_d"]
    rows = windows(summary, xy, radii, contacts, a.window * d, a.min_grains)
    if not rows:
        raise InputError(f"{run}: no window of {a.window:g} d holds {a.min_grains} grains")
    lx, ly = summary["block"]
    whole = antisymmetric(window_stress(np.ones(len(xy), bool), xy, radii, contacts, lx * ly,
                                        summary["thickness"], symmetric=False))
    by_q = spread([r["a"] / r["q"] for r in rows if r["q"] > 0])
    by_p = spread([r["a"] / r["p"] for r in rows if r["p"] > 0])
    print(f"{run}: B/d = {summary['B_over_d']:.0f}, snapshot at s/B {at:.3f}, "
          f"{len(rows)} windows of {a.window:g} d")
    print("| |a| over | median | 95th percentile | largest | whole block |")
    print("|---|---|---|---|---|")
    print(f"| q | {by_q[0]:.3g} | {by_q[1]:.3g} | {by_q[2]:.3g} | {whole[0] / whole[2]:.3g} |")
    print(f"| p | {by_p[0]:.3g} | {by_p[1]:.3g} | {by_p[2]:.3g} | {whole[0] / whole[1]:.3g} |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"run": run, "B_over_d": summary["B_over_d"], "at": at,
                       "window_over_d": a.window, "a_over_q": by_q, "a_over_p": by_p,
                       "whole_block": {"a": whole[0], "p": whole[1], "q": whole[2]},
                       "windows": rows}, f, indent=1)


def entry():
    """The command: tools/couple_stress.py in a checkout, mpm-lig-couple-stress installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
