#!/usr/bin/python3
"""Material points inside a rigid footing, step by step, next to its load curve. The code is
mpm_lig_post/commands/footing_intrusion.py (installed: mpm-lig-footing-intrusion)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("footing_intrusion")
