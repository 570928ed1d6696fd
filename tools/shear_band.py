#!/usr/bin/python3
"""The shear band of a direct-DEM footing and its width in grain diameters. The code
is mpm_lig_post/commands/shear_band.py (installed: mpm-lig-shear-band)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("shear_band")
