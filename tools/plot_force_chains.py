#!/usr/bin/python3
"""Force chains of an RVE before and after loading (seed Fig. The code is
mpm_lig_post/commands/plot_force_chains.py (installed: mpm-lig-plot-force-chains)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_force_chains")
