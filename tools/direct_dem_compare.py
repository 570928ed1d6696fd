#!/usr/bin/python3
"""Direct DEM footing runs (tools/direct_dem.py) against the multiscale runs of the same case. The
code is mpm_lig_post/commands/direct_dem_compare.py (installed: mpm-lig-direct-dem-compare)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("direct_dem_compare")
