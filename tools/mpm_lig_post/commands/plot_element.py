"""Plot an mpm_lig element test: usage plot_element.py RUN_DIR [-o FILE.png] [--dpi N]

Four panels from RUN_DIR/history.csv: q against the test's strain (axial, shear or per-axis),
stress ratio q/p, volumetric strain (drained) or p (undrained/isotropic), and void ratio.
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import os  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.tables import read_history, read_json, require_columns  # noqa: E402


def main():
    args = cli.parser(__doc__.split("\n")[0], "element.png").parse_args()
    run = cli.output_dir(args)
    summary = read_json(os.path.join(run, "summary.json"))
    for key in ("test", "dimension", "grains", "engine"):
        if key not in summary:
            raise InputError(f"{run}/summary.json: missing key '{key}'")
    history_path = os.path.join(run, "history.csv")
    table = read_history(history_path)
    require_columns(table, ("p", "q", "void_ratio"), history_path)

    def col(name):
        require_columns(table, (name,), history_path)
        return table[name]

    test, dim = summary["test"], summary["dimension"]
    axial = "e_yy" if dim == 2 else "e_zz"
    if test == "undrained_cyclic_simple_shear":
        x, xlabel = [100 * g for g in col("gamma_xy")], "shear strain γ [%]"
        shear = col("s_xy") / 1e3
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
    out = cli.picture_path(args)
    fig.savefig(out, dpi=args.dpi)
    print(out)


def entry():
    """The command: tools/plot_element.py in a checkout, mpm-lig-plot-element installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
