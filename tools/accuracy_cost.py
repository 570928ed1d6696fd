#!/usr/bin/python3
"""What accuracy costs. The code is mpm_lig_post/commands/accuracy_cost.py (installed:
mpm-lig-accuracy-cost)."""
from mpm_lig_post.commands.accuracy_cost import entry

if __name__ == "__main__":
    entry()
