#!/usr/bin/python3
"""Direct DEM of a 2D mpm_lig footing case. The code is mpm_lig_post/commands/direct_dem.py
(installed: mpm-lig-direct-dem)."""
from mpm_lig_post.commands.direct_dem import entry

if __name__ == "__main__":
    entry()
