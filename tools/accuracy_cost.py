#!/usr/bin/python3
"""What accuracy costs. The code is mpm_lig_post/commands/accuracy_cost.py (installed:
mpm-lig-accuracy-cost)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("accuracy_cost")
