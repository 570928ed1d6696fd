"""Matplotlib set-up (Agg, publication defaults) and saving."""
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "font.size": 11,
    "axes.labelsize": 12,
    "axes.titlesize": 12,
    "legend.fontsize": 10,
    "xtick.labelsize": 10,
    "ytick.labelsize": 10,
    "xtick.direction": "in",
    "ytick.direction": "in",
    "xtick.top": True,
    "ytick.right": True,
    "axes.grid": False,
    "lines.linewidth": 1.4,
    "savefig.dpi": 200,
    "savefig.bbox": "tight",
    "mathtext.fontset": "dejavusans",
}


def subplots(*args, **kwargs):
    """plt.subplots under the project style."""
    plt.rcParams.update(STYLE)
    return plt.subplots(*args, **kwargs)


def save(fig, path):
    """Write the figure (creating the folder) and report where."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fig.savefig(path)
    plt.close(fig)
    print(f"wrote {path}")
