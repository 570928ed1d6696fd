#!/usr/bin/python3
"""Native LIGGGHTS twin of an mpm_lig element test. The code is
mpm_lig_post/commands/native_twin.py (installed: mpm-lig-native-twin)."""
from mpm_lig_post import launch

if __name__ == "__main__":
    launch.command("native_twin")
