"""How fast a footing run's material points move against the footing, and how many packings carry nothing.

usage: footing_noise.py OUTPUT_DIR [OUTPUT_DIR ...] --case CASE.json [--from S] [--free-below P]

For each run, over the field outputs of results.h5 from s/B = S on (default 0.2, past the
first loading): the lowest and highest 95th percentile of the points' speeds, the fastest point
and its speed over the footing's, and the largest share of points whose mean stress is below P
(default 1 kPa: a packing that has lost its contacts; the in-plane mean -(sxx + syy)/2 in 2D,
where a DEM point's szz is 0, and -tr(sigma)/3 in 3D). Then the
load q/q_s: the highest value to s/B = 0.4 and the means over s/B 0.1-0.4, 0.4-1.0 and 1.0-1.5
(over the part of a window the run reached; nan for a window it has not reached). B and q_s come from the case (rigid_bodies[0].width[0],
the surface traction); the footing's speed is the settlement's mean rate in history.csv.

Pure FLIP (analysis.flip 1) keeps velocity patterns the grid cannot see; their speeds far above
the footing's are what this table shows (docs/footing_dem_e0187.md).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py")

import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, footing  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402


def footing_scales(case_path):
    """(B, q_s, dimension) of the case's first footing and vertical surface traction."""
    case = read_json(case_path)
    width = footing.width(case, case_path)
    try:
        dimension = int(case.get("dimension", 2))
    except (TypeError, ValueError):
        raise InputError(f"{case_path}: dimension is not an integer") from None
    surcharge = footing.surcharge(case, case_path)
    if surcharge is not None:
        return width, surcharge, dimension
    raise InputError(f"{case_path}: no traction boundary condition with a vertical component "
                     "(the surcharge q_s)")


def window_mean(s_over_b, q, lo, hi):
    inside = (s_over_b >= lo) & (s_over_b <= hi)
    return q[inside].mean() if inside.any() else float("nan")


def mean_stress(stress, dimension):
    """In 2D the in-plane mean (a 2D packing's szz is 0), in 3D -tr(sigma)/3; compression > 0."""
    if dimension == 2:
        return -(stress[:, 0] + stress[:, 1]) / 2.0
    return -(stress[:, 0] + stress[:, 1] + stress[:, 2]) / 3.0


def run_row(directory, width, surcharge, dimension, start, free_below):
    history_path = os.path.join(directory, "history.csv")
    history = read_history(history_path)
    require_columns(history, ("time", "settlement", "q"), history_path)
    if history["time"][-1] <= 0.0 or history["settlement"][-1] <= 0.0:
        raise InputError(f"{history_path}: the footing has not moved")
    footing_speed = history["settlement"][-1] / history["time"][-1]
    s_over_b = history["settlement"] / width
    q = history["q"] / surcharge
    fields = FieldFile(os.path.join(directory, "results.h5"))
    p95, fastest, free = [], [], []
    for step in fields.steps:
        f = fields.step(step)
        if not np.isfinite(f.time):
            raise InputError(f"{directory}/results.h5: output step {step} has no time")
        if np.interp(f.time, history["time"], s_over_b) < start:
            continue
        speed = np.linalg.norm(f["velocity"], axis=1)
        p = mean_stress(f["stress"], dimension)
        p95.append(np.percentile(speed, 95))
        fastest.append(speed.max())
        free.append(np.mean(p < free_below))
    fields.close()
    if not p95:
        raise InputError(f"{directory}: no field output at s/B >= {start:g}")
    early = s_over_b <= 0.4
    return (f"{s_over_b[-1]:6.2f} {min(p95):6.2f} {max(p95):6.2f} {max(fastest):7.2f} "
            f"{max(fastest) / footing_speed:6.1f} {100 * max(free):6.1f} {q[early].max():7.2f} "
            f"{window_mean(s_over_b, q, 0.1, 0.4):7.2f} {window_mean(s_over_b, q, 0.4, 1.0):7.2f} "
            f"{window_mean(s_over_b, q, 1.0, 1.5):7.2f}  {directory}")


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("runs", nargs="+", help="output folders of footing runs")
    p.add_argument("--case", required=True, help="the runs' case file (B and q_s)")
    p.add_argument("--from", dest="start", type=cli.finite, default=0.2,
                   help="first s/B of the outputs looked at (default 0.2)")
    p.add_argument("--free-below", type=cli.positive, default=1e3,
                   help="mean stress [Pa] below which a point counts as carrying nothing (default 1e3)")
    args = p.parse_args()
    width, surcharge, dimension = footing_scales(args.case)
    print(f"speeds in m/s over the outputs from s/B = {args.start:g}; q in q_s = {surcharge:g} Pa")
    print(f"{'s/B':>6} {'p95 lo':>6} {'p95 hi':>6} {'fastest':>7} {'/ v_f':>6} {'free %':>6} "
          f"{'peak':>7} {'0.1-0.4':>7} {'0.4-1.0':>7} {'1.0-1.5':>7}  run")
    for run in args.runs:
        print(run_row(run, width, surcharge, dimension, args.start, args.free_below))


def entry():
    """The command: tools/footing_noise.py in a checkout, mpm-lig-footing-noise installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
