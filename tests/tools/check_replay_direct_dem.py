#!/usr/bin/python3
"""Checks of tools/replay_direct_dem.py on the tiny direct-DEM run of check_direct_dem.py.

usage: check_replay_direct_dem.py WORK RUN MPM_LIG
  RUN: a direct-DEM run of tests/tools/direct_dem_tiny.json with --probes (direct_dem_real's)

- bad input: exit 2, named, on one line, the output folder not created (a torn window,
  det F <= 0, and for a free volume a window without compression among them);
- a replay of the probe "far" on one RVE: exit 0, one RVE history row per probe row, and the
  RVE's Hencky strain at every row equal to 1/2 ln(F F^T) of the probe's F (the path reached
  the RVE as the grains went through it), replay.json and replay.png written;
- the same with --volume free: the RVE's in-plane deviatoric strain is the probe's, its p the
  grains' within 2 % at every row after the first (its volume follows their stress, not
  det F), and the
  volumetric strains of both are in the --at state;
- the same with --volume cells: the RVE's volumetric strain is the grains' own
  (cells_volumetric) and its deviatoric strain the probe's at every row; a probes.csv without
  the column (an earlier tool's) refused with exit 2.
"""
import json
import os
import shutil
import sys

import numpy as np

from checking import check, finish
from checking import tool as run_tool

HERE = os.path.dirname(os.path.abspath(__file__))
TINY = os.path.join(HERE, "direct_dem_tiny.json")

def tool(args):
    return run_tool("replay_direct_dem.py", args)


def hencky_left(F):
    """1/2 ln(F F^T) of a 2 x 2 F."""
    values, vectors = np.linalg.eigh(F @ F.T)
    return vectors @ np.diag(0.5 * np.log(values)) @ vectors.T


def damaged(work, run, column, value):
    """A copy of RUN whose probe far has `value` in `column` at its third row."""
    copy = os.path.join(work, f"damaged_{column}")
    os.makedirs(copy)
    shutil.copy(os.path.join(run, "summary.json"), copy)
    with open(os.path.join(run, "probes.csv")) as f:
        lines = f.read().splitlines()
    header = lines[0].split(",")
    far = [k for k, line in enumerate(lines) if line.startswith("far,")]
    row = lines[far[2]].split(",")
    row[header.index(column)] = repr(value)
    lines[far[2]] = ",".join(row)
    with open(os.path.join(copy, "probes.csv"), "w") as f:
        f.write("\n".join(lines) + "\n")
    return copy


def main():
    work, run, mpm_lig = sys.argv[1:4]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    empty = os.path.join(work, "no_probes")
    os.makedirs(empty)
    full = os.path.join(work, "not_empty")
    os.makedirs(full)
    open(os.path.join(full, "x"), "w").close()
    cases = [
        ("a run without probes", [TINY, empty, "--mpm-lig", mpm_lig], "probes.csv"),
        ("no such probe", [TINY, run, "--probes", "keel", "--mpm-lig", mpm_lig],
         "--probes keel"),
        ("no such mpm_lig", [TINY, run, "--mpm-lig", "/nonexistent/mpm_lig"], "--mpm-lig"),
        ("an output folder that is not empty", [TINY, run, "--mpm-lig", mpm_lig], "not empty"),
        ("a seed given twice", [TINY, run, "--seeds", "3", "3", "--mpm-lig", mpm_lig],
         "--seeds"),
        ("a negative --at", [TINY, run, "--at", "-0.1", "--mpm-lig", mpm_lig], "--at"),
        ("a torn window", [TINY, damaged(work, run, "F22", -0.5), "--mpm-lig", mpm_lig],
         "probe far: det F <= 0"),
        ("no compression, free volume", [TINY, damaged(work, run, "p", -1.0), "--mpm-lig",
                                         mpm_lig, "--volume", "free"], "probe far: p <= 0"),
    ]
    for name, args, key in cases:
        out = full if "not empty" in name else os.path.join(work, "out_" + name.replace(" ", "_"))
        code, _, stderr = tool(args + ["-o", out])
        check(code == 2 and key in stderr and len(stderr.strip().splitlines()) == 1
              and "Traceback" not in stderr, f"{name}: exit {code}, one line naming '{key}': "
              f"{stderr.strip()[:150]}")
        if "not empty" not in name:
            check(not os.path.exists(out), f"{name}: no output folder created")
    out = os.path.join(work, "replay")
    code, stdout, stderr = tool([TINY, run, "-o", out, "--mpm-lig", mpm_lig, "--probes", "far",
                                 "--seeds", "11", "--at", "0.05"])
    check(code == 0, f"the replay of probe far ends with exit 0 ({stderr.strip()[-200:]})")
    if code != 0:
        return
    rows = np.genfromtxt(os.path.join(run, "probes.csv"), delimiter=",", names=True,
                         dtype=None, encoding=None)
    far = rows[rows["probe"] == "far"]
    history = np.genfromtxt(os.path.join(out, "runs", "far_s11", "history.csv"), delimiter=",",
                            names=True)
    check(len(history) == len(far), f"{len(history)} RVE rows for {len(far)} probe rows")
    worst = 0.0
    for k in range(min(len(history), len(far))):
        F = np.array([[far["F11"][k], far["F12"][k]], [far["F21"][k], far["F22"][k]]])
        want = hencky_left(F)
        got = np.array([[history["e_xx"][k], history["e_xy"][k]],
                        [history["e_xy"][k], history["e_yy"][k]]])
        worst = max(worst, np.abs(got - want).max())
    check(worst < 1e-9, f"the RVE's Hencky strain is 1/2 ln(F F^T) of the probe's F at every "
          f"row (worst {worst:.2e})")
    report = json.load(open(os.path.join(out, "replay.json")))
    r = report["probes"]["far"]
    check(r["rows"] == len(far) and "11" in r["seeds"] and
          np.isfinite(r["seeds"]["11"]["mean_abs_dp_over_p0"]),
          "replay.json: the probe's rows and the seed's differences")
    k = int(np.argmin(np.abs(far["s_over_B"] - 0.05)))
    state = r["at"].get("0.05", {})
    p0 = report["p0"]
    check(abs(state.get("grains_p_over_p0", np.nan) - far["p"][k] / p0) < 1e-12 and
          abs(state.get("rve_p_over_p0", np.nan) - history["p"][k] / p0) < 1e-12 and
          abs(state.get("rve_ratio", np.nan) - history["q"][k] / history["p"][k]) < 1e-12,
          f"--at 0.05: the grains' and the RVE's p and q/p of row {k} (s/B "
          f"{far['s_over_B'][k]:.3f}): {state}")
    check(os.path.getsize(os.path.join(out, "replay.png")) > 0, "replay.png drawn")
    check("| far |" in stdout, "the table printed")
    free_volume(work, run, mpm_lig, far)
    cells_volume(work, run, mpm_lig, far)


def deviatoric_gap(history, far, n):
    """The largest difference between the RVE's in-plane deviatoric Hencky strain and that of
    the probe's F over the first n rows."""
    worst = 0.0
    for k in range(n):
        F = np.array([[far["F11"][k], far["F12"][k]], [far["F21"][k], far["F22"][k]]])
        want = hencky_left(F)
        got = np.array([[history["e_xx"][k], history["e_xy"][k]],
                        [history["e_xy"][k], history["e_yy"][k]]])
        worst = max(worst, np.abs((got - np.trace(got) / 2 * np.eye(2)) -
                                  (want - np.trace(want) / 2 * np.eye(2))).max())
    return worst


def cells_volume(work, run, mpm_lig, far):
    out = os.path.join(work, "replay_cells")
    code, _, stderr = tool([TINY, run, "-o", out, "--mpm-lig", mpm_lig, "--probes", "far",
                            "--seeds", "11", "--volume", "cells"])
    check(code == 0, f"--volume cells: exit 0 ({stderr.strip()[-200:]})")
    if code == 0:
        history = np.genfromtxt(os.path.join(out, "runs", "far_s11", "history.csv"),
                                delimiter=",", names=True)
        n = min(len(history), len(far))
        worst_vol = float(np.max(np.abs(history["e_xx"][:n] + history["e_yy"][:n] -
                                        far["cells_volumetric"][:n])))
        check(len(history) == len(far) and worst_vol < 1e-9 and
              np.abs(far["cells_volumetric"]).max() > 1e-6,
              f"--volume cells: the RVE's volumetric strain is the grains' cells' at every row "
              f"(worst {worst_vol:.1e}; theirs up to {np.abs(far['cells_volumetric']).max():.4f})")
        worst_dev = deviatoric_gap(history, far, n)
        check(worst_dev < 1e-9, f"--volume cells: the RVE's deviatoric strain is the probe's "
              f"(worst {worst_dev:.1e})")
    # an earlier tool's probes.csv, without the column
    older = os.path.join(work, "older_probes")
    os.makedirs(older)
    shutil.copy(os.path.join(run, "summary.json"), older)
    with open(os.path.join(run, "probes.csv")) as f:
        lines = [line.rsplit(",", 1)[0] for line in f.read().splitlines()]
    with open(os.path.join(older, "probes.csv"), "w") as f:
        f.write("\n".join(lines) + "\n")
    refused = os.path.join(work, "replay_cells_older")
    code, _, stderr = tool([TINY, older, "-o", refused, "--mpm-lig", mpm_lig, "--probes", "far",
                            "--seeds", "11", "--volume", "cells"])
    check(code == 2 and "cells_volumetric" in stderr and not os.path.exists(refused),
          f"--volume cells on a probes.csv without the column: exit {code}, named, nothing "
          f"created ({stderr.strip()[:120]})")


def free_volume(work, run, mpm_lig, far):
    out = os.path.join(work, "replay_free")
    code, _, stderr = tool([TINY, run, "-o", out, "--mpm-lig", mpm_lig, "--probes", "far",
                            "--seeds", "11", "--at", "0.05", "--volume", "free"])
    check(code == 0, f"--volume free: exit 0 ({stderr.strip()[-200:]})")
    if code != 0:
        return
    history = np.genfromtxt(os.path.join(out, "runs", "far_s11", "history.csv"), delimiter=",",
                            names=True)
    n = min(len(history), len(far))
    # row 0 is the RVE's prepared packing, at its own p0: the servo holds p from the first
    # increment on
    worst_p = float(np.max(np.abs(history["p"][1:n] - far["p"][1:n]) / far["p"][1:n]))
    worst_dev = deviatoric_gap(history, far, n)
    check(len(history) == len(far) and worst_p <= 0.02,
          f"--volume free: the RVE's p is the grains' within 2 % at every row after the first ({worst_p:.2%})")
    check(worst_dev < 1e-6, f"--volume free: the RVE's deviatoric strain is the probe's "
          f"(worst {worst_dev:.1e})")
    state = json.load(open(os.path.join(out, "replay.json")))["probes"]["far"]["at"]["0.05"]
    k = int(np.argmin(np.abs(far["s_over_B"] - 0.05)))
    det = far["F11"][k] * far["F22"][k] - far["F12"][k] * far["F21"][k]
    check(abs(state["grains_volumetric"] - np.log(det)) < 1e-12 and
          abs(state["rve_volumetric"] - history["e_vol"][k]) < 1e-12,
          f"--volume free: the volumetric strains at s/B 0.05 ({state['grains_volumetric']:.2e} "
          f"grains, {state['rve_volumetric']:.2e} RVE)")


if __name__ == "__main__":
    main()
    finish()
