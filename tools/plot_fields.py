#!/usr/bin/python3
"""Contours of deviatoric strain and displacement magnitude at one output step (seed Fig. The code
is mpm_lig_post/commands/plot_fields.py (installed: mpm-lig-plot-fields)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("plot_fields")
