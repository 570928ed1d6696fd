#!/usr/bin/python3
"""How fast a footing run's material points move against the footing, and how many packings carry
nothing. The code is mpm_lig_post/commands/footing_noise.py (installed: mpm-lig-footing-noise)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("footing_noise")
