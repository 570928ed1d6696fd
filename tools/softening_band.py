#!/usr/bin/python3
"""A softening layer on three meshes, with and without an internal length: its band's width and
its load curve. The code is mpm_lig_post/commands/softening_band.py (installed:
mpm-lig-softening-band)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("softening_band")
