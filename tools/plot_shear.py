#!/usr/bin/python3
"""Cyclic simple shear. The code is mpm_lig_post/commands/plot_shear.py (installed:
mpm-lig-plot-shear)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_shear")
