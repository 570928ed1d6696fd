"""A softening layer in simple shear on three meshes, with and without an internal length: the
width of its shear band and its load-displacement curve (docs/methods.md §7).

usage: softening_band.py -o OUT_DIR [--mpm-lig build/mpm_lig] [--length L]
                         [--refinements 2 4 8] [--weights M ...] [--yield-strains E ...]
                         [--residual-weights B ...] [--points-per-cell 1|2]
                         [--imperfection cell|alternate] [--dpi N]

The layer: 0.5 m high, periodic along x, von Mises (E 10 MPa, nu 0.3, q_y 100 kPa) softening
linearly with the deviatoric plastic strain (H = 0.1 x 3G) to half its yield stress; its base
fixed, its top pushed sideways to 0.04 m over 1 s (a ramp of 0.05 s), damping 0.1. One cell
just above mid-height is 2 % weaker: the imperfection, one cell wide on every mesh (with
--imperfection alternate every other row of cells is, a pattern of the shortest wave). For each
mesh h = L/n (n in --refinements, L the length, default 0.1 m) the layer runs without an
internal length, with `analysis.internal_length` L by the second gradient (its softening
modulus the layer's, G/9), with --yield-strains by the bounded second gradient at each
yield strain ε_y, with --residual-weights by the second gradient with its fit's residual energy
at each weight β, and, with --weights, by the non-local average at each weight m. With
--points-per-cell 1 (default 2) a strain alternating from one point row to the next is one the
fitted gradient cannot see (docs/methods.md §7, the odd-even mode). Measured on
each run: the band's width while it forms, from the peak to half-softening, and late, from
there to the end (the extent along y where the plastic strain's increment exceeds half its
largest value, interpolated between point rows), the peak
shear stress and the mean shear stress over the last half of the displacement (the top's
reaction over the layer's width), and how much of the band's increment alternates from row to
row (the mean |second difference| over the mean |first difference| of its row profile where
it exceeds a tenth of its largest value: well below 1 for a smooth band). Prints a table;
writes OUT_DIR/softening_band.json and OUT_DIR/softening_band.png (shear stress against
displacement, plastic-strain profiles).
Exit 0 done, 1 a run failed (its log named), 2 bad input (before anything runs).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib", "h5py")

import json  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import checkout, cli, figures  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import FieldFile  # noqa: E402
from mpm_lig_post.mpm_run import run_case  # noqa: E402
from mpm_lig_post.tables import read_history, require_columns  # noqa: E402

HEIGHT = 0.5          # m
DISPLACEMENT = 0.04   # m, the top's final sideways displacement
DURATION = 1.0        # s
RAMP = 0.05           # s, the top's speed rises over this
YOUNG, POISSON, DENSITY = 1.0e7, 0.3, 2000.0
YIELD = 1.0e5
SHEAR = YOUNG / (2.0 * (1.0 + POISSON))
SOFTENING = 0.1 * 3.0 * SHEAR
RESIDUAL = 0.5 * YIELD
WEAKER = 0.98         # the imperfection's yield stress over the rest's
TOP_X = 2             # boundary_conditions index of the top's sideways velocity


SOFTENING_TANGENT = SHEAR * (SOFTENING / 3.0) / (SHEAR - SOFTENING / 3.0)
# In simple shear q = √3 τ and ε_q = γ/√3, so the yield stress falls with γᵖ at H/3 and the
# softening tangent of τ against γ is −G (H/3) / (G − H/3) = −G/9: the G_s of the second
# gradient.


def layer_case(cells_y, length, method, weight, yield_strain=None, residual_weight=None,
               points_per_cell=2, alternate=False):
    """The layer on `cells_y` cells of height (two columns, periodic along x); with an
    internal length by `method` when `length` is given (bounded at `yield_strain`, with the
    fit's residual weighed by `residual_weight`)."""
    h = HEIGHT / cells_y
    width = 2.0 * h
    weak = cells_y // 2  # the weak cell: rows [weak h, (weak + 1) h]
    material = {"type": "von_mises", "density": DENSITY, "youngs_modulus": YOUNG,
                "poisson_ratio": POISSON, "softening_modulus": SOFTENING,
                "residual_yield_stress": RESIDUAL}
    analysis = {"type": "mpm", "damping": 0.1, "time_step": {"cfl": 0.5},
                "end": {"time": DURATION}}
    if length and method == "nonlocal":
        analysis["internal_length"] = {"length": length, "method": method,
                                       "nonlocal_weight": weight}
    elif length:
        analysis["internal_length"] = {"length": length, "method": method,
                                       "softening_modulus": SOFTENING_TANGENT}
        if yield_strain:
            analysis["internal_length"]["yield_strain"] = yield_strain
        if residual_weight:
            analysis["internal_length"]["residual_weight"] = residual_weight
    return {
        "title": f"softening layer, h = {h:g} m" + (f", internal length {length:g} m, {method}"
                                                    if length else ", local"),
        "dimension": 2,
        "analysis": analysis,
        "mesh": {"origin": [0, 0], "size": [width, HEIGHT], "cells": [2, cells_y],
                 "periodic": ["x"]},
        "materials": [dict(material, id=0, yield_stress=YIELD),
                      dict(material, id=1, yield_stress=WEAKER * YIELD)],
        "bodies": [dict(body, points_per_cell=points_per_cell) for body in (
            [{"material": k % 2, "box": {"min": [0, k * h], "max": [width, (k + 1) * h]}}
             for k in range(cells_y)] if alternate else [
                {"material": 0, "box": {"min": [0, 0], "max": [width, weak * h]}},
                {"material": 1, "box": {"min": [0, weak * h], "max": [width, (weak + 1) * h]}},
                {"material": 0, "box": {"min": [0, (weak + 1) * h], "max": [width, HEIGHT]}}])],
        "boundary_conditions": [
            {"type": "fixed", "nodes": {"face": "y-"}},
            {"type": "velocity", "direction": "y", "velocity": 0.0, "nodes": {"face": "y+"}},
            {"type": "velocity", "direction": "x", "nodes": {"face": "y+"},
             "velocity": DISPLACEMENT / (DURATION - 0.5 * RAMP),
             "function": {"type": "ramp", "time": RAMP}},
        ],
        "output": {"every": 1000000, "history_every": 10},
    }


def output_every(case):
    """Steps between field outputs: about 200 over the run (the time step as mpm_lig's CFL
    rule sets it, the second gradient's stiffening included)."""
    h = min(a / n for a, n in zip(case["mesh"]["size"], case["mesh"]["cells"]))
    lame = YOUNG * POISSON / ((1.0 + POISSON) * (1.0 - 2.0 * POISSON))
    modulus = lame + 2.0 * SHEAR
    gradient = case["analysis"].get("internal_length", {})
    if "softening_modulus" in gradient:
        modulus += gradient["softening_modulus"] * (gradient["length"] / h) ** 2 * (
            1.0 + 4.0 * gradient.get("residual_weight", 0.0)
            * case["bodies"][0]["points_per_cell"] ** 2 / np.pi ** 2)
    dt = case["analysis"]["time_step"]["cfl"] * h / np.sqrt(modulus / DENSITY)
    return max(1, int(DURATION / dt / 200))


def point_strain(fields, step):
    """(y, plastic strain) of every point at an output step: each point's state field is its
    material's (plastic_strain_mK)."""
    at = fields.step(step)
    y = at["positions"][:, 1]
    material = at["material"].astype(int).ravel()
    strain = np.full(len(y), np.nan)
    for k in np.unique(material):
        strain[material == k] = at[f"plastic_strain_m{k}"].ravel()[material == k]
    return at.time, y, strain


def run_layer(mpm_lig, case, folder):
    """Run one layer: its (displacement, shear stress) curve and the plastic-strain increment
    from the peak to half-softening (and its y), with the time of each."""
    os.makedirs(folder)
    case["output"]["every"] = output_every(case)
    case_path = os.path.join(folder, "case.json")
    with open(case_path, "w") as f:
        json.dump(case, f, indent=1)
    out = os.path.join(folder, "run")
    run_case(mpm_lig, case_path, out, os.path.join(folder, "run.log"))
    history = read_history(os.path.join(out, "history.csv"))
    column = f"bc{TOP_X}_fx"
    require_columns(history, ("time", column), out)
    time = np.asarray(history["time"])
    speed = DISPLACEMENT / (DURATION - 0.5 * RAMP)
    displacement = np.where(time < RAMP, 0.5 * speed * time ** 2 / RAMP,
                            speed * (time - 0.5 * RAMP))
    stress = np.abs(np.asarray(history[column])) / case["mesh"]["size"][0]
    # The band is read while it forms: from the peak to where the stress first falls halfway
    # to the residual strength (later, with its centre at the residual, a band widens).
    peak = int(np.argmax(stress))
    halfway = 0.5 * (stress[peak] + RESIDUAL / np.sqrt(3.0))
    after = np.nonzero(stress[peak:] <= halfway)[0]
    t_half = time[peak + after[0]] if len(after) else time[-1]
    fields = FieldFile(os.path.join(out, "results.h5"))
    try:
        times = np.array([fields.step(k).time for k in fields.steps])
        at_peak = fields.steps[max(0, int(np.searchsorted(times, time[peak])) - 1)]
        at_half = fields.steps[min(len(times) - 1, int(np.searchsorted(times, t_half)))]
        t0, y, strain0 = point_strain(fields, at_peak)
        t1, y1, strain1 = point_strain(fields, at_half)
        t2, y2, strain2 = point_strain(fields, fields.steps[-1])
    finally:
        fields.close()
    # What the top's work stores in the second gradient at the end (a band that has slipped
    # keeps its gradient energy: the length's hardening).
    share = None
    if "gradient_energy" in history:
        force = stress * case["mesh"]["size"][0]
        work = float(np.sum(0.5 * (force[1:] + force[:-1]) * np.diff(displacement)))
        share = float(history["gradient_energy"][-1]) / work
    return {"displacement": displacement, "stress": stress, "y": y1,
            "increment": strain1 - strain0, "from_time": t0, "to_time": t1,
            "y_late": y2, "increment_late": strain2 - strain1, "end_time": t2,
            "gradient_energy_share": share}


def band_width(y, strain):
    """Extent along y where the row-mean plastic strain exceeds half its largest value, the
    crossings interpolated between rows."""
    rows = np.unique(np.round(y, 9))
    profile = np.array([strain[np.abs(y - r) < 1e-8].mean() for r in rows])
    half = 0.5 * profile.max()
    if not half > 0.0:
        return 0.0, rows, profile
    above = np.nonzero(profile >= half)[0]
    lo, hi = above[0], above[-1]

    def crossing(a, b):
        return rows[a] + (half - profile[a]) * (rows[b] - rows[a]) / (profile[b] - profile[a])
    bottom = crossing(lo - 1, lo) if lo > 0 else rows[lo]
    top = crossing(hi, hi + 1) if hi + 1 < len(rows) else rows[hi]
    return float(top - bottom), rows, profile


def alternation(profile):
    """Mean |second difference| over mean |first difference| of a row profile, over the rows
    where it exceeds a tenth of its largest value."""
    inside = np.nonzero(profile > 0.1 * profile.max())[0]
    inside = inside[(inside > 0) & (inside < len(profile) - 1)]
    if len(inside) == 0:
        return 0.0
    second = np.abs(profile[inside] - 0.5 * (profile[inside - 1] + profile[inside + 1]))
    first = 0.5 * np.abs(profile[inside + 1] - profile[inside - 1])
    return float(second.mean() / max(first.mean(), 1e-300))


def summarise(result):
    width, rows, profile = band_width(result["y"], result["increment"])
    late, _, _ = band_width(result["y_late"], result["increment_late"])
    u, tau = result["displacement"], result["stress"]
    peak = int(np.argmax(tau))
    window = (u >= u[peak]) & (u <= u[peak] + 0.25 * DISPLACEMENT)
    return {"band_width": width, "band_width_late": late, "band_from_time": result["from_time"],
            "band_to_time": result["to_time"], "peak_stress": float(tau[peak]),
            "peak_displacement": float(u[peak]),
            "mean_stress_post_peak": float(tau[window].mean()),
            "mean_stress_late": float(tau[u >= 0.5 * DISPLACEMENT].mean()),
            "gradient_energy_share": result["gradient_energy_share"],
            "largest_increment": float(profile.max()), "alternation": alternation(profile)}


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("-o", "--output", required=True, metavar="OUT_DIR")
    p.add_argument("--mpm-lig", help="the mpm_lig executable (default: build/mpm_lig of this "
                   "checkout, else the PATH's)")
    p.add_argument("--length", type=cli.positive, default=0.1,
                   help="the internal length [m] (default 0.1; at most 0.1 m: the layer is 0.5 m)")
    p.add_argument("--refinements", type=cli.positive_int, nargs="+", default=[2, 4, 8],
                   help="meshes h = length / n (default 2 4 8)")
    p.add_argument("--weights", type=cli.non_negative, nargs="*", default=[],
                   help="also the method nonlocal at these non-local weights m (default: "
                   "none; 1 and 0.5 show why it is not the regularisation)")
    p.add_argument("--yield-strains", type=cli.positive, nargs="*", default=[],
                   help="also the second gradient bounded at these yield strains ε_y "
                   "(analysis.internal_length.yield_strain; default: none)")
    p.add_argument("--residual-weights", type=cli.positive, nargs="*", default=[],
                   help="also the second gradient with its fit's residual energy at these "
                   "weights β (analysis.internal_length.residual_weight; default: none)")
    p.add_argument("--points-per-cell", type=int, choices=(1, 2), default=2,
                   help="the points per cell along each axis (default 2; 1: the odd-even mode)")
    p.add_argument("--imperfection", choices=("cell", "alternate"), default="cell",
                   help="the weaker cell just above mid-height (default) or every other row "
                   "of cells")
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    if a.length > 0.1:
        raise InputError(f"--length {a.length}: at most 0.1 m (the layer is {HEIGHT} m high)")
    meshes = []
    for n in a.refinements:
        cells = HEIGHT / (a.length / n)
        if abs(cells - round(cells)) > 1e-9 or round(cells) < 4 or round(cells) > 2000:
            raise InputError(f"--refinements {n}: {HEIGHT} m / (length / {n}) = {cells:g} cells "
                             "must be a whole number, 4 ... 2000")
        meshes.append(int(round(cells)))
    if any(m > 2.0 for m in a.weights):
        raise InputError("--weights: at most 2")
    mpm_lig = checkout.find_mpm_lig(a.mpm_lig)
    out = os.path.abspath(a.output)
    cli.writable_folder(out)
    if os.path.isdir(out) and os.listdir(out):
        raise InputError(f"{out}: not empty (choose a new folder)")
    os.makedirs(out, exist_ok=True)
    variants = [("local", None, None, None, None, None),
                ("second_gradient", a.length, "second_gradient", None, None, None)]
    variants += [(f"bounded_e{e:g}", a.length, "second_gradient", None, e, None)
                 for e in a.yield_strains]
    variants += [(f"residual_b{b:g}", a.length, "second_gradient", None, None, b)
                 for b in a.residual_weights]
    variants += [(f"nonlocal_m{m:g}", a.length, "nonlocal", m, None, None) for m in a.weights]
    report = {"length": a.length, "height": HEIGHT, "displacement": DISPLACEMENT,
              "yield_stress": YIELD, "softening_modulus": SOFTENING,
              "residual_yield_stress": RESIDUAL, "points_per_cell": a.points_per_cell,
              "imperfection": a.imperfection,
              "runs": {}}
    curves = {}
    for name, length, method, weight, yield_strain, residual in variants:
        for cells, n in zip(meshes, a.refinements):
            key = f"{name}_h{n}"
            print(f"running {key}: h = length / {n} ({cells} cells)", flush=True)
            case = layer_case(cells, length, method, weight, yield_strain, residual,
                              a.points_per_cell, a.imperfection == "alternate")
            result = run_layer(mpm_lig, case, os.path.join(out, key))
            curves[key] = result
            report["runs"][key] = dict(summarise(result), variant=name, refinement=n,
                                       cell=HEIGHT / cells)
    print_table(report)
    with open(os.path.join(out, "softening_band.json"), "w") as f:
        json.dump(report, f, indent=1)
    picture(os.path.join(out, "softening_band.png"), report, curves, a.dpi)


def print_table(report):
    length = report["length"]
    print("| run | h | band width / length | band width / h | late band width / length | "
          "peak tau [kPa] | mean tau over the quarter after the peak [kPa] | "
          "mean tau, last half [kPa] | gradient energy / work at the end | alternation |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for key, r in report["runs"].items():
        share = r["gradient_energy_share"]
        print(f"| {r['variant']} | length/{r['refinement']} | {r['band_width'] / length:.2f} | "
              f"{r['band_width'] / r['cell']:.2f} | {r['band_width_late'] / length:.2f} | "
              f"{r['peak_stress'] / 1e3:.2f} | "
              f"{r['mean_stress_post_peak'] / 1e3:.2f} | {r['mean_stress_late'] / 1e3:.2f} | "
              f"{'-' if share is None else f'{share:.3f}'} | {r['alternation']:.2f} |")


def picture(path, report, curves, dpi):
    fig, axes = figures.subplots(1, 2, figsize=(10.0, 4.0))
    for key, result in curves.items():
        r = report["runs"][key]
        style = "--" if r["variant"] == "local" else "-"
        axes[0].plot(result["displacement"] * 1e3, result["stress"] / 1e3, style, lw=1.0,
                     label=key)
        _, rows, profile = band_width(result["y"], result["increment"])
        axes[1].plot(profile / profile.max(), rows, style, lw=1.0, label=key)
    axes[0].set_xlabel("top displacement [mm]")
    axes[0].set_ylabel("shear stress [kPa]")
    axes[1].set_xlabel("plastic strain increment, peak to half-softened / its largest")
    axes[1].set_ylabel("y [m]")
    axes[0].legend(fontsize=7)
    figures.save(fig, path, dpi)


def entry():
    """The command: tools/softening_band.py in a checkout, mpm-lig-softening-band installed."""
    cli.run(main, failures=RuntimeError)


if __name__ == "__main__":
    entry()
