"""Material points inside a rigid footing, step by step, next to its load curve.

usage: footing_intrusion.py OUTPUT_DIR --case CASE.json [-o picture.png] [--every N]

The footing of mpm_lig acts on grid nodes, not on the points: a point can end up inside the
footing's volume (within its footprint, above its base) and is carried along there until it
leaves again. Each entry and exit is a jolt in the load. This tool counts, at every field output
step of results.h5, the points whose centre lies inside the first footing of the case
(rigid_bodies[0]: centre, width, initial base; the base at the step's time comes from the
settlement column of history.csv), prints s/B, the count and q/q_s (q_s: the case's surface
traction) at each step where the count changes (or every N-th step with --every), and draws
q/q_s and the count against s/B. Fields must be written often enough to see events
(output.every of a few tens of steps).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py", "matplotlib")

import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures, footing  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402


def footing_of(case_path):
    """(centre, half width, initial base, surcharge or None) of rigid_bodies[0]."""
    case = read_json(case_path)
    centre, width, base = footing.footing(case, case_path)
    return centre, 0.5 * width, base, footing.surcharge(case, case_path)


def points_inside(positions, centre, half_width, base):
    """How many points lie within the footprint and above the base. A point on a face (put
    there by keep_points_out, to round-off) is not inside."""
    dims = len(centre)
    tolerance = 1e-9 * half_width.max()
    horizontal = positions[:, :dims]
    under = np.all(np.abs(horizontal - centre) < half_width - tolerance, axis=1)
    return int(np.count_nonzero(under & (positions[:, dims] > base + tolerance)))


def main():
    p = cli.parser(__doc__.split("\n")[0], "intrusion.png")
    p.add_argument("--case", required=True, help="the run's case file (its first footing)")
    p.add_argument("--every", type=cli.non_negative_int, default=0,
                   help="print every N-th output step as well as every change (default: changes)")
    args = p.parse_args()
    directory = cli.output_dir(args)
    centre, half_width, base0, surcharge = footing_of(args.case)
    history_path = os.path.join(directory, "history.csv")
    history = read_history(history_path)
    require_columns(history, ("time", "settlement", "q"), history_path)
    width = 2 * half_width[0]
    scale = surcharge or 1e3
    fields = FieldFile(os.path.join(directory, "results.h5"))
    s_over_b, counts, loads = [], [], []
    for step in fields.steps:
        f = fields.step(step)
        settlement = float(np.interp(f.time, history["time"], history["settlement"]))
        counts.append(points_inside(f["positions"], centre, half_width, base0 - settlement))
        s_over_b.append(settlement / width)
        loads.append(float(np.interp(f.time, history["time"], history["q"])) / scale)
    label = "q/q_s" if surcharge else "q [kPa]"
    print(f"{'s/B':>7} {'points inside':>13} {label:>8}")
    for k, n in enumerate(counts):
        if k == 0 or n != counts[k - 1] or (args.every and k % args.every == 0):
            print(f"{s_over_b[k]:7.3f} {n:13d} {loads[k]:8.3f}")
    print(f"most points inside the footing at once: {max(counts)}; "
          f"first at s/B = {next((s for s, n in zip(s_over_b, counts) if n), float('nan')):.3g}")

    fig, (top, bottom) = figures.subplots(2, 1, figsize=(6.4, 5.6), sharex=True)
    top.plot(history["settlement"] / width, history["q"] / scale, color="k", lw=0.8)
    top.set_ylabel(rf"${label.replace('q_s', '{q_s}')}$" if surcharge else label)
    top.set_ylim(bottom=0)
    bottom.step(s_over_b, counts, where="post", color="C3")
    bottom.set_ylabel("points inside\nthe footing")
    bottom.set_xlabel(r"normalised settlement $s/B$ [–]")
    bottom.set_xlim(left=0)
    top.set_title(f"footing load and points inside it: {figures.run_name(directory)}")
    figures.finish(fig, cli.picture_path(args), args.dpi)


def entry():
    """The command: tools/footing_intrusion.py in a checkout, mpm-lig-footing-intrusion installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
