#!/usr/bin/python3
"""Checks the RVE snapshots of a run of tests/coupling/rve_snapshots.json: the folder names
the point nearest to the requested position, snapshots exist at the start, every `every`
steps and at the end, every one holds all the grains, and the periodic cell has followed the
point: its area at each field output step over its initial area equals the point's volume
ratio from results.h5 (det F).

usage: check_rve_snapshots.py CASE OUTPUT_DIR"""
import json
import os
import sys

import h5py
import numpy as np

from mpm_lig_post.vtk_legacy import read_polydata


def cell_area(prefix):
    """In-plane area of the periodic cell drawn in PREFIX_cell.vtk (edges along axis 0 and 1)."""
    cell = read_polydata(prefix + "_cell.vtk")
    direction = cell.field("edge_direction", where="cell")
    segments = cell.lines()
    h0 = segments[direction == 0][0]
    h1 = segments[direction == 1][0]
    a, b = h0[1] - h0[0], h1[1] - h1[0]
    return abs(a[0] * b[1] - a[1] * b[0])


def main():
    case = json.load(open(sys.argv[1]))
    out = sys.argv[2]
    spec = case["output"]["rve_snapshots"]
    steps = case["analysis"]["end"]["steps"]
    grains = case["materials"][0]["rve"]["grains"]
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    with h5py.File(os.path.join(out, "results.h5"), "r") as h5:
        positions = h5["step_000000/positions"][:, :2]
        volume = {int(k[5:]): h5[k]["volume"][:] for k in h5 if k.startswith("step_")}
    target = np.array(spec["at"][0])
    point = int(np.argmin(np.linalg.norm(positions - target, axis=1)))
    folder = os.path.join(out, "snapshots", "point_%06d" % point)
    found = sorted(os.listdir(os.path.join(out, "snapshots")))
    check(found == ["point_%06d" % point], "snapshot folders %s, expected point_%06d" % (found, point))

    expected = sorted({0, steps} | set(range(0, steps + 1, spec["every"])))
    written = sorted(int(f[4:10]) for f in os.listdir(folder) if f.endswith("_grains.vtk"))
    check(written == expected, "snapshot steps %s, expected %s" % (written, expected))

    first = os.path.join(folder, "rve_000000")
    area0 = cell_area(first)
    for step in written:
        prefix = os.path.join(folder, "rve_%06d" % step)
        n = len(read_polydata(prefix + "_grains.vtk").points)
        check(n == grains, "step %d: %d grains, expected %d" % (step, n, grains))
        if step in volume:
            ratio = cell_area(prefix) / area0
            det_f = volume[step][point] / volume[0][point]
            check(abs(ratio - det_f) < 1e-6 * det_f,
                  "step %d: cell area ratio %.9f, point volume ratio %.9f" % (step, ratio, det_f))
            print("step %d: cell area ratio %.9f, det F %.9f" % (step, ratio, det_f))
    moved = [s for s in written if s in volume and abs(volume[s][point] / volume[0][point] - 1) > 1e-4]
    check(moved, "the point's volume never changed: the check would prove nothing")
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
