#!/usr/bin/python3
"""The couple stress a symmetric stress drops: the antisymmetric part of a direct-DEM footing's grain stress. The code
is mpm_lig_post/commands/couple_stress.py (installed: mpm-lig-couple-stress)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("couple_stress")
