"""Matplotlib set-up (Agg, publication defaults) and saving. pyplot is imported on first
use, so a tool that stops on bad input does not pay for it."""
import os

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


def pyplot():
    """matplotlib.pyplot on the Agg backend, under the project style."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(STYLE)
    return plt


def subplots(*args, **kwargs):
    """plt.subplots under the project style."""
    return pyplot().subplots(*args, **kwargs)


def save(fig, path, dpi=None):
    """Write the figure (creating the folder) and report where."""
    folder = os.path.dirname(os.path.abspath(path))
    os.makedirs(folder, exist_ok=True)
    fig.savefig(path, dpi=dpi or STYLE["savefig.dpi"])
    pyplot().close(fig)
    print(f"wrote {path}")


def run_name(directory):
    """A run's name in titles: its output folder's own name."""
    return os.path.basename(os.path.abspath(directory))


def finish(fig, path, dpi=None):
    """Lay the figure out and save it: the last step of every picture command."""
    fig.tight_layout()
    save(fig, path, dpi)
