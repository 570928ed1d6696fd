"""Normalised load-settlement curve of a strip footing (seed Fig. 6) with bearing-capacity lines.

usage: plot_footing.py OUTPUT_DIR [-o picture.png] [--case CASE.json] [--width B]
                       [--surcharge q_s | --cu c_u] [--phi DEG] [--prandtl]
                       [--label TEXT] [--compare DIR LABEL ...] [--window A B]

Reads OUTPUT_DIR/history.csv (settlement [m], load, q [Pa] of the first footing) and
summary.json when present (its peak_q is cross-checked). The footing width B comes from
--width or from --case (rigid_bodies[0].width[0], the full width also for a half model). q is
divided by the surcharge q_s (--surcharge, or the case's first traction with a vertical
component) or by the undrained strength c_u (--cu, or the case's tresca material; with
--prandtl or without a surcharge); the horizontal lines are Vesic's
N_q = tan^2(pi/4 + phi/2) exp(pi tan phi) for --phi DEG (over q_s) and Prandtl's 2 + pi
(--prandtl, over c_u). Without a normaliser q is plotted in kPa.
--compare draws other runs of the same footing (same B and normaliser) as dashed lines, e.g. a
continuum run on the same mesh; --window A B prints each curve's mean over s/B in [A, B] too.
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import math  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures, footing  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402


def vesic_nq(phi_deg):
    """N_q = tan^2(pi/4 + phi/2) e^{pi tan phi} (Prandtl-Reissner, as in Vesic 1973)."""
    phi = math.radians(phi_deg)
    return math.tan(math.pi / 4 + phi / 2) ** 2 * math.exp(math.pi * math.tan(phi))


def case_values(path):
    """(B, q_s, c_u) read from a case file; None where it does not say."""
    case = read_json(path)
    try:
        width = footing.width(case, path)
    except InputError:
        width = None
    cu = None
    for m in case.get("materials", []):
        if m.get("type") == "tresca" and "undrained_strength" in m:
            cu = float(m["undrained_strength"])
    return width, footing.surcharge(case, path), cu


def report_window(label, settlement, y, window):
    inside = (settlement >= window[0]) & (settlement <= window[1])
    if not inside.any():
        raise InputError(f"{label}: no sample with s/B in [{window[0]}, {window[1]}]")
    print(f"{label}: mean over s/B in [{window[0]:g}, {window[1]:g}] = {y[inside].mean():.4g} "
          f"(min {y[inside].min():.4g}, max {y[inside].max():.4g})")


def main():
    p = cli.parser(__doc__.split("\n")[0], "footing.png")
    p.add_argument("--case", help="the run's case file (footing width, surcharge, c_u)")
    p.add_argument("--width", type=cli.positive, help="footing width B [m]")
    norm = p.add_mutually_exclusive_group()
    norm.add_argument("--surcharge", type=cli.positive, help="surcharge q_s [Pa]: plot q/q_s")
    norm.add_argument("--cu", type=cli.positive, help="undrained strength c_u [Pa]: plot q/c_u")
    p.add_argument("--phi", type=cli.positive, help="friction angle phi' [deg]: draw Vesic's N_q")
    p.add_argument("--prandtl", action="store_true", help="draw Prandtl's 2 + pi")
    p.add_argument("--label", default="MPM", help="legend text of OUTPUT_DIR's curve")
    p.add_argument("--compare", nargs=2, action="append", default=[], metavar=("DIR", "LABEL"),
                   help="another run's output directory and its legend text (repeatable)")
    p.add_argument("--window", nargs=2, type=cli.non_negative, metavar=("A", "B"),
                   help="print each curve's mean over s/B in [A, B]")
    args = p.parse_args()
    if args.phi is not None and args.phi >= 90:
        raise InputError(f"--phi {args.phi:g}: a friction angle below 90 deg is needed")
    if args.window and not args.window[0] < args.window[1]:
        raise InputError(f"--window {args.window[0]:g} {args.window[1]:g}: expected A < B")
    directory = cli.output_dir(args)
    path = os.path.join(directory, "history.csv")
    table = read_history(path)
    require_columns(table, ("settlement", "q"), path)
    width, surcharge, cu = case_values(args.case) if args.case else (None, None, None)
    width = args.width or width
    if width is None:
        raise InputError("footing width unknown: give --width B or --case CASE.json "
                         "(with rigid_bodies[0].width)")
    if width <= 0:
        raise InputError(f"footing width must be > 0, got {width}")
    if args.surcharge is not None or args.cu is not None:
        surcharge, cu = args.surcharge, args.cu
    elif args.prandtl or surcharge is None:
        surcharge = None  # from the case: normalise by c_u when asked for 2 + pi or no q_s
    else:
        cu = None
    if args.phi is not None and surcharge is None:
        raise InputError("--phi needs the surcharge: give --surcharge q_s or a --case "
                         "with a traction boundary condition")
    if args.prandtl and cu is None:
        raise InputError("--prandtl needs c_u: give --cu or a --case with a tresca material")
    for name, value in (("surcharge", surcharge), ("cu", cu)):
        if value is not None and value <= 0:
            raise InputError(f"--{name} must be > 0, got {value}")

    settlement, q = table["settlement"] / width, table["q"]
    others = []
    for other_dir, label in args.compare:
        other_path = os.path.join(other_dir, "history.csv")
        other = read_history(other_path)
        require_columns(other, ("settlement", "q"), other_path)
        others.append((label, other["settlement"] / width, other["q"]))
    if surcharge is not None:
        ylabel, scale = r"normalised load $q/q_s$", surcharge
    elif cu is not None:
        ylabel, scale = r"normalised load $q/c_u$", cu
    else:
        ylabel, scale = r"footing pressure $q$ [kPa]", 1e3
    normalised = surcharge is not None or cu is not None
    y = q / scale
    peak = int(np.argmax(y))
    print(f"B = {width:g} m, peak q = {q[peak]:.6g} Pa at s/B = {settlement[peak]:.4g}, "
          f"peak {ylabel.split('$')[1] if normalised else 'q [kPa]'} = {y[peak]:.4g}")
    summary = read_json(os.path.join(directory, "summary.json"), required=False)
    if summary and "peak_q" in summary and not np.isclose(summary["peak_q"], q.max(), rtol=1e-3):
        print(f"note: summary.json peak_q = {summary['peak_q']:.6g} Pa differs from the "
              f"history's {q.max():.6g} Pa (history_every > 1 misses the exact peak)")

    if args.window:
        report_window(args.label, settlement, y, args.window)
    fig, ax = figures.subplots(figsize=(6.4, 4.6))
    ax.plot(settlement, y, color="k", label=args.label)
    for k, (label, s_other, q_other) in enumerate(others):
        y_other = q_other / scale
        k_peak = int(np.argmax(y_other))
        print(f"{label}: peak {y_other[k_peak]:.4g} at s/B = {s_other[k_peak]:.4g}")
        if args.window:
            report_window(label, s_other, y_other, args.window)
        ax.plot(s_other, y_other, color=f"C{k + 1}", ls=(0, (4, 2)), lw=1.2, label=label)
    ax.plot(settlement[peak], y[peak], "o", color="k", ms=5, mfc="w",
            label=f"peak {y[peak]:.3g}")
    if args.phi is not None:
        nq = vesic_nq(args.phi)
        print(f"Vesic N_q({args.phi:g} deg) = {nq:.4g}; peak / N_q = {y[peak] / nq:.3f}")
        ax.axhline(nq, color="C0", ls="--",
                   label=rf"Vesić $N_q$ = {nq:.3g} ($\varphi'$ = {args.phi:g}°)")
    if args.prandtl:
        nc = 2 + math.pi
        print(f"Prandtl 2 + pi = {nc:.4g}; peak / (2 + pi) = {y[peak] / nc:.3f}")
        ax.axhline(nc, color="C3", ls="-.", label=r"Prandtl $2+\pi$ = 5.14")
    ax.set_xlabel(r"normalised settlement $s/B$ [–]")
    ax.set_ylabel(ylabel)
    ax.set_xlim(left=0)
    ax.set_ylim(bottom=0)
    if len(others) >= 2:
        # Several curves fill the axes: the legend goes below them, not over the data.
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=2, frameon=False)
    else:
        ax.legend(loc="lower right" if not others else "best", frameon=False)
    ax.set_title(f"strip footing, B = {width:g} m: {figures.run_name(directory)}")
    figures.finish(fig, cli.picture_path(args), args.dpi)


def entry():
    """The command: tools/plot_footing.py in a checkout, mpm-lig-plot-footing installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
