"""The shear band of a direct-DEM footing (tools/direct_dem.py) and its width in grain diameters,
from the grains' own motion between two states: the start of loading (reference.npz) or a grain
snapshot, and a later snapshot.

usage: shear_band.py RUN_DIR --to S [--from S0] [--widths 1 2 3] [--level 0.5] [-o PNG]
                     [--json FILE] [--dpi N]

The grains' displacement from the state at s/B = S0 (default: the start of loading) to the
snapshot nearest s/B = S is coarse-grained on a grid of spacing w/2 with a Gaussian of width
w = each --widths value times d (d = r_min + r_max; mpm_lig_post.coarse_grain: a weighted
least-squares affine fit per grid point), giving the increment of eps_q. The band is the
region where that increment exceeds --level times its 99th percentile, restricted to the
connected part that touches the footing's edge (x = B/2 at the surface); its width is
2 A / P (A its area, P its perimeter: a strip of length L and width W has A = L W, P ~ 2 L),
in grain diameters (a band of length L reads W L / (L + W): 5-15 % low for the bands here,
tests/tools/check_shear_band.py). A Gaussian of width w widens a band of width W to about
sqrt(W^2 + (2.355 w)^2) at the half level: the width without the smearing, sqrt(max(0,
W_meas^2 - (2.355 w)^2)), is given beside it, and the measured widths at several w show
whether it converged. Prints one row per width; writes a picture of the increment field with
the band's outline (default RUN_DIR/shear_band_S.png) and --json.
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import json  # noqa: E402
import math  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.coarse_grain import affine_fit, deviatoric_strain, hencky  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.tables import read_json  # noqa: E402
from mpm_lig_post.vtk_legacy import read_polydata  # noqa: E402

SMEAR = 2.0 * math.sqrt(2.0 * math.log(2.0))  # full width at half maximum of a unit Gaussian


def snapshots(run):
    """{s/B: grains.vtk path} of the run's snapshots (their loading step over the run's)."""
    summary = read_json(os.path.join(run, "summary.json"))
    ds_over_B = summary["footing_speed"] * summary["time_step"] / summary["B"]
    found = {}
    folder = os.path.join(run, "snapshots")
    for name in sorted(os.listdir(folder)) if os.path.isdir(folder) else []:
        if name.endswith("_grains.vtk"):
            step = int(name.split("_")[1])
            found[round(step * ds_over_B, 6)] = os.path.join(folder, name)
    return summary, found


def nearest_snapshot(run, found, s):
    """(grains.vtk path, its s/B) of the snapshot within 0.02 of s/B = s."""
    if not found:
        raise InputError(f"{run}/snapshots: no grain snapshot")
    nearest = min(found, key=lambda k: abs(k - s))
    if abs(nearest - s) > 0.02:
        raise InputError(f"{run}: no snapshot near s/B = {s:g} (has "
                         f"{', '.join(f'{k:.3f}' for k in sorted(found))})")
    return found[nearest], nearest


def positions_at(run, found, s):
    """Grain centres (id order) at the snapshot nearest s/B = s, or at the start (s = 0)."""
    if s == 0:
        return np.load(os.path.join(run, "reference.npz"))["xy"], 0.0
    path, nearest = nearest_snapshot(run, found, s)
    return read_polydata(path).points[:, :2], nearest


def band(run, s_from, s_to, widths, level):
    summary, found = snapshots(run)
    d = summary["B"] / summary["B_over_d"]
    start, at_from = positions_at(run, found, s_from)
    end, at_to = positions_at(run, found, s_to)
    if summary.get("footing_column"):
        # A column added to a settled block (--start-from --footing-column) is not in
        # reference.npz; its discs, created last, close the snapshots' id order: left out.
        known = len(np.load(os.path.join(run, "reference.npz"))["ids"])
        start, end = start[:known], end[:known]
    if len(start) != len(end):
        raise InputError(f"{run}: the two states hold {len(start)} and {len(end)} grains")
    lx, ly = summary["block"]
    edge = np.array([0.5 * summary["B"], ly - s_to * summary["B"]])
    rows, fields = [], []
    for factor in widths:
        w = factor * d
        xs = np.arange(0.5 * w, lx, 0.5 * w)
        ys = np.arange(0.5 * w, ly, 0.5 * w)
        X, Y = np.meshgrid(xs, ys, indexing="xy")
        points = np.column_stack([X.ravel(), Y.ravel()])
        F, _, used = affine_fit(start, end, points, w)
        eq = deviatoric_strain(hencky(F)).reshape(X.shape)
        eq[(used < 3).reshape(X.shape)] = 0.0
        threshold = level * np.percentile(eq, 99)
        region = connected_to(eq > threshold, xs, ys, edge)
        area = region.sum() * (0.5 * w) ** 2
        perimeter = outline_length(region, xs, ys)
        measured = 2.0 * area / perimeter if perimeter > 0 else float("nan")
        unsmeared = math.sqrt(max(0.0, measured ** 2 - (SMEAR * w) ** 2))
        rows.append({"width_over_d": factor, "threshold": threshold, "area": area,
                     "perimeter": perimeter, "band_width_over_d": measured / d,
                     "unsmeared_over_d": unsmeared / d, "peak_increment": float(eq.max())})
        fields.append((xs, ys, eq, region))
    return summary, d, (at_from, at_to), rows, fields


def connected_to(mask, xs, ys, point):
    """The part of `mask` (ny x nx) 4-connected to the cell nearest `point` (or to the masked
    cell nearest it)."""
    cells = np.argwhere(mask)
    if not len(cells):
        return mask
    gx, gy = np.searchsorted(xs, point[0]), np.searchsorted(ys, point[1])
    seed = cells[np.argmin((cells[:, 0] - gy) ** 2 + (cells[:, 1] - gx) ** 2)]
    region = np.zeros_like(mask)
    stack = [tuple(seed)]
    while stack:
        j, i = stack.pop()
        if region[j, i] or not mask[j, i]:
            continue
        region[j, i] = True
        for dj, di in ((1, 0), (-1, 0), (0, 1), (0, -1)):
            if 0 <= j + dj < mask.shape[0] and 0 <= i + di < mask.shape[1]:
                stack.append((j + dj, i + di))
    return region


def outline_length(region, xs, ys):
    """Length of the region's outline: the 0.5 contour of its indicator (marching squares)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    padded = np.pad(region.astype(float), 1)
    h = xs[1] - xs[0] if len(xs) > 1 else 1.0
    fig, ax = plt.subplots()
    contour = ax.contour(padded, levels=[0.5])
    plt.close(fig)
    length = 0.0
    for path in contour.allsegs[0]:
        length += np.sum(np.hypot(*np.diff(path, axis=0).T)) * h
    return length


def main():
    p = cli.parser(__doc__.split("\n")[1], "shear_band.png")
    p.add_argument("--to", type=cli.positive, required=True, help="s/B of the later state")
    p.add_argument("--from", dest="start", type=cli.non_negative, default=0.0,
                   help="s/B of the earlier state (default 0: the start of loading)")
    p.add_argument("--widths", type=cli.positive, nargs="+", default=[1.0, 2.0, 3.0],
                   help="Gaussian widths in grain diameters d (default 1 2 3)")
    p.add_argument("--level", type=cli.positive, default=0.5,
                   help="the band: above this fraction of the 99th percentile (default 0.5)")
    p.add_argument("--json", help="write the rows here")
    a = p.parse_args()
    if a.start >= a.to:
        raise InputError(f"--from {a.start:g}: must be below --to {a.to:g}")
    run = cli.output_dir(a)
    if a.output is None:
        a.output = os.path.join(run, f"shear_band_{a.to:g}.png")
    cli.picture_file(a.output)
    cli.writable_file(a.json, "--json file")
    summary, d, (s0, s1), rows, fields = band(run, a.start, a.to, a.widths, a.level)
    print(f"{run}: B/d = {summary['B_over_d']:.0f}, eps_q increment from s/B {s0:.3f} to {s1:.3f}")
    print("| w/d | band width / d | without the smearing / d | threshold | peak |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['width_over_d']:g} | {r['band_width_over_d']:.2f} | "
              f"{r['unsmeared_over_d']:.2f} | {r['threshold']:.3g} | {r['peak_increment']:.3g} |")
    if a.json:
        with open(a.json, "w") as f:
            json.dump({"run": run, "B_over_d": summary["B_over_d"], "from": s0, "to": s1,
                       "rows": rows}, f, indent=1)
    fig, axes = figures.subplots(1, len(fields), figsize=(5 * len(fields), 4.5), squeeze=False)
    for ax, (xs, ys, eq, region), r in zip(axes[0], fields, rows):
        ax.pcolormesh(xs / summary["B"], ys / summary["B"], eq, shading="auto", cmap="viridis")
        if region.any() and not region.all():
            ax.contour(xs / summary["B"], ys / summary["B"], region.astype(float), levels=[0.5],
                       colors="w", linewidths=0.8)
        ax.set_aspect("equal")
        ax.set_title(f"w = {r['width_over_d']:g} d: band {r['band_width_over_d']:.1f} d",
                     fontsize=9)
        ax.set_xlabel("x / B")
    axes[0][0].set_ylabel("y / B")
    figures.save(fig, a.output, a.dpi)


def entry():
    """The command: tools/shear_band.py in a checkout, mpm-lig-shear-band installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
