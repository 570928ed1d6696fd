#!/usr/bin/python3
"""The volume of a direct-DEM probe window's grains, two ways: the least-squares det F that
probes.csv records, and the sum of the grains' Voronoi cells, at every grain snapshot. The
grains near a side plane are mirrored across it, so that their cells end at the plane (without
the mirror a window beside the footing's axis, x = 0, counts the open space beyond the plane
in its cells); grains whose cells are still open or larger than 2.5 pi r^2 (the free surface)
are left out.

usage: docs/study/cell_angle/window_voronoi.py RUN_DIR   (a tools/direct_dem.py run with
--probes and --snapshots; the numbers of docs/direct_dem.md "Can the RVE localise?")
"""
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "tools"))
from mpm_lig_post.direct_dem.cells import closed, walled_areas  # noqa: E402
from mpm_lig_post.direct_dem.probes import members, window_F  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402


def main(run):
    summary = json.load(open(os.path.join(run, "summary.json")))
    B = summary["B"]
    lx, ly = summary["block"]
    reference = np.load(os.path.join(run, "reference.npz"))["xy"]
    ds_over_B = summary["footing_speed"] * summary["time_step"] / B
    folder = os.path.join(run, "snapshots")
    names = sorted(n for n in os.listdir(folder) if n.endswith("_grains.vtk"))
    reach = 4.0 * read_polydata(os.path.join(folder, names[0])).field("radius").max()
    start = walled_areas(reference, lx, reach)
    print("| s/B | window | grains (inner) | ln det F, least squares | ln of the Voronoi sum | "
          "grains' ln(A/A0): 10th, 50th, 90th percentile |")
    print("|---|---|---|---|---|---|")
    for name in names:
        grains = read_polydata(os.path.join(folder, name))
        xy, radius = grains.points[:, :2], grains.field("radius")
        now = walled_areas(xy, lx, reach)
        inner = closed(start, radius) & closed(now, radius)
        s = int(name.split("_")[1]) * ds_over_B
        for probe, w in summary["probes"].items():
            centre = np.array([w["x_over_B"] * B, ly - w["depth_over_B"] * B])
            m = members(reference, centre, w["side_over_B"] * B)
            ok = m & inner
            fit = np.log(np.linalg.det(window_F(reference[m], xy[m])))
            cells = np.log(now[ok].sum() / start[ok].sum())
            q = np.percentile(np.log(now[ok] / start[ok]), [10, 50, 90])
            print(f"| {s:.3f} | {probe} | {m.sum()} ({ok.sum()}) | {fit:+.4f} | {cells:+.4f} | "
                  f"{q[0]:+.3f}, {q[1]:+.3f}, {q[2]:+.3f} |")


if __name__ == "__main__":
    main(sys.argv[1])
