#!/usr/bin/python3
"""The multiscale footing beside the grains, place by place: an MPM run's points over the
windows of a direct DEM's probes. The code is mpm_lig_post/commands/mpm_probes.py (installed:
mpm-lig-mpm-probes)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("mpm_probes")
