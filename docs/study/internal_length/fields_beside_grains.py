#!/usr/bin/python3
"""The multiscale footing's deviatoric strain beside the grains', one colour scale: the direct
DEM's eps_q coarse-grained on the case's points (its results.h5, written by tools/direct_dem.py)
and each mpm_lig run's points, at the output nearest one settlement.

usage: fields_beside_grains.py DEM_RUN[:LABEL] MPM_RUN:LABEL ... -o PNG [--at 0.5]
       [--eq-max 1.0] [--speed 0.5] [--width 0.2] [--more-dem DEM_RUN:LABEL ...]
       [--mpm-only] [--since S]

--mpm-only reads the first run as an mpm_lig run too (meshes set beside each other).
--since S shows the MPM runs' strain gained from s/B = S to --at (eps_q of the difference of
their Hencky strains), where the band is slipping now rather than where it has been.

--more-dem adds direct DEM runs after the first (e.g. the footing on a column beside the
one-grain block).

The MPM runs' settlement is speed x time (the footing's constant speed, m/s, and its width B);
the direct DEM's output steps are labelled by 1000 s/B.
"""
import argparse
import os
import sys

import h5py
import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.tri as mtri  # noqa: E402


def nearest_step(path, s_of):
    """(group name, s/B) of the output nearest the wanted settlement, s_of(attrs) its s/B."""
    with h5py.File(path, "r") as f:
        steps = [(k, s_of(f[k].attrs)) for k in f if k.startswith("step_")]
    return steps


def field(path, group):
    with h5py.File(path, "r") as f:
        g = f[group]
        return g["positions"][:, :2], g["deviatoric_strain"][()].ravel()


def equivalent_strain(e):
    """sqrt(2/3 e':e') of strains in Voigt order xx yy zz xy xz yz (tensor shears)."""
    mean = e[:, :3].sum(axis=1) / 3.0
    dev = (e[:, :3] - mean[:, None]) ** 2
    return np.sqrt(2.0 / 3.0 * (dev.sum(axis=1) + 2.0 * (e[:, 3:] ** 2).sum(axis=1)))


def strain_gained(path, group_from, group_to):
    with h5py.File(path, "r") as f:
        gained = f[group_to]["strain"][()] - f[group_from]["strain"][()]
        return f[group_to]["positions"][:, :2], equivalent_strain(gained)


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("dem_run")
    a.add_argument("mpm", nargs="+", metavar="MPM_RUN:LABEL")
    a.add_argument("-o", "--output", required=True)
    a.add_argument("--at", type=float, default=0.5)
    a.add_argument("--eq-max", type=float, default=1.0)
    a.add_argument("--speed", type=float, default=0.5)
    a.add_argument("--width", type=float, default=0.2)
    a.add_argument("--more-dem", nargs="*", default=[], metavar="DEM_RUN:LABEL")
    a.add_argument("--mpm-only", action="store_true")
    a.add_argument("--since", type=float)
    args = a.parse_args()
    dem_runs = [] if args.mpm_only else [args.dem_run] + args.more_dem
    mpm_runs = ([args.dem_run] if args.mpm_only else []) + args.mpm
    panels = []
    for item in dem_runs:
        run, _, label = item.partition(":")
        panels.append((os.path.join(run, "results.h5"), label or "grains (direct DEM)",
                       lambda attrs: attrs["step"] / 1000.0, False))
    for item in mpm_runs:
        run, _, label = item.partition(":")
        panels.append((os.path.join(run, "results.h5"), label or os.path.basename(run),
                       lambda attrs: args.speed * attrs["time"] / args.width, True))
    fig, axes = plt.subplots(1, len(panels), figsize=(3.3 * len(panels), 3.6), squeeze=False)
    levels = np.linspace(0.0, args.eq_max, 21)
    for ax, (path, label, s_of, mpm) in zip(axes[0], panels):
        if not os.path.isfile(path):
            sys.exit(f"{path}: no such file")
        steps = nearest_step(path, s_of)
        group, s = min(steps, key=lambda gs: abs(gs[1] - args.at))
        xy, eq = field(path, group)
        if mpm and args.since is not None:
            group_from, s_from = min(steps, key=lambda gs: abs(gs[1] - args.since))
            xy, eq = strain_gained(path, group_from, group)
            label = f"{label}, gained from s/B {s_from:.2f}"
        tri = mtri.Triangulation(xy[:, 0], xy[:, 1])
        # triangles spanning a gap (over the footing, where points have drawn apart) hidden
        corners = xy[tri.triangles]
        longest = np.max(np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2), axis=1)
        tri.set_mask(longest > 3.0 * np.median(longest))
        shown = ax.tricontourf(tri, np.minimum(eq, args.eq_max), levels=levels, cmap="viridis")
        ax.set_aspect("equal")
        ax.set_xlim(0.0, 0.6)
        ax.set_ylim(0.0, 0.8)
        ax.set_title(f"{label}\ns/B = {s:.2f}", fontsize=9)
        ax.set_xlabel("x [m]")
    axes[0][0].set_ylabel("y [m]")
    what = "ε_q" if args.since is None else "ε_q (MPM: gained)"
    fig.colorbar(shown, ax=list(axes[0]), shrink=0.8, label=f"{what} (cut at {args.eq_max:g})")
    fig.savefig(args.output, dpi=130, bbox_inches="tight")
    print(f"wrote {args.output}")


if __name__ == "__main__":
    main()
