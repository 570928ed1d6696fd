"""Readers and figure helpers shared by the mpm_lig plotting tools (tools/plot_*.py).

Every reader raises InputError with the file and, where it applies, the missing column or
dataset named; `cli.run` turns it into a one-line message on stderr and exit code 2.
"""
from .errors import InputError

__all__ = ["InputError"]
