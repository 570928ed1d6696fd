#!/usr/bin/python3
"""Plot an mpm_lig element test. The code is mpm_lig_post/commands/plot_element.py (installed:
mpm-lig-plot-element)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_element")
