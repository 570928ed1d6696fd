#!/usr/bin/python3
"""Library API vs native executable on the same DEM work (≈400 dense grains under shear). The code
is mpm_lig_post/commands/bench_engine.py (a checkout's tool: no installed command)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("bench_engine")
