"""The mpm_lig tools, one module per command. Each module's `entry()` is the command: the
wrapper tools/NAME.py runs it from a checkout, and an installed package (pyproject.toml) has it
as mpm-lig-NAME."""
