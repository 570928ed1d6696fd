#!/usr/bin/python3
"""Normalised load-settlement curve of a strip footing (seed Fig. The code is
mpm_lig_post/commands/plot_footing.py (installed: mpm-lig-plot-footing)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_footing")
