"""Where the DEM time went: each material point's cumulative DEM particle-steps drawn over the
points (the cost map), with the breakdown of summary.json.

usage: plot_dem_work.py OUTPUT_DIR [-o picture.png] [--step N] [--initial]
                        [--below-strain E [E ...]] [--stages S [S ...] --case CASE.json]
                        [--by-net-strain FROM_STEP]

Reads the dem_particle_steps_m<ID> fields of OUTPUT_DIR/results.h5 at the last output step (or
--step N) and the points' positions there (--initial: at the first output step, the undeformed
layout). Prints the share of the work taken by the most expensive 1, 5, 10 and 25 % of the
points and summary.json's dem_work_shares (work at substeps.max, in packings below 10 % of the
preparation pressure, in updates with strain per step below 1e-5). --below-strain E...: for
each E, the share of the work the points did while their logarithmic strain |ε| was still
below E (at the output steps' resolution: up to the last output step before they passed it) —
an upper bound of what a continuum start (materials[].start_as_continuum) with strain
threshold E could have saved on this run (a point that switches later redoes that strain in
its catch-up: only points that never pass E save their work).
--stages S...: a footing run's work between the settlements s/B = S (CASE.json gives the
footing's width; each output step's work interpolated to s/B by history.csv's settlement).
--by-net-strain FROM_STEP: the work from output step FROM_STEP to the last (or --step), the
points grouped by their net strain change |Δε| over it (below 0.01, 0.01-0.05, 0.05-0.2, above):
per group the points, their share of the work, the median ratio of the strain path seen at the
output steps (Σ |Δε| between them) to the net change, and the median particle-steps per unit of
that path. The sub-step rule charges work per unit of strain the RVE runs, so a group that
takes many times more work per unit of the seen path than the sheared points follows strain
that reverses between output steps (noise).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py", "matplotlib")

import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures, footing  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import read_history, read_json  # noqa: E402

PREFIX = "dem_particle_steps_m"


def point_work(fields, step):
    """Per point: cumulative particle-steps (summed over DEM materials; 0 elsewhere)."""
    s = fields.step(step)
    names = [n for n in s.names() if n.startswith(PREFIX)]
    if not names:
        raise InputError(f"{fields.path}: step {s.step}: no {PREFIX}<ID> field (no DEM material, "
                         "or written by an mpm_lig without per-point DEM work)")
    return sum(s[n] for n in names), s.time


def strain_norm(voigt):
    """|ε| of tensors given as Voigt rows (xx yy zz xy xz yz, tensor shear components)."""
    v = np.asarray(voigt, dtype=float)
    return np.sqrt((v[:, :3] ** 2).sum(axis=1) + 2.0 * (v[:, 3:] ** 2).sum(axis=1))


def work_below_strain(fields, thresholds, last_step):
    """[(E, share of the work done by the points while |ε| < E)] over the output steps up to
    last_step; a point's work counts up to the last output step at which it was below E."""
    steps = [s for s in fields.steps if s <= last_step]
    total, _ = point_work(fields, steps[-1])
    out = []
    for threshold in thresholds:
        saved = np.zeros_like(total)
        below = np.ones(len(total), dtype=bool)
        for step in steps:
            work, _ = point_work(fields, step)
            below &= strain_norm(fields.step(step)["strain"]) < threshold
            saved[below] = work[below]
        out.append((threshold, saved.sum() / total.sum() if total.sum() > 0 else 0.0))
    return out


def work_by_stage(fields, directory, case_file, edges):
    """[(s/B from, s/B to, particle-steps)] of a footing run between the settlements `edges`."""
    case = read_json(case_file)
    width = footing.width(case, case_file)
    path = os.path.join(directory, "history.csv")
    history = read_history(path)
    steps = np.asarray(history["step"], float)
    s_over_b = np.asarray(history["settlement"], float) / width
    out_steps = np.asarray(fields.steps, float)
    totals = np.array([point_work(fields, s)[0].sum() for s in fields.steps])
    at = np.interp(out_steps, steps, s_over_b)
    if edges[-1] > at[-1] + 1e-9:
        raise InputError(f"{directory}: the run ends at s/B = {at[-1]:.3g}, before {edges[-1]:g}")
    work = np.interp(edges, at, totals)
    return [(edges[i], edges[i + 1], work[i + 1] - work[i]) for i in range(len(edges) - 1)]


NET_STRAIN_GROUPS = (0.0, 0.01, 0.05, 0.2, np.inf)


def work_by_net_strain(fields, first, last):
    """[(|Δε| from, to, points, work share, median path / net, median work per unit path)]
    between output steps `first` and `last`, the points grouped by their net |Δε|."""
    steps = [s for s in fields.steps if first <= s <= last]
    if len(steps) < 2:
        raise InputError(f"--by-net-strain {first}: fewer than two output steps from it to {last}")
    strains = [np.asarray(fields.step(s)["strain"], dtype=float) for s in steps]
    net = strain_norm(strains[-1] - strains[0])
    path = sum(strain_norm(b - a) for a, b in zip(strains, strains[1:]))
    work = point_work(fields, steps[-1])[0] - point_work(fields, steps[0])[0]
    total = work.sum()
    out = []
    for lo, hi in zip(NET_STRAIN_GROUPS, NET_STRAIN_GROUPS[1:]):
        group = (net >= lo) & (net < hi)
        if not group.any():
            out.append((lo, hi, 0, 0.0, float("nan"), float("nan")))
            continue
        seen = path[group] > 0
        ratio = np.median(path[group][seen] / np.maximum(net[group][seen], 1e-300)) \
            if seen.any() else float("nan")
        per_path = np.median(work[group][seen] / path[group][seen]) if seen.any() else float("nan")
        out.append((lo, hi, int(group.sum()), work[group].sum() / total if total > 0 else 0.0,
                    ratio, per_path))
    return out


def top_shares(work, fractions=(0.01, 0.05, 0.10, 0.25)):
    """[(fraction of points, share of the work they took)] for the most expensive points."""
    order = np.sort(work)[::-1]
    total = order.sum()
    out = []
    for f in fractions:
        k = max(1, int(round(f * len(order))))
        out.append((f, order[:k].sum() / total if total > 0 else 0.0))
    return out


def main():
    p = cli.parser(__doc__.split("\n")[0], "dem_work.png")
    p.add_argument("--step", type=cli.non_negative_int, help="output step (default: the last)")
    p.add_argument("--initial", action="store_true",
                   help="draw the points where they started (first output step)")
    p.add_argument("--below-strain", type=cli.positive, nargs="+", default=[], metavar="E",
                   help="print the work done while each point's |strain| was below E")
    p.add_argument("--stages", type=cli.non_negative, nargs="+", default=[], metavar="S",
                   help="a footing's work between these settlements s/B (needs --case)")
    p.add_argument("--case", help="the run's case file (the footing's width, for --stages)")
    p.add_argument("--by-net-strain", type=cli.non_negative_int, metavar="FROM_STEP",
                   help="the work from this output step on, by the points' net strain change")
    args = p.parse_args()
    directory = cli.output_dir(args)
    if args.stages and (not args.case or len(args.stages) < 2 or
                        any(b <= a for a, b in zip(args.stages, args.stages[1:]))):
        raise InputError("--stages: give two or more increasing settlements and --case")
    fields = FieldFile(os.path.join(directory, "results.h5"))
    try:
        step = args.step if args.step is not None else fields.steps[-1]
        work, time = point_work(fields, step)
        where = fields.step(fields.steps[0] if args.initial else step)["positions"]
        below = work_below_strain(fields, args.below_strain, step) if args.below_strain else []
        stages = work_by_stage(fields, directory, args.case, args.stages) if args.stages else []
        by_net = (work_by_net_strain(fields, args.by_net_strain, step)
                  if args.by_net_strain is not None else [])
    finally:
        fields.close()
    total = work.sum()
    print(f"{len(work)} points, {total:.4g} DEM particle-steps up to step {step} "
          f"(t = {time:.4g} s)")
    for f, share in top_shares(work):
        print(f"  the {100 * f:g} % most expensive points: {100 * share:.1f} % of the work")
    summary = read_json(os.path.join(directory, "summary.json"), required=False)
    shares = (summary or {}).get("dem_work_shares")
    if shares:
        for key, value in shares.items():
            print(f"  {key.replace('_', ' ')}: {100 * value:.1f} % of the work")
    for lo, hi, steps_done in stages:
        print(f"  s/B {lo:g} to {hi:g}: {steps_done:.3g} particle-steps "
              f"({100 * steps_done / total:.1f} % of the work)")
    for threshold, share in below:
        print(f"  done while the point's |strain| < {threshold:g}: {100 * share:.1f} % of the work "
              "(bounds what a continuum start with that threshold saves)")
    if by_net:
        print(f"  from output step {args.by_net_strain} to {step}, by net |strain change|:")
    for lo, hi, count, share, ratio, per_path in by_net:
        print(f"    {lo:g} to {hi:g}: {count} points, {100 * share:.1f} % of the work, "
              f"path / net {ratio:.3g}, {per_path:.3g} particle-steps per unit path")
    fig, ax = figures.subplots(figsize=(6.4, 5.2))  # imports matplotlib
    positive = work > 0
    vmin = work[positive].min() if positive.any() else 1.0
    from matplotlib.colors import LogNorm
    norm = LogNorm(vmin=vmin, vmax=max(work.max(), vmin * 10))
    art = ax.scatter(where[:, 0], where[:, 1], c=np.maximum(work, vmin), cmap="magma_r", norm=norm,
                     s=max(4.0, 2.4e4 / max(len(work), 1)), marker="s", edgecolors="none")
    fig.colorbar(art, ax=ax, label="DEM particle-steps of the point")
    ax.set_aspect("equal")
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")
    ax.set_title(f"where the DEM work went: {figures.run_name(directory)}, "
                 f"t = {time:.3g} s")
    figures.finish(fig, cli.picture_path(args), args.dpi)


def entry():
    """The command: tools/plot_dem_work.py in a checkout, mpm-lig-plot-dem-work installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
