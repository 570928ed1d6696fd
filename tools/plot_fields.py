#!/usr/bin/python3
"""Contours of deviatoric strain and displacement magnitude at one output step (seed Fig. The code
is mpm_lig_post/commands/plot_fields.py (installed: mpm-lig-plot-fields)."""
from mpm_lig_post.commands.plot_fields import entry

if __name__ == "__main__":
    entry()
