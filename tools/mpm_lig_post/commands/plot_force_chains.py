"""Force chains of an RVE before and after loading (seed Fig. 4), side by side.

usage: plot_force_chains.py OUTPUT_DIR [-o picture.png] [--steps A B] [--rve SUBDIR|NAME]
                            [--plane xy|xz|yz]

Reads the RVE snapshots (PREFIX_grains.vtk, PREFIX_contacts.vtk, PREFIX_cell.vtk, legacy VTK
as src/rve/snapshot.cpp writes them; PREFIX = rve_NNNNNN, NNNNNN the increment) found under
OUTPUT_DIR (e.g. OUTPUT_DIR/snapshots). Default: the first and the last snapshot. Grains are
circles (3D: spheres projected on --plane, default xz), contact forces centre-to-centre lines
of width proportional to |f|, on one force scale for both panels; the periodic cell dashed.
With several RVEs (an MPM run's output.rve_snapshots: snapshots/point_NNNNNN/, NNNNNN the
material point, the increment the MPM step) --rve names the folder, by its path under
OUTPUT_DIR or by its own name.
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import glob  # noqa: E402
import os  # noqa: E402
import re  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402

AXES = {"x": 0, "y": 1, "z": 2}
MAX_WIDTH = 4.0  # line width [pt] of the largest force


def snapshot_sets(directory):
    """{folder: {increment: prefix}} of every complete-enough snapshot under `directory`."""
    found = {}
    pattern = os.path.join(directory, "**", "*_grains.vtk")
    for grains in glob.glob(pattern, recursive=True):
        prefix = grains[: -len("_grains.vtk")]
        match = re.search(r"(\d+)$", prefix)
        if match:
            found.setdefault(os.path.dirname(prefix), {})[int(match.group(1))] = prefix
    return found


def choose(directory, rve, steps):
    """The two snapshot prefixes to draw."""
    sets = snapshot_sets(directory)
    if not sets:
        raise InputError(f"{directory}: no RVE snapshot (*_grains.vtk) found")
    if rve is not None:
        folder = os.path.normpath(os.path.join(directory, rve))
        named = [f for f in sets if os.path.basename(f) == os.path.basename(os.path.normpath(rve))]
        if folder not in sets and len(named) == 1:
            folder = named[0]  # a folder's own name, e.g. point_000132 of an MPM run
        if folder not in sets:
            raise InputError(f"{folder}: no RVE snapshot there "
                             f"(snapshot folders: {', '.join(sorted(sets))})")
    elif len(sets) > 1:
        raise InputError(f"{directory}: snapshots of several RVEs, choose one with --rve "
                         f"({', '.join(os.path.relpath(f, directory) for f in sorted(sets))})")
    else:
        folder = next(iter(sets))
    by_step = sets[folder]
    available = sorted(by_step)
    if steps is None:
        steps = (available[0], available[-1])
    for s in steps:
        if s not in by_step:
            raise InputError(f"{folder}: no snapshot of increment {s} (have {available})")
    return [(s, by_step[s]) for s in steps]


class Snapshot:
    """Grain centres and radii, contact segments and forces, cell edges of one prefix."""

    def __init__(self, prefix):
        grains = read_polydata(prefix + "_grains.vtk")
        self.centres = grains.points
        self.radii = grains.field("radius")
        contacts = read_polydata(prefix + "_contacts.vtk")
        self.segments = contacts.lines()
        self.force = contacts.field("force", "cell") if len(self.segments) else np.zeros(0)
        cell_path = prefix + "_cell.vtk"
        self.cell = read_polydata(cell_path).lines() if os.path.isfile(cell_path) else None
        self.dimension = 2 if np.allclose(self.centres[:, 2], self.centres[0, 2]) else 3


def draw_panel(ax, snap, plane, force_max, title):
    from matplotlib.collections import EllipseCollection, LineCollection

    i, j = plane
    # 3D: far grains first so near ones cover them
    depth_axis = 3 - i - j
    order = np.argsort(snap.centres[:, depth_axis]) if snap.dimension == 3 else slice(None)
    centres, radii = snap.centres[order], snap.radii[order]
    diameters = 2 * radii
    ax.add_collection(EllipseCollection(
        diameters, diameters, np.zeros_like(radii), units="xy", offsets=centres[:, [i, j]],
        offset_transform=ax.transData, facecolors="0.88", edgecolors="0.55", linewidths=0.4,
        alpha=0.9 if snap.dimension == 3 else 1.0))
    if len(snap.force):
        widths = MAX_WIDTH * snap.force / force_max
        ax.add_collection(LineCollection(snap.segments[:, :, [i, j]], linewidths=widths,
                                         colors="k", capstyle="round"))
    if snap.cell is not None:
        edges = snap.cell[:, :, [i, j]]
        ax.add_collection(LineCollection(edges, colors="C3", linewidths=0.8, linestyles="--"))
        corners = snap.cell.reshape(-1, 3)[:, [i, j]]
    else:
        corners = centres[:, [i, j]]
    pad = radii.max()
    lo = np.minimum(corners.min(axis=0), (centres[:, [i, j]] - pad).min(axis=0))
    hi = np.maximum(corners.max(axis=0), (centres[:, [i, j]] + pad).max(axis=0))
    ax.set_xlim(lo[0], hi[0])
    ax.set_ylim(lo[1], hi[1])
    ax.set_aspect("equal")
    names = "xyz"
    ax.set_xlabel(f"{names[i]} [m]")
    ax.set_ylabel(f"{names[j]} [m]")
    ax.set_title(title)


def main():
    p = cli.parser(__doc__.split("\n")[0], "force_chains.png")
    p.add_argument("--steps", nargs=2, type=cli.non_negative_int, metavar=("A", "B"),
                   help="increments of the two snapshots (default: first and last)")
    p.add_argument("--rve", help="snapshot folder, relative to OUTPUT_DIR, when there are several")
    p.add_argument("--plane", choices=["xy", "xz", "yz"],
                   help="projection plane (default xy in 2D, xz in 3D)")
    args = p.parse_args()
    directory = cli.output_dir(args)
    chosen = choose(directory, args.rve, args.steps)
    snaps = [Snapshot(prefix) for _, prefix in chosen]
    plane_name = args.plane or ("xy" if snaps[0].dimension == 2 else "xz")
    plane = (AXES[plane_name[0]], AXES[plane_name[1]])
    force_max = max([s.force.max() for s in snaps if len(s.force)], default=1.0)
    fig, axes = figures.subplots(1, 2, figsize=(11, 5.4))
    for ax, (step, _), snap, label in zip(axes, chosen, snaps, "ab"):
        mean = snap.force.mean() if len(snap.force) else 0.0
        draw_panel(ax, snap, plane, force_max,
                   f"({label}) increment {step}: {len(snap.force)} contacts, "
                   f"mean |f| = {mean:.3g} N")
    from matplotlib.lines import Line2D

    handles = [Line2D([], [], color="k", lw=MAX_WIDTH * f) for f in (1.0, 0.5, 0.1)]
    labels = [f"|f| = {f * force_max:.3g} N" for f in (1.0, 0.5, 0.1)]
    handles.append(Line2D([], [], color="C3", lw=0.8, ls="--"))
    labels.append("periodic cell")
    fig.legend(handles, labels, loc="lower center", ncol=4, frameon=False)
    fig.tight_layout(rect=(0, 0.07, 1, 1))
    figures.save(fig, cli.picture_path(args), args.dpi)


def entry():
    """The command: tools/plot_force_chains.py in a checkout, mpm-lig-plot-force-chains installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
