#!/usr/bin/python3
"""Plot an mpm_lig element test: usage plot_element.py RUN_DIR [--output FILE.png]

Four panels from RUN_DIR/history.csv: q against the test's strain (axial, shear or per-axis),
stress ratio q/p, volumetric strain (drained) or p (undrained/isotropic), and void ratio.
"""
import argparse
import csv
import json

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run")
    parser.add_argument("--output", help="image file (default RUN/element.png)")
    args = parser.parse_args()
    summary = json.load(open(f"{args.run}/summary.json"))
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(f"{args.run}/history.csv"))]
    col = lambda name: [r[name] for r in rows]
    test, dim = summary["test"], summary["dimension"]
    axial = "e_yy" if dim == 2 else "e_zz"
    if test == "undrained_cyclic_simple_shear":
        x, xlabel = [100 * g for g in col("gamma_xy")], "shear strain γ [%]"
        shear = [r["s_xy"] / 1e3 for r in rows]
    elif test == "isotropic_compression":
        x, xlabel = [-100 * e for e in col("e_xx")], "per-axis strain [%]"
    else:
        x, xlabel = [-100 * e for e in col(axial)], "axial strain [%]"
    p = [v / 1e3 for v in col("p")]
    q = [v / 1e3 for v in col("q")]
    fig, ax = plt.subplots(2, 2, figsize=(10, 7))
    if test == "undrained_cyclic_simple_shear":
        ax[0, 0].plot(x, shear)
        ax[0, 0].set_ylabel("τ_xy [kPa]")
        ax[0, 1].plot(p, shear)
        ax[0, 1].set_xlabel("p [kPa]")
        ax[0, 1].set_ylabel("τ_xy [kPa]")
    else:
        ax[0, 0].plot(x, q)
        ax[0, 0].set_ylabel("q [kPa]")
        ax[0, 1].plot(x, [a / b if b > 0 else 0 for a, b in zip(q, p)])
        ax[0, 1].set_xlabel(xlabel)
        ax[0, 1].set_ylabel("q/p")
    ax[0, 0].set_xlabel(xlabel)
    if test == "drained_biaxial" or test == "drained_triaxial":
        ax[1, 0].plot(x, [-100 * v for v in col("e_vol")])
        ax[1, 0].set_ylabel("volumetric strain (compression +) [%]")
    else:
        ax[1, 0].plot(x, p)
        ax[1, 0].set_ylabel("p [kPa]")
    ax[1, 0].set_xlabel(xlabel)
    ax[1, 1].plot(x, col("void_ratio"))
    ax[1, 1].set_xlabel(xlabel)
    ax[1, 1].set_ylabel("void ratio")
    fig.suptitle(f"{test}, {summary['grains']} grains, {summary['engine']}")
    fig.tight_layout()
    out = args.output or f"{args.run}/element.png"
    fig.savefig(out, dpi=120)
    print(out)


if __name__ == "__main__":
    main()
