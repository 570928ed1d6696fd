#!/usr/bin/python3
"""The footing's two contacts against the closed forms, at two time steps and four meshes. The
code is mpm_lig_post/commands/footing_contact_study.py (installed: mpm-lig-footing-contact-study)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("footing_contact_study")
