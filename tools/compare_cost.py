#!/usr/bin/python3
"""Cost and error of runs against a reference run of the same problem (work avoidance. The code is
mpm_lig_post/commands/compare_cost.py (installed: mpm-lig-compare-cost)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("compare_cost")
