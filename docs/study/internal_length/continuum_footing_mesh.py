#!/usr/bin/python3
"""The internal length's mesh study on a continuum: the DEM footing's mesh, footing and penalty
contact on a Mohr-Coulomb soil softening with its plastic strain (odd_even_continuum/mc_soft.json)
pushed to s/B = 1.0 on h = B/4, B/8, B/16 (and B/32), without and with the length: whether the
regularised footing's post-peak load converges with h when no RVE is involved (minutes, where
the DEM footing's B/16 takes a day of one core).

usage: continuum_footing_mesh.py -o OUT [--mpm-lig build/mpm_lig] [--meshes 4 8 16]
       [--variants local length ...] [--length 0.08] [--softening-modulus 3.5e5] [--reuse]
       [--flip F] [--set PATH=JSON ...] [--tag NAME] [--whole] [--plot PNG]

Variants: local (no length), length (the second gradient), bounded01 / bounded03 (yield_strain
0.1 / 0.3), residual (residual_weight 1). Writes OUT/<variant>_h<n>/ (case.json and the run)
and OUT/continuum_footing_mesh.json: per run the MPM steps, the highest load to s/B 0.4 and
the trapezoid means of q/q_s over the windows below, and the gradient's share of the footing's
work over s/B 0.4-1.0 (stored, and dissipated by a bounded gradient) and the local damping's
(output.damping_work, which every case it writes turns on) over s/B 0-0.4 and 0.4-1.0. --reuse skips runs whose
summary.json exists. --flip sets analysis.flip (the base case's 0.99 otherwise) and adds
_flipF to the run names. --set changes any key of the case (PATH as study specs write it,
VALUE as JSON: analysis.volumetric_smoothing=false, rigid_bodies[0].interface='"smooth"'); --tag
NAME is added to the run names of such a probe. --whole runs the whole footing on a soil twice
as wide, without the symmetry plane at its centre line (names get _whole). --plot PNG draws
q/q_s against s/B of every run of the call, one panel a variant.
"""
import argparse
import copy
import csv
import json
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "..", "tools"))
from mpm_lig_post.study_spec import set_path  # noqa: E402

BASE = os.path.join(HERE, "odd_even_continuum", "mc_soft.json")
WINDOWS = [(0.05, 0.1), (0.1, 0.4), (0.4, 1.0), (0.4, 0.7), (0.7, 1.0)]
VARIANTS = {"local": None, "length": {}, "bounded01": {"yield_strain": 0.1},
            "bounded03": {"yield_strain": 0.3}, "residual": {"residual_weight": 1.0}}
WIDTH, SURCHARGE, SURFACE = 0.2, 1e5, 0.6


def mirror(c):
    """The whole footing: the soil 1.2 m wide, the footing at its middle, the surcharge on both
    sides of it."""
    c["mesh"]["size"][0] = 1.2
    c["bodies"][0]["box"]["max"][0] = 1.2
    c["rigid_bodies"][0]["center"][0] = 0.6
    right = c["boundary_conditions"][3]
    left = copy.deepcopy(right)
    right["points"]["min"][0], right["points"]["max"][0] = 0.7, 1.2
    left["points"]["min"][0], left["points"]["max"][0] = 0.0, 0.5
    c["boundary_conditions"].append(left)


def case_for(base, refinement, variant, length, softening_modulus, flip=None, settings=(),
             whole=False):
    """The base case on h = B/refinement (0.6 x 0.8 m, cells of B/refinement) to s/B = 1.0."""
    c = copy.deepcopy(base)
    h = WIDTH / refinement
    if whole:
        mirror(c)
    c["mesh"]["cells"] = [round(c["mesh"]["size"][0] / h), round(0.8 / h)]
    c["analysis"]["end"]["time"] = WIDTH / c["rigid_bodies"][0]["velocity"]
    # the surcharge on the top row of points beside the footing (one point a cell)
    for bc in c["boundary_conditions"][3:]:
        bc["points"]["min"][1] = SURFACE - h / 2 - h / 4
    if flip is not None:
        c["analysis"]["flip"] = flip
    extra = VARIANTS[variant]
    if extra is not None:
        c["analysis"]["internal_length"] = {"length": length,
                                            "softening_modulus": softening_modulus, **extra}
    for assignment in settings:
        path, value = assignment.split("=", 1)
        set_path(c, path, json.loads(value), create=True)
    c["output"]["damping_work"] = True
    c["title"] = f"continuum footing, h = B/{refinement}, {variant}, to s/B 1.0"
    c["_about"] = ("docs/study/internal_length/continuum_footing_mesh.py: mc_soft.json on "
                   f"h = B/{refinement} to s/B 1.0, {variant}")
    c.pop("_run", None)
    return c


def read_history(path):
    rows = list(csv.DictReader(open(path)))
    s = np.array([float(r["settlement"]) for r in rows]) / WIDTH
    q = np.array([float(r["q"]) for r in rows]) / SURCHARGE
    load = np.array([float(r["load"]) for r in rows])
    energy = np.array([float(r.get("gradient_energy", 0.0) or 0.0) for r in rows])
    dissipated = np.array([float(r.get("gradient_dissipation", 0.0) or 0.0) for r in rows])
    damping = (np.array([float(r["damping_work"]) for r in rows]) if "damping_work" in rows[0]
               else None)
    return s, q, load, energy, dissipated, damping


def window_mean(s, q, a, b):
    m = (s >= a) & (s <= b)
    return float(np.trapz(q[m], s[m]) / (s[m][-1] - s[m][0]))


def measure(run_dir):
    s, q, load, energy, dissipated, damping = read_history(os.path.join(run_dir, "history.csv"))
    u = s * WIDTH
    work = np.concatenate([[0.0], np.cumsum(0.5 * (load[1:] + load[:-1]) * np.diff(u))])
    a, b = np.searchsorted(s, 0.4), min(np.searchsorted(s, 1.0), len(s) - 1)
    early = s <= 0.4
    i = int(np.argmax(np.where(early, q, -np.inf)))
    summary = json.load(open(os.path.join(run_dir, "summary.json")))
    return {"mpm_steps": summary["mpm_steps"], "highest": float(q[i]), "at": float(s[i]),
            "windows": {f"{lo}-{hi}": window_mean(s, q, lo, hi) for lo, hi in WINDOWS},
            "gradient_energy_share_0.4-1.0": float((energy[b] - energy[a]) / (work[b] - work[a])),
            "gradient_dissipation_share_0.4-1.0":
                float((dissipated[b] - dissipated[a]) / (work[b] - work[a])),
            # the local damping's work over the footing's (runs written before
            # output.damping_work: None)
            "damping_share_0.4-1.0": (None if damping is None else
                                      float((damping[b] - damping[a]) / (work[b] - work[a]))),
            "damping_share_0-0.4": (None if damping is None else
                                    float((damping[a] - damping[0]) / (work[a] - work[0])))}


def plot(args, results):
    """q/q_s against s/B, one panel a variant, one line a mesh."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(args.variants), figsize=(5.5 * len(args.variants), 4),
                             sharey=True, squeeze=False)
    for ax, variant in zip(axes[0], args.variants):
        for name in results:
            if name.startswith(variant + "_h"):
                s, q = read_history(os.path.join(args.output, name, "history.csv"))[:2]
                ax.plot(s, q, lw=1, label=f"B/{name.split('_h')[1].split('_')[0]}")
        title = variant + (f", {args.tag}" if args.tag else "")
        ax.set(title=title, xlabel="s/B", xlim=(0, 1))
        ax.legend()
    axes[0][0].set_ylabel("q/q_s")
    fig.tight_layout()
    fig.savefig(args.plot, dpi=110)
    print(f"wrote {args.plot}")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("-o", "--output", required=True)
    p.add_argument("--mpm-lig", default="build/mpm_lig")
    p.add_argument("--meshes", type=int, nargs="+", default=[4, 8, 16])
    p.add_argument("--variants", nargs="+", default=["local", "length"], choices=list(VARIANTS))
    p.add_argument("--length", type=float, default=0.08)
    p.add_argument("--softening-modulus", type=float, default=3.5e5)
    p.add_argument("--reuse", action="store_true")
    p.add_argument("--flip", type=float)
    p.add_argument("--set", nargs="+", default=[], dest="settings")
    p.add_argument("--tag", default="")
    p.add_argument("--whole", action="store_true")
    p.add_argument("--plot", metavar="PNG")
    args = p.parse_args()
    base = json.load(open(BASE))
    os.makedirs(args.output, exist_ok=True)
    results = {}
    for variant in args.variants:
        for n in args.meshes:
            name = f"{variant}_h{n}" + ("" if args.flip is None else f"_flip{args.flip:g}")
            name += f"_{args.tag}" if args.tag else ""
            name += "_whole" if args.whole else ""
            run_dir = os.path.join(args.output, name)
            case_path = os.path.join(args.output, f"{name}.json")
            if not (args.reuse and os.path.isfile(os.path.join(run_dir, "summary.json"))):
                with open(case_path, "w") as f:
                    json.dump(case_for(base, n, variant, args.length, args.softening_modulus,
                                       args.flip, args.settings, args.whole), f, indent=1)
                done = subprocess.run([args.mpm_lig, case_path, "--output", run_dir,
                                       "--replace"], capture_output=True, text=True)
                if done.returncode != 0:
                    sys.exit(f"{name}: mpm_lig exited {done.returncode}: {done.stderr.strip()}")
            results[name] = measure(run_dir)
            r = results[name]
            w = " ".join(f"{k} {v:.2f}" for k, v in r["windows"].items())
            print(f"{name:14s} steps {r['mpm_steps']:6d} highest {r['highest']:.2f} "
                  f"({r['at']:.3f}) {w} gradient energy / dissipated share "
                  f"{r['gradient_energy_share_0.4-1.0']:.3f} / "
                  f"{r['gradient_dissipation_share_0.4-1.0']:.3f} damping share 0-0.4 / 0.4-1.0 "
                  f"{r['damping_share_0-0.4']} / {r['damping_share_0.4-1.0']}",
                  flush=True)
    if args.plot:
        plot(args, results)
    out = os.path.join(args.output, "continuum_footing_mesh" + (f"_{args.tag}" if args.tag else "")
                       + ".json")
    with open(out, "w") as f:
        json.dump({"length": args.length, "softening_modulus": args.softening_modulus,
                   "settings": args.settings, "runs": results}, f, indent=1)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
