#!/usr/bin/python3
"""Runs the hard cases of tests/hard and prints their table. The code is
mpm_lig_post/commands/hard_cases.py (a checkout's tool: no installed command)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("hard_cases")
