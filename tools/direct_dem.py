#!/usr/bin/python3
"""Direct DEM of a 2D mpm_lig footing case. The code is mpm_lig_post/commands/direct_dem.py
(installed: mpm-lig-direct-dem), which imports numpy unchecked: what a run needs is checked here."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("direct_dem", needs=("numpy", "h5py", "matplotlib"))
