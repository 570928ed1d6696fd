#!/usr/bin/python3
"""Stepping efficiency and wall time of a dem_rve run projected to other rank counts, from the
run's cost record (<output>/packings/m<id>/cost_record.h5, docs/outputs.md). The code is
mpm_lig_post/commands/scaling_model.py (installed: mpm-lig-scaling-model)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("scaling_model")
