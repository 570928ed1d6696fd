#!/usr/bin/python3
"""Whether a 2D RVE deformed uniformly or in a band between two snapshots. The code
is mpm_lig_post/commands/rve_localisation.py (installed: mpm-lig-rve-localisation)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("rve_localisation")
