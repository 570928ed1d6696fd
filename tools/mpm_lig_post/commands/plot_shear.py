"""Cyclic simple shear: shear stress-strain loops and stress path (seed Fig. 3).

usage: plot_shear.py OUTPUT_DIR [-o picture.png] [--points]

Reads OUTPUT_DIR/history.csv, either of an MPM cyclic simple shear run (columns
shear_strain, shear_stress, mean_stress, optional cycle) or of an element test (gamma_xy or
e_xy, s_xy, p). Stresses in Pa, mean stress compression positive (an MPM mean_stress that is
negative throughout is read as tension positive and flipped); shear strain is the engineering
strain gamma (element test: gamma_xy, else 2 e_xy). Without a cycle column the cycles are
counted along the strain path 0 -> +gamma_a -> -gamma_a -> 0. Prints per cycle the secant
shear modulus G_sec = (tau(gamma_max) - tau(gamma_min)) / (gamma_max - gamma_min) and the
mean-stress ratio p_end/p0 (p0: first row; 1 - p/p0 is the pore-pressure ratio of the
equivalent undrained test).

--points (MPM runs) adds panel (c) from OUTPUT_DIR/results.h5: every material point's mean
effective stress p' = -(s_xx + s_yy)/2 over time, coloured by its initial height, and prints
each point's height, final p'/p0 and largest |gamma| = 2 |e_xy| (log strain) in the run: in a
boundary-value problem the points need not follow the same path (localisation).
"""
from mpm_lig_post.requirements import require

require("numpy", "h5py", "matplotlib")

import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.shear import (count_cycles, cycle_table, cycles_to_liquefaction,  # noqa: E402
                                 shear_series)
from mpm_lig_post.tables import read_history  # noqa: E402

def print_table(rows):
    print(f"{'cycle':>5} {'gamma_a [%]':>11} {'|tau|max [kPa]':>14} {'G_sec [MPa]':>11} "
          f"{'G/G_1':>6} {'p_end [kPa]':>11} {'p_end/p0':>8}")
    g1 = rows[0][3]
    for c, amp, tmax, g, pe, ratio in rows:
        print(f"{c:5d} {100 * amp:11.4g} {tmax / 1e3:14.4g} {g / 1e6:11.4g} "
              f"{g / g1:6.3f} {pe / 1e3:11.4g} {ratio:8.3f}")


def point_series(directory):
    """(times, initial heights, p' per step and point, largest |gamma| per point) from results.h5."""
    fields = FieldFile(os.path.join(directory, "results.h5"))
    try:
        first = fields.step(fields.steps[0])
        height = first["positions"][:, 1]
        times, pressure, gamma = [], [], np.zeros(len(height))
        for step in fields.steps:
            s = fields.step(step)
            stress, strain = s["stress"], s["strain"]
            times.append(s.time)
            pressure.append(-(stress[:, 0] + stress[:, 1]) / 2)
            gamma = np.maximum(gamma, 2 * np.abs(strain[:, 3]))
    finally:
        fields.close()
    if len(times) < 2:
        raise InputError(f"{directory}/results.h5: --points needs at least two output steps")
    return np.array(times), height, np.array(pressure), gamma


def print_points(height, pressure, gamma):
    print("point  y0 [m]  p_end/p0  max|gamma| [%]")
    for k in np.argsort(height):
        p0 = pressure[0, k]
        ratio = pressure[-1, k] / p0 if p0 != 0 else float("nan")
        print(f"{k:5d} {height[k]:7.4g} {ratio:9.3f} {100 * gamma[k]:15.3g}")


def draw_points(ax, times, height, pressure):
    span = max(np.ptp(height), 1e-12)
    colours = figures.pyplot().cm.plasma((height - height.min()) / span * 0.9)
    for k in np.argsort(height):
        ax.plot(times, pressure[:, k] / 1e3, color=colours[k], lw=1.0)
    ax.set_xlabel("time [s]")
    ax.set_ylabel(r"$p'$ of each point [kPa]")
    ax.set_title("(c) points, coloured by height")
    ax.set_ylim(bottom=0)
    sm = figures.pyplot().cm.ScalarMappable(
        cmap="plasma", norm=figures.pyplot().Normalize(height.min(), height.min() + span / 0.9))
    ax.figure.colorbar(sm, ax=ax, label="initial height y [m]")


def draw(gamma, tau, p, cycle, title, png, dpi, points=None):
    if points is None:
        fig, (loops, path) = figures.subplots(1, 2, figsize=(10.5, 4.3))
    else:
        fig, (loops, path, per_point) = figures.subplots(1, 3, figsize=(15.5, 4.3))
        draw_points(per_point, *points)
    cycles = np.unique(cycle)
    colours = figures.pyplot().cm.viridis(np.linspace(0.0, 0.9, len(cycles)))
    for c, colour in zip(cycles, colours):
        idx = np.flatnonzero(cycle == c)
        if idx[0] > 0:
            idx = np.concatenate(([idx[0] - 1], idx))
        label = f"cycle {c}" if len(cycles) <= 12 else None
        loops.plot(100 * gamma[idx], tau[idx] / 1e3, color=colour, label=label)
        path.plot(p[idx] / 1e3, tau[idx] / 1e3, color=colour, label=label)
    path.plot(p[0] / 1e3, tau[0] / 1e3, "o", color="k", ms=5, label="start")
    path.plot(p[-1] / 1e3, tau[-1] / 1e3, "s", color="C3", ms=5, label="end")
    loops.set_xlabel(r"shear strain $\gamma$ [%]")
    loops.set_ylabel(r"shear stress $\tau$ [kPa]")
    loops.set_title("(a) stress-strain loops")
    path.set_xlabel(r"mean effective stress $p'$ [kPa]")
    path.set_ylabel(r"shear stress $\tau$ [kPa]")
    path.set_title("(b) stress path")
    path.set_xlim(0, 1.05 * max(np.max(p), 1e-12) / 1e3)
    for ax in (loops, path):
        ax.axhline(0, color="0.6", lw=0.6, zorder=0)
    loops.axvline(0, color="0.6", lw=0.6, zorder=0)
    path.legend(loc="best", frameon=False, ncol=2 if len(cycles) > 5 else 1)
    if len(cycles) > 12:
        sm = figures.pyplot().cm.ScalarMappable(cmap="viridis", norm=figures.pyplot().Normalize(
            cycles[0], cycles[-1] / 0.9))
        fig.colorbar(sm, ax=loops, label="cycle")
    fig.suptitle(title)
    fig.tight_layout()
    figures.save(fig, png, dpi)


def main():
    parser = cli.parser(__doc__.split("\n")[0], "shear.png")
    parser.add_argument("--points", action="store_true",
                        help="add each material point's p' over time from results.h5")
    args = parser.parse_args()
    directory = cli.output_dir(args)
    path = os.path.join(directory, "history.csv")
    gamma, tau, p, cycle = shear_series(read_history(path), path)
    if len(gamma) < 2:
        raise InputError(f"{path}: needs at least two rows")
    cycle = count_cycles(gamma) if cycle is None else np.rint(cycle).astype(int)
    rows = cycle_table(gamma, tau, p, cycle)
    print_table(rows)
    liquefied = cycles_to_liquefaction(gamma, p)
    print("p' < 0.1 p'0: " + ("not reached" if liquefied is None
                              else f"after {liquefied:.1f} cycles of strain path"))
    points = None
    if args.points:
        times, height, pressure, point_gamma = point_series(directory)
        print_points(height, pressure, point_gamma)
        points = (times, height, pressure)
    draw(gamma, tau, p, cycle, f"cyclic simple shear: {figures.run_name(directory)}",
         cli.picture_path(args), args.dpi, points)


def entry():
    """The command: tools/plot_shear.py in a checkout, mpm-lig-plot-shear installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
