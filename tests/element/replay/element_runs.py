"""Running mpm_lig element tests from the replay checks: a case written, run, its rows read."""
import csv
import json
import os
import subprocess
import sys


def run(command, log):
    """Run `command` with its output in `log`; exit naming it and showing the log on failure."""
    with open(log, "w") as out:
        if subprocess.call(command, stdout=out, stderr=subprocess.STDOUT) != 0:
            sys.exit(f"FAILED: {' '.join(command)}\n{open(log).read()}")


def element_test(mpm_lig, case, work, name):
    """Write `case` as WORK/NAME.json, run it into WORK/NAME; (history rows as text, summary,
    output folder)."""
    case_file = os.path.join(work, name + ".json")
    with open(case_file, "w") as f:
        json.dump(case, f, indent=1)
    out = os.path.join(work, name)
    run([mpm_lig, case_file, "--output", out], out + ".log")
    with open(os.path.join(out, "history.csv")) as f:
        rows = list(csv.DictReader(f))
    return rows, json.load(open(os.path.join(out, "summary.json"))), out
