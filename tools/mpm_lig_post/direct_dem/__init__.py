"""The direct DEM of a footing case (tools/direct_dem.py): the case (case.py), the
preparation of the packing (preparation.py), the opened block and its loading (block.py), the
run with its checkpoints (run.py, checkpoint.py) and its report (report.py)."""
