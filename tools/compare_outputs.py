#!/usr/bin/python3
"""Whether two output directories of one case hold the same results, bit for bit. The code is
mpm_lig_post/commands/compare_outputs.py (installed: mpm-lig-compare-outputs)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("compare_outputs")
