#!/usr/bin/python3
"""Where a window's volume change sits: in the grains that carry its shear, or in the others.

Between two snapshots, each grain's local shear (the least-squares deformation gradient of
its neighbours within 2.5 mean diameters, as tools/rve_localisation.py) and its Voronoi cell.
The grains of a window are split into the most sheared ones that carry half of the window's
summed shear (the "slip" grains: their share of the grains is the half-share fraction) and
the rest (the "matrix"); printed for each part: its share of the grains, its mean shear and
the change of its summed Voronoi area, ln(sum A / sum A0), and for a direct DEM its grains' own
mean stress at both snapshots (Love-Weber over each grain's cell). The same for the grains of a direct
DEM's probe windows and for RVEs replayed on those windows' paths, side by side.

usage:
  grain_split.py grains RUN_DIR --between S0 S1 [--windows NAME ...]
      RUN_DIR a tools/direct_dem.py run with --probes and --snapshots at S0 and S1 (s/B; S0
      may be 0, the start of loading); the grains near a side plane mirrored across it, so
      that their cells end at the plane;
      grains whose cell is open or larger than 2.5 pi r^2 (at a wall or the free surface) are
      left out.
  grain_split.py rve REPLAY_DIR PROBE --between S0 S1
      REPLAY_DIR a tools/replay_direct_dem.py output whose element cases were run again with
      "snapshot_every" 1 (runs/PROBE_sSEED/snapshots); the increments nearest S0 and S1 by
      the probe's path. The RVE's cells are periodic (its 3 x 3 images).
"""
import argparse
import json
import os
import sys

import numpy as np
from scipy.spatial import cKDTree

TOOLS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "tools")
sys.path.insert(0, TOOLS)
from mpm_lig_post.commands.rve_localisation import local_shear, read_snapshot, shear  # noqa: E402
from mpm_lig_post.direct_dem.cells import closed, voronoi_areas, walled_areas  # noqa: E402
from mpm_lig_post.direct_dem.probes import members, read_probes  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402
from window_stress import set_p_q, snapshot_contacts  # noqa: E402  (this folder's)

REACH = 2.5  # neighbours within this many mean diameters, as rve_localisation's default


def periodic_areas(xy, sides):
    """Voronoi areas of a periodic cell's grains (the cell's 3 x 3 images; the central copy)."""
    shifts = [i * sides[:, 0] + j * sides[:, 1] for i in (0, -1, 1) for j in (0, -1, 1)]
    return voronoi_areas(np.vstack([xy + s for s in shifts]))[: len(xy)]


def open_shear(x0, x1, reach_length):
    """Each grain's local shear between two configurations of a non-periodic set of grains."""
    tree = cKDTree(x0)
    gamma = np.full(len(x0), np.nan)
    for k, near in enumerate(tree.query_ball_point(x0, reach_length)):
        near = [j for j in near if j != k]
        if len(near) < 3:
            continue
        a = x0[near] - x0[k]
        b = x1[near] - x1[k]
        gamma[k] = shear(np.linalg.lstsq(a, b, rcond=None)[0].T)
    return gamma


def split(gamma, area0, area1, solid, pressures=None):
    """The slip grains (the most sheared, carrying half the summed shear) and the matrix."""
    order = np.argsort(gamma)[::-1]
    carried = np.cumsum(gamma[order]) / gamma.sum()
    n_slip = int(np.searchsorted(carried, 0.5)) + 1
    slip = np.zeros(len(gamma), bool)
    slip[order[:n_slip]] = True

    def part(mask):
        row = {"share": float(mask.mean()), "mean_shear": float(gamma[mask].mean()),
               "volumetric": float(np.log(area1[mask].sum() / area0[mask].sum())),
               "void_ratio": [float(a[mask].sum() / solid[mask].sum() - 1.0)
                              for a in (area0, area1)]}
        if pressures is not None:  # the part's own mean stress at both snapshots
            row["p"] = pressures(mask)
        return row

    return {"grains": len(gamma), "slip": part(slip), "matrix": part(~slip),
            "all": part(np.ones(len(gamma), bool))}


def grains_mode(run, s0, s1, windows):
    summary = json.load(open(os.path.join(run, "summary.json")))
    B, (_, ly) = summary["B"], summary["block"]
    reference = np.load(os.path.join(run, "reference.npz"))["xy"]
    ds_over_B = summary["footing_speed"] * summary["time_step"] / B
    folder = os.path.join(run, "snapshots")
    snaps = {int(n.split("_")[1]) * ds_over_B: os.path.join(folder, n)
             for n in os.listdir(folder) if n.endswith("_grains.vtk")}

    def nearest(s):
        at = min(snaps, key=lambda t: abs(t - s))
        if abs(at - s) > 0.005:
            sys.exit(f"no snapshot near s/B {s} (have {sorted(round(t, 3) for t in snaps)})")
        g = read_polydata(snaps[at])
        return at, g.points[:, :2], g.field("radius"), snaps[at]

    ids = np.load(os.path.join(run, "reference.npz"))["ids"]
    t1, x1, radius, snap1 = nearest(s1)
    lx, reach = summary["block"][0], 4.0 * radius.max()
    a1 = walled_areas(x1, lx, reach)
    states = [(x1, a1, snapshot_contacts(snap1, ids))]
    # The start of loading has no snapshot: its positions are the reference (same order).
    if s0 == 0:
        t0, x0, a0 = 0.0, reference, walled_areas(reference, lx, reach)
    else:
        t0, x0, _, snap0 = nearest(s0)
        a0 = walled_areas(x0, lx, reach)
        states.insert(0, (x0, a0, snapshot_contacts(snap0, ids)))
    inner = closed(a0, radius) & closed(a1, radius)
    gamma = open_shear(x0, x1, REACH * 2.0 * radius.mean())
    rows = {}
    for name in windows or sorted(summary["probes"]):
        w = summary["probes"][name]
        centre = np.array([w["x_over_B"] * B, ly - w["depth_over_B"] * B])
        ok = members(reference, centre, w["side_over_B"] * B) & inner & np.isfinite(gamma)

        def pressures(part, ok=ok):
            """p [Pa] of the window's grains where `part` (of the window's) at both snapshots."""
            inside = np.zeros(len(ok), bool)
            inside[np.flatnonzero(ok)[part]] = True
            return [float(set_p_q(inside, x, radius, contacts, a, summary["thickness"])[0])
                    for x, a, contacts in states]

        rows[name] = split(gamma[ok], a0[ok], a1[ok], np.pi * radius[ok] ** 2,
                           pressures if len(states) == 2 else None)
    return {"s_over_B": [t0, t1], "windows": rows}


def rve_mode(replay, probe, s0, s1):
    runs = os.path.join(replay, "runs")
    with open(os.path.join(runs, probe + "_s" + str(json.load(open(os.path.join(
            replay, "replay.json")))["seeds"][0]), "history.csv")) as f:
        replayed = sum(1 for _ in f) - 1  # the rows the replay ran (to its --upto)
    path = read_probes_path(replay, probe)[:replayed]
    k0, k1 = (int(np.argmin(np.abs(path - s))) for s in (s0, s1))
    rows = {}
    for name in sorted(os.listdir(runs)):
        folder = os.path.join(runs, name, "snapshots")
        wanted = [os.path.join(folder, f"rve_{k:06d}_grains.vtk") for k in (k0, k1)]
        if not (name.startswith(probe + "_s") and all(map(os.path.isfile, wanted))):
            continue
        first = read_snapshot(os.path.join(folder, f"rve_{k0:06d}"))
        last = read_snapshot(os.path.join(folder, f"rve_{k1:06d}"))
        gamma, _ = local_shear(first[0], last[0], (first[1], last[1]), first[2], last[2], REACH)
        rows[name] = split(gamma, periodic_areas(first[0], first[2]),
                           periodic_areas(last[0], last[2]), np.pi * first[1] ** 2)
    if not rows:
        sys.exit(f"{runs}: no {probe}_sSEED run with snapshots")
    return {"s_over_B": [float(path[k0]), float(path[k1])], "increments": [k0, k1], "rves": rows}


def read_probes_path(replay, probe):
    """s/B of each increment of the probe's replay (its path's rows are the direct DEM's)."""
    with open(os.path.join(replay, "replay.json")) as f:
        run = json.load(f)["run"]
    return read_probes(run)[probe]["s_over_B"]


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("mode", choices=("grains", "rve"))
    p.add_argument("folder")
    p.add_argument("probe", nargs="?")
    p.add_argument("--between", nargs=2, type=float, required=True, metavar=("S0", "S1"))
    p.add_argument("--windows", nargs="+")
    p.add_argument("--json")
    a = p.parse_args()
    if a.mode == "grains":
        out = grains_mode(a.folder, *a.between, a.windows)
        table = out["windows"]
    else:
        out = rve_mode(a.folder, a.probe, *a.between)
        table = out["rves"]
    print(f"s/B {out['s_over_B'][0]:.3f} to {out['s_over_B'][1]:.3f}")
    print("| | grains | slip: share, mean shear, ln(A/A0) | matrix: share, mean shear, ln(A/A0) "
          "| all: ln(A/A0) |")
    print("|---|---|---|---|---|")
    for name, r in table.items():
        s, m = r["slip"], r["matrix"]
        print(f"| {name} | {r['grains']} | {s['share']:.2f}, {s['mean_shear']:.3f}, "
              f"{s['volumetric']:+.4f} | {m['share']:.2f}, {m['mean_shear']:.3f}, "
              f"{m['volumetric']:+.4f} | {r['all']['volumetric']:+.4f} |")
    for name, r in table.items():
        print(f"{name}: void ratio at the two snapshots: " + ", ".join(
            f"{k} {r[k]['void_ratio'][0]:.4f} -> {r[k]['void_ratio'][1]:.4f}"
            for k in ("slip", "matrix", "all")))
    for name, r in table.items():
        if "p" in r["all"]:
            print(f"{name}: the grains' own mean stress at the two snapshots [kPa]: " + ", ".join(
                f"{k} {r[k]['p'][0] / 1e3:.0f} -> {r[k]['p'][1] / 1e3:.0f}"
                for k in ("slip", "matrix", "all")))
    if a.json:
        with open(a.json, "w") as f:
            json.dump(out, f, indent=1)


if __name__ == "__main__":
    main()
