#!/usr/bin/python3
"""Project the cost of an mpm_lig run with dem_rve materials from short measured runs. The code is
mpm_lig_post/commands/cost_projection.py (installed: mpm-lig-cost-projection)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("cost_projection")
