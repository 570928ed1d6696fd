#!/usr/bin/python3
"""Checks of tools/mpm_probes.py: an MPM footing run's points over a direct DEM's probe windows.

usage: check_mpm_probes.py WORK DEM_RUN MPM_LIG
  DEM_RUN: the tiny direct DEM with --probes (direct_dem_real's); the MPM run is
  tests/tools/footing_tiny.json (a Tresca footing, three footing widths wide).

- bad input: a window that holds no MPM point (--window 1e-4 B), a probe the DEM run does
  not have: exit 2 naming it, on one line, nothing written;
- the run's probes (wedge, far): exit 0; each window's side is the one the DEM run recorded for it; at
  s/B = 0 the MPM's p is the volume-weighted mean of its points in the wedge window, computed
  here from results.h5; the grains' volumetric strain at every row is ln det F of probes.csv.
"""
import json
import os
import shutil
import subprocess
import sys

import h5py
import numpy as np

from checking import check, finish
from checking import tool as run_tool

HERE = os.path.dirname(os.path.abspath(__file__))
CASE = os.path.join(HERE, "footing_tiny.json")


def tool(args):
    return run_tool("mpm_probes.py", args)


def main():
    work, dem, mpm_lig = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    mpm = os.path.join(work, "mpm")
    code = subprocess.call([mpm_lig, CASE, "--output", mpm], stdout=subprocess.DEVNULL)
    check(code == 0, f"the MPM footing ran ({code})")
    for args, named in ((["--probes", "wedge", "--window", "1e-4"], "probe wedge: no MPM point"),
                        (["--probes", "nowhere"], "nowhere")):
        out = os.path.join(work, "bad_" + args[1])
        code, _, err = tool([mpm, CASE, dem, "-o", out] + args)
        check(code == 2 and named in err and err.count("\n") == 1 and not os.path.exists(out),
              f"{' '.join(args)}: exit 2 naming it ({code}: {err.strip()})")

    out = os.path.join(work, "both")
    code, stdout, err = tool([mpm, CASE, dem, "-o", out])
    check(code == 0, f"the run's probes (wedge, far): exit 0 ({code}: {err.strip()})")
    if code != 0:
        return
    print(stdout)
    report = json.load(open(os.path.join(out, "mpm_probes.json")))
    recorded = json.load(open(os.path.join(dem, "summary.json")))["probes"]
    for name in ("wedge", "far"):
        check(abs(report["windows_over_B"][name] - recorded[name]["side_over_B"]) < 1e-12,
              f"probe {name}: the DEM run's own window ({report['windows_over_B'][name]:.4f} B)")
    rows = {}
    with open(os.path.join(out, "mpm_probes.csv")) as f:
        header = f.readline().strip().split(",")
        for line in f:
            v = line.strip().split(",")
            rows.setdefault(v[0], []).append([float(x) for x in v[1:]])
    col = {name: k for k, name in enumerate(header[1:])}
    wedge = np.array(rows["wedge"])

    # The MPM's p at s/B = 0, by hand: points of the wedge window at step 0.
    case = json.load(open(CASE))
    B, surface = case["rigid_bodies"][0]["width"][0], case["rigid_bodies"][0]["base"]
    w = recorded["wedge"]
    with h5py.File(os.path.join(mpm, "results.h5"), "r") as f:
        first = sorted(g for g in f if g.startswith("step_"))[0]
        x = f[first]["positions"][:, :2] - f[first]["displacement"][:, :2]
        s, v = f[first]["stress"][()], f[first]["volume"][()].ravel()
    centre = np.array([w["x_over_B"] * B, surface - w["depth_over_B"] * B])
    inside = np.all(np.abs(x - centre) <= 0.5 * w["side_over_B"] * B, axis=1)
    p = -0.5 * ((s[inside, 0] + s[inside, 1]) * v[inside]).sum() / v[inside].sum()
    p0 = report["p0"]
    check(wedge[0, col["s_over_B"]] == 0.0 and
          abs(wedge[0, col["mpm_p_over_p0"]] - p / p0) < 1e-5 * max(1.0, abs(p / p0)),
          f"the MPM's p at s/B 0 over the wedge's {int(inside.sum())} points "
          f"({wedge[0, col['mpm_p_over_p0']]:.6g} against {p / p0:.6g} p0)")

    # The grains' volumetric strain: ln det F of probes.csv's wedge rows.
    with open(os.path.join(dem, "probes.csv")) as f:
        h = f.readline().strip().split(",")
        F = [[float(r[h.index(c)]) for c in ("F11", "F12", "F21", "F22")]
             for r in (line.strip().split(",") for line in f) if r[0] == "wedge"]
    dets = [np.log(a * d - b * c) for a, b, c, d in F][:len(wedge)]
    check(np.allclose(wedge[:, col["grains_volumetric"]], dets, atol=1e-5),
          "the grains' volumetric strain is ln det F of their window")
    # ... and their own volume, the cells' column of probes.csv, carried over row for row
    with open(os.path.join(dem, "probes.csv")) as f:
        h = f.readline().strip().split(",")
        cells = [float(r[h.index("cells_volumetric")]) for r in
                 (line.strip().split(",") for line in f) if r[0] == "wedge"][:len(wedge)]
    check("grains_cells_volumetric" in col and
          np.allclose(wedge[:, col["grains_cells_volumetric"]], cells, atol=1e-5),
          "the grains' own volume change (their cells) carried into mpm_probes.csv")
    check(os.path.getsize(os.path.join(out, "mpm_probes.png")) > 10000, "picture written")


if __name__ == "__main__":
    main()
    finish()
