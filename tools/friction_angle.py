#!/usr/bin/python3
"""Macroscopic friction angle from drained biaxial/triaxial element tests. The code is
mpm_lig_post/commands/friction_angle.py (installed: mpm-lig-friction-angle)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("friction_angle")
