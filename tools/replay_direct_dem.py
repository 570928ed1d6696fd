#!/usr/bin/python3
"""The RVE against the grains on the grains' own path: direct-DEM probes replayed on RVEs. The
code is mpm_lig_post/commands/replay_direct_dem.py (installed: mpm-lig-replay-direct-dem)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("replay_direct_dem")
