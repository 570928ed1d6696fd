#!/usr/bin/python3
"""Cold-build benchmark (docs/build.md). The code is mpm_lig_post/commands/bench_build.py (a
checkout's tool: no installed command)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("bench_build")
