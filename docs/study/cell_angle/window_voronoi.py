#!/usr/bin/python3
"""The volume of a direct-DEM probe window's grains, two ways: the least-squares det F that
probes.csv records, and the sum of the grains' Voronoi cells (grains beside a wall or the free
surface, whose cells are open or larger than 2.5 pi r^2, left out), at every grain snapshot.

usage: docs/study/cell_angle/window_voronoi.py RUN_DIR   (a tools/direct_dem.py run with
--probes and --snapshots; the numbers of docs/direct_dem.md "Can the RVE localise?")
"""
import json
import os
import sys

import numpy as np
from scipy.spatial import Voronoi

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..",
                                "tools"))
from mpm_lig_post.direct_dem.probes import members, window_F  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402


def voronoi_areas(xy):
    """Area of each point's Voronoi cell; nan where the cell is open."""
    v = Voronoi(xy)
    areas = np.full(len(xy), np.nan)
    for i, region in enumerate(v.point_region):
        corners = v.regions[region]
        if corners and -1 not in corners:
            x, y = v.vertices[corners].T
            areas[i] = 0.5 * abs(np.dot(x, np.roll(y, 1)) - np.dot(y, np.roll(x, 1)))
    return areas


def main(run):
    summary = json.load(open(os.path.join(run, "summary.json")))
    B = summary["B"]
    _, ly = summary["block"]
    reference = np.load(os.path.join(run, "reference.npz"))["xy"]
    start = voronoi_areas(reference)
    ds_over_B = summary["footing_speed"] * summary["time_step"] / B
    folder = os.path.join(run, "snapshots")
    print("| s/B | window | grains (inner) | ln det F, least squares | ln of the Voronoi sum | "
          "grains' ln(A/A0): 10th, 50th, 90th percentile |")
    print("|---|---|---|---|---|---|")
    for name in sorted(n for n in os.listdir(folder) if n.endswith("_grains.vtk")):
        grains = read_polydata(os.path.join(folder, name))
        xy, radius = grains.points[:, :2], grains.field("radius")
        now = voronoi_areas(xy)
        closed = 2.5 * np.pi * radius ** 2
        inner = np.isfinite(start) & np.isfinite(now) & (start < closed) & (now < closed)
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
