#!/usr/bin/python3
"""A Mohr-Coulomb continuum calibrated from a packing's own element tests, for the parts of an MPM
case where grains need not be simulated (a `dem_rve` region beside a continuum region). The code
is mpm_lig_post/commands/calibrate_continuum.py (installed: mpm-lig-calibrate-continuum)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("calibrate_continuum")
