"""Contours of deviatoric strain and displacement magnitude at one output step (seed Fig. 7).

usage: plot_fields.py OUTPUT_DIR [-o picture.png] [--step N] [--slice AXIS=VALUE]
                      [--eq-max E]

Reads OUTPUT_DIR/results.h5 (src/io/field_writer.h): the material points' `positions`,
`deviatoric_strain` (eps_q = sqrt(2/3 e:e)) and `displacement` at output step N (default: the
last), drawn as filled contours over the points (a triangulation of the deformed positions
without the triangles that span gaps larger than the points' own size). 2D: the x-y plane.
3D: the points within half a point spacing of a plane, --slice y=VALUE by default through the
middle of the body (x-z plane). The colour scale of eps_q ends at --eq-max (default: its 99th
percentile, so a few extreme points at a footing edge do not wash out the rest).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py", "matplotlib")

import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import read_json  # noqa: E402

AXES = "xyz"


def point_spacing(step, dimension, count):
    """Per-point size: volume^(1/D) (the initial spacing of a regular filling)."""
    if "volume" in step.names():
        return np.abs(step["volume"]) ** (1.0 / dimension)
    return np.full(count, np.nan)


def plane_points(positions, spacing, dimension, slice_spec):
    """(in-plane coordinates (n x 2), selected mask, axis names, description)."""
    if dimension == 2:
        if slice_spec:
            raise InputError("--slice applies to 3D results only")
        return positions[:, :2], np.ones(len(positions), bool), ("x", "y"), ""
    axis_name, value = "y", None
    if slice_spec:
        axis_name, _, text = slice_spec.partition("=")
        if axis_name not in AXES or not text:
            raise InputError(f"--slice: expected AXIS=VALUE with AXIS x, y or z, got '{slice_spec}'")
        try:
            value = float(text)
        except ValueError:
            raise InputError(f"--slice: '{text}' is not a number") from None
    axis = AXES.index(axis_name)
    coordinate = positions[:, axis]
    if value is None:
        value = 0.5 * (coordinate.min() + coordinate.max())
    h = np.nanmedian(spacing) if np.isfinite(spacing).any() else np.ptp(coordinate) / 20
    # points exactly half a spacing either side (a regular filling sliced between layers)
    # fall in by the 0.51 margin
    mask = np.abs(coordinate - value) <= 0.51 * h
    if not mask.any():
        raise InputError(f"--slice {axis_name}={value:g}: no material point within {0.5 * h:.3g} "
                         f"of it (points span {coordinate.min():.4g} ... {coordinate.max():.4g})")
    plane = [a for a in range(3) if a != axis]
    return positions[:, plane], mask, (AXES[plane[0]], AXES[plane[1]]), f", slice {axis_name} = {value:.4g} m"


def triangulation(xy, spacing):
    """Delaunay triangulation of the points without triangles bridging gaps."""
    from matplotlib.tri import Triangulation

    tri = Triangulation(xy[:, 0], xy[:, 1])
    corners = xy[tri.triangles]
    edges = np.linalg.norm(corners - np.roll(corners, 1, axis=1), axis=2).max(axis=1)
    local = spacing[tri.triangles].mean(axis=1)
    if np.isnan(local).all():
        local = np.full(len(edges), np.median(edges))
    tri.set_mask(edges > 2.5 * local)
    return tri


def contour(fig, ax, tri, values, label, cmap, vmax=None):
    from matplotlib.ticker import MaxNLocator

    vmax = vmax if vmax is not None else values.max()
    vmin = min(values.min(), 0.0)
    if vmax <= vmin:
        vmax = vmin + 1e-12
    levels = MaxNLocator(nbins=20).tick_values(vmin, vmax)
    levels = levels[levels <= vmax * (1 + 1e-9) + 1e-300]
    if levels[-1] < vmax:
        levels = np.append(levels, levels[-1] + (levels[1] - levels[0]))
    extend = "max" if values.max() > vmax * (1 + 1e-9) else "neither"
    filled = ax.tricontourf(tri, np.minimum(values, vmax), levels=levels, cmap=cmap, extend=extend)
    fig.colorbar(filled, ax=ax, label=label, shrink=0.9, extend=extend, ticks=MaxNLocator(6))
    ax.set_aspect("equal")


def main():
    p = cli.parser(__doc__.split("\n")[0], "fields.png")
    p.add_argument("--step", type=cli.non_negative_int, help="output step (default: the last)")
    p.add_argument("--slice", dest="slice_spec", metavar="AXIS=VALUE",
                   help="3D: plane of the section (default y through the middle)")
    p.add_argument("--eq-max", type=cli.positive, help="upper end of the eps_q colour scale")
    args = p.parse_args()
    directory = cli.output_dir(args)
    fields = FieldFile(os.path.join(directory, "results.h5"))
    step = fields.step(args.step)
    positions = step["positions"]
    eq = step["deviatoric_strain"]
    displacement = step["displacement"]
    summary = read_json(os.path.join(directory, "summary.json"), required=False) or {}
    dimension = int(summary.get("dimension", 2 if np.allclose(positions[:, 2], 0) else 3))
    spacing = point_spacing(step, dimension, len(positions))
    xy, mask, names, where = plane_points(positions, spacing, dimension, args.slice_spec)
    if mask.sum() < 3:
        raise InputError(f"{fields.path}: step {step.step}: fewer than 3 points to contour")
    xy, spacing = xy[mask], spacing[mask]
    eq, u = eq[mask], np.linalg.norm(displacement[mask], axis=1)
    tri = triangulation(xy, spacing)
    eq_max = args.eq_max if args.eq_max is not None else float(np.percentile(eq, 99))
    print(f"step {step.step}, t = {step.time:.6g} s, {mask.sum()} points{where}: "
          f"eps_q max {eq.max():.4g} (scale to {eq_max:.4g}), |u| max {u.max():.4g} m")

    wide = np.ptp(xy[:, 0]) >= np.ptp(xy[:, 1])
    fig, axes = figures.subplots(2 if wide else 1, 1 if wide else 2,
                                 figsize=(7.5, 7.5) if wide else (11, 5))
    contour(fig, axes[0], tri, eq, r"deviatoric strain $\varepsilon_q$ [–]", "viridis", eq_max)
    contour(fig, axes[1], tri, u, r"displacement $|u|$ [m]", "magma")
    for ax, title in zip(axes, (r"(a) $\varepsilon_q$", r"(b) $|u|$")):
        ax.set_xlabel(f"{names[0]} [m]")
        ax.set_ylabel(f"{names[1]} [m]")
        ax.set_title(f"{title}, step {step.step}, t = {step.time:.4g} s{where}")
    figures.finish(fig, cli.picture_path(args), args.dpi)
    fields.close()


def entry():
    """The command: tools/plot_fields.py in a checkout, mpm-lig-plot-fields installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
