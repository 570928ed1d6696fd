"""The Python side of mpm_lig: readers of its outputs, figure helpers and the study machinery
shared by the tools, and under `commands/` the code of each tool (tools/NAME.py in a checkout,
mpm-lig-NAME when installed from pyproject.toml).

Every reader raises InputError with the file and, where it applies, the missing column or
dataset named; `cli.run` turns it into a one-line message on stderr and exit code 2.
"""
from .errors import InputError

__all__ = ["InputError"]
