#!/usr/bin/python3
"""Where the DEM time went. The code is mpm_lig_post/commands/plot_dem_work.py (installed:
mpm-lig-plot-dem-work)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_dem_work")
