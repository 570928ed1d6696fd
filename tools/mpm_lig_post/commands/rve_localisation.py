"""Whether a 2D RVE deformed uniformly or in a band between two of its snapshots: each grain's
local shear and how unevenly the packing shares it.

usage: rve_localisation.py OUTPUT_DIR... [--steps A B] [--rve SUBDIR|NAME] [--reach R]
                           [--json FILE] [-o PNG] [--dpi N]

Reads the RVE snapshots of an element test or an MPM run (as tools/plot_force_chains.py finds
them; default the first and the last). The cell's deformation F between the two is
H_B M H_A^-1 (H the cell's sides; M the change of cell basis that the RVE's tilt reduction
may have made in between, the small unimodular matrix under which neighbouring grains stay
closest to their affine separation). Each grain's motion apart from F, taken to the nearest periodic image,
gives around every grain a least-squares deformation gradient over the grains within R mean
diameters (default 2.5) in the first snapshot, and its shear gamma = sqrt(2) |dev sym(F - 1)|.
Printed per run: the cell's own gamma, the grains' mean gamma, the half-share fraction (the
smallest fraction of the grains that carries half of the summed gamma: near 0.5 for a uniform
deformation, near half the band's share of the cell for a band) and the share of the 10 %
most sheared grains. Draws each run's grains coloured by gamma, with their periodic images
(default OUTPUT_DIR/rve_localisation.png, OUTPUT_DIR the first run).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import itertools  # noqa: E402
import json  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.commands.plot_force_chains import choose  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402

# Cell basis changes tried between two snapshots: integer entries in [-2, 2], determinant 1.
BASIS_CHANGES = [np.array(m, float).reshape(2, 2)
                 for m in itertools.product(range(-2, 3), repeat=4)
                 if round(np.linalg.det(np.array(m, float).reshape(2, 2))) == 1]


def read_snapshot(prefix):
    """(centres n x 2, radii n, cell sides 2 x 2 as columns a, b) of a 2D snapshot."""
    grains = read_polydata(prefix + "_grains.vtk")
    centres, radii = grains.points, grains.field("radius")
    if not np.allclose(centres[:, 2], centres[0, 2]):
        raise InputError(f"{prefix}_grains.vtk: 3D grains (this measure is for 2D RVEs)")
    cell_path = prefix + "_cell.vtk"
    if not os.path.isfile(cell_path):
        raise InputError(f"{cell_path}: missing (the cell is needed for the periodic images)")
    edges = read_polydata(cell_path).lines()
    if len(edges) != 12:
        raise InputError(f"{cell_path}: expected the cell's 12 edges, found {len(edges)}")
    # src/rve/snapshot.cpp writes the edges along a first (0-3), then b (4-7), then c.
    sides = np.column_stack([edges[0, 1, :2] - edges[0, 0, :2], edges[4, 1, :2] - edges[4, 0, :2]])
    return centres[:, :2], radii, sides


def nearest_image(d, sides):
    """Vectors d (n x 2) taken to their nearest periodic image in the lattice of `sides`."""
    fractions = np.linalg.solve(sides, d.T).T
    return d - np.round(fractions) @ sides.T


def neighbour_pairs(x0, sides0, cutoff):
    """(i, j, d) of every pair of grains closer than `cutoff` in the first snapshot, i < j,
    d = x0[j] - x0[i] at its nearest image."""
    i, j = np.triu_indices(len(x0), 1)
    d = nearest_image(x0[j] - x0[i], sides0)
    close = np.linalg.norm(d, axis=1) < cutoff
    if not close.any():
        raise InputError(f"no two grains closer than {cutoff:g} m in the first snapshot")
    return i[close], j[close], d[close]


def cell_deformation(x0, x1, sides0, sides1, pairs):
    """F of the cell and each grain's non-affine motion (n x 2, nearest image). Of the cell
    basis changes the RVE may have made between the snapshots, the one under which
    neighbouring grains (`pairs`) stay closest to their affine separation: a wrong one maps
    them a cell's width apart."""
    i, j, before = pairs
    after = nearest_image(x1[j] - x1[i], sides1)
    best = None
    for m in BASIS_CHANGES:
        F = sides1 @ m @ np.linalg.inv(sides0)
        spread = np.median(np.linalg.norm(after - before @ F.T, axis=1))
        if best is None or spread < best[0]:
            best = (spread, F)
    F = best[1]
    return F, nearest_image(x1 - x0 @ F.T, sides1)


def shear(F):
    """gamma = sqrt(2) |dev sym(F - 1)| of 2 x 2 gradients (... x 2 x 2)."""
    e = 0.5 * (F + np.swapaxes(F, -1, -2)) - np.eye(2)
    dev = e - 0.5 * np.trace(e, axis1=-2, axis2=-1)[..., None, None] * np.eye(2)
    return np.sqrt(2.0) * np.sqrt(np.sum(dev * dev, axis=(-2, -1)))


def local_shear(x0, x1, radii, sides0, sides1, reach):
    """(gamma of each grain, gamma of the cell) between two snapshots of one RVE."""
    if len(x0) != len(x1) or not np.allclose(radii[0], radii[1]):
        raise InputError("the two snapshots hold different grains")
    pairs = neighbour_pairs(x0, sides0, reach * 2.0 * radii[0].mean())
    F, u = cell_deformation(x0, x1, sides0, sides1, pairs)
    # Each grain's neighbours from the pairs, both ways, in the order of their index.
    i, j, d = pairs
    owner = np.concatenate([i, j])
    other = np.concatenate([j, i])
    offset = np.concatenate([d, -d])
    order = np.lexsort((other, owner))
    owner, other, offset = owner[order], other[order], offset[order]
    starts = np.searchsorted(owner, np.arange(len(x0) + 1))
    gamma = np.zeros(len(x0))
    for k in range(len(x0)):
        near = slice(starts[k], starts[k + 1])
        if starts[k + 1] - starts[k] < 3:
            raise InputError(f"grain {k}: fewer than 3 grains within {reach:g} diameters")
        A = offset[near]
        B = A @ F.T + nearest_image(u[other[near]] - u[k], sides1)
        local = np.linalg.lstsq(A, B, rcond=None)[0].T
        gamma[k] = shear(local)
    return gamma, float(shear(F))


def half_share(gamma):
    """The smallest fraction of the grains whose gamma sums to half of the total."""
    ordered = np.sort(gamma)[::-1]
    carried = np.cumsum(ordered) / ordered.sum()
    return (np.searchsorted(carried, 0.5) + 1) / len(gamma)


def top_share(gamma, fraction=0.1):
    ordered = np.sort(gamma)[::-1]
    return float(ordered[: max(1, int(round(fraction * len(gamma))))].sum() / ordered.sum())


def measure(directory, rve, steps, reach):
    chosen = choose(directory, rve, steps)
    first, last = (read_snapshot(prefix) for _, prefix in chosen)
    gamma, cell = local_shear(first[0], last[0], (first[1], last[1]), first[2], last[2], reach)
    row = {"steps": [s for s, _ in chosen], "grains": len(gamma), "cell_shear": cell,
           "mean_shear": float(gamma.mean()), "half_share_fraction": float(half_share(gamma)),
           "top_10_percent_share": top_share(gamma)}
    return row, (first[0], first[2], gamma)


def draw(ax, centres, sides, gamma, title):
    top = np.percentile(gamma, 95)
    for i, j in itertools.product((-1, 0, 1), repeat=2):
        shifted = centres + i * sides[:, 0] + j * sides[:, 1]
        ax.scatter(shifted[:, 0], shifted[:, 1], c=gamma, s=5, vmin=0, vmax=top, cmap="viridis")
    corners = np.array([[0, 0], sides[:, 0], sides[:, 0] + sides[:, 1], sides[:, 1], [0, 0]])
    ax.plot(corners[:, 0], corners[:, 1], "r-", lw=0.8)
    ax.set_aspect("equal")
    ax.set_title(title, fontsize=8)
    ax.axis("off")


def main():
    p = cli.parser(__doc__.split("\n")[0], "rve_localisation.png")
    p.add_argument("more", nargs="*", metavar="OUTPUT_DIR", help="further runs")
    p.add_argument("--steps", nargs=2, type=cli.non_negative_int, metavar=("A", "B"),
                   help="increments of the two snapshots (default: first and last)")
    p.add_argument("--rve", help="snapshot folder, relative to OUTPUT_DIR, when there are several")
    p.add_argument("--reach", type=cli.positive, default=2.5,
                   help="neighbours within this many mean diameters (default 2.5)")
    p.add_argument("--json", type=cli.writable_file, help="write the rows as JSON")
    args = p.parse_args()
    runs = [cli.output_dir(args)] + [d.rstrip("/") for d in args.more]
    for d in runs[1:]:
        if not os.path.isdir(d):
            raise InputError(f"{d}: not a folder")
    rows, fields = {}, {}
    for d in runs:  # every run measured before anything is printed or written
        rows[d], fields[d] = measure(d, args.rve, args.steps, args.reach)
    print("| run | increments | cell gamma | mean grain gamma | half-share fraction | "
          "share of the top 10 % |")
    print("|---|---|---|---|---|---|")
    for d in runs:
        r = rows[d]
        print(f"| {d} | {r['steps'][0]}-{r['steps'][1]} | {r['cell_shear']:.3f} | "
              f"{r['mean_shear']:.3f} | {r['half_share_fraction']:.3f} | "
              f"{r['top_10_percent_share']:.3f} |")
    if args.json:
        with open(args.json, "w") as f:
            json.dump(rows, f, indent=1)
    fig, axes = figures.subplots(1, len(runs), figsize=(3.2 * len(runs), 3.4))
    for ax, d in zip(np.atleast_1d(axes), runs):
        centres, sides, gamma = fields[d]
        draw(ax, centres, sides, gamma,
             f"{os.path.basename(d)}: half share {rows[d]['half_share_fraction']:.2f}")
    figures.save(fig, cli.picture_path(args), args.dpi)


def entry():
    """The command: tools/rve_localisation.py in a checkout, mpm-lig-rve-localisation installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
