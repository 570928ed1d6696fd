#!/usr/bin/python3
"""How much of a window's stress ratio is lost to averaging: the grains' stress over a whole
probe window against the same grains' stress over sub-windows of a few grain diameters.

The grains' Love-Weber stress (tools/mpm_lig_post/love_weber.py, the contacts of the
snapshot's contacts.npz) over their summed Voronoi cells (mirrored at the side planes,
tools/mpm_lig_post/direct_dem/cells.py) gives the window's stress as the probes compute it
(without the velocity fluctuations, over the cells' area); q/p of that is printed beside sum(q_k) / sum(p_k) over
square sub-windows k of SUB grain diameters (by the grains' reference positions; sub-windows
of fewer than 5 grains left out). Where the stress turns across the window (a band between
regions that do not move alike) the whole window's q/p falls below its parts'; in a uniform
state the two differ only by the sub-windows' noise.

usage: window_stress.py RUN_DIR [--windows NAME ...] [--sub SUB] [--json FILE]
       RUN_DIR a tools/direct_dem.py run with --probes and --snapshots
"""
import argparse
import json
import os
import sys

import numpy as np

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools")
sys.path.insert(0, TOOLS)
from mpm_lig_post.direct_dem.cells import closed, walled_areas  # noqa: E402
from mpm_lig_post.direct_dem.probes import members  # noqa: E402
from mpm_lig_post.love_weber import invariants, window_stress  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402


def snapshot_contacts(snapshot, ids):
    """A grain snapshot's contacts as love_weber takes them: (first, second) indices into the
    snapshot's grains (ordered as `ids`) and the force on first from second."""
    c = np.load(snapshot.replace("_grains.vtk", "_contacts.npz"))
    where = {int(k): n for n, k in enumerate(ids)}
    return (np.array([where[int(k)] for k in c["id1"]], int),
            np.array([where[int(k)] for k in c["id2"]], int),
            np.column_stack([c["fx"], c["fy"]]))


def set_p_q(inside, xy, radius, contacts, areas, thickness):
    """(p, q) of the grains where `inside` (bool per grain) over their summed cells."""
    return invariants(window_stress(inside, xy, radius, contacts, areas[inside].sum(),
                                    thickness))


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("run")
    a.add_argument("--windows", nargs="+")
    a.add_argument("--sub", type=float, default=5.0, help="sub-window side, grain diameters")
    a.add_argument("--json")
    args = a.parse_args()
    summary = json.load(open(os.path.join(args.run, "summary.json")))
    B, (lx, ly), thickness = summary["B"], summary["block"], summary["thickness"]
    d = B / summary["B_over_d"]
    reference = np.load(os.path.join(args.run, "reference.npz"))
    ids, start = reference["ids"], reference["xy"]
    ds_over_B = summary["footing_speed"] * summary["time_step"] / B
    folder = os.path.join(args.run, "snapshots")
    out = []
    print(f"| s/B | window | q/p of the window | sum q / sum p over its {args.sub:g} d sub-windows "
          "(how many) |")
    print("|---|---|---|---|")
    for name in sorted(n for n in os.listdir(folder) if n.endswith("_grains.vtk")):
        s = int(name.split("_")[1]) * ds_over_B
        grains = read_polydata(os.path.join(folder, name))
        xy, radius = grains.points[:, :2], grains.field("radius")
        areas = walled_areas(xy, lx, 4.0 * radius.max())
        contacts = snapshot_contacts(os.path.join(folder, name), ids)
        kept = closed(areas, radius)
        for probe in args.windows or sorted(summary["probes"]):
            w = summary["probes"][probe]
            centre = np.array([w["x_over_B"] * B, ly - w["depth_over_B"] * B])
            side = w["side_over_B"] * B
            inside = members(start, centre, side) & kept
            p, q = set_p_q(inside, xy, radius, contacts, areas, thickness)
            cell = np.floor((start - (centre - 0.5 * side)) / (args.sub * d)).astype(int)
            keys = np.where(inside, cell[:, 0] * 100000 + cell[:, 1], -1)
            parts = [set_p_q(keys == k, xy, radius, contacts, areas, thickness)
                     for k in np.unique(keys[inside]) if np.sum(keys == k) >= 5]
            ps, qs = np.array(parts).T
            row = {"s_over_B": s, "window": probe, "ratio": q / p,
                   "parts_ratio": float(qs.sum() / ps.sum()), "parts": len(parts)}
            out.append(row)
            print(f"| {s:.3f} | {probe} | {row['ratio']:.3f} | {row['parts_ratio']:.3f} "
                  f"({row['parts']}) |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump({"run": args.run, "sub_diameters": args.sub, "rows": out}, f, indent=1)


if __name__ == "__main__":
    main()
