"""Runs the hard cases of tests/hard and prints their table: case | criterion | measured margin
(the rows of docs/testing.md, "Hard cases"). The default sizes are those of the `hard` tests;
--long runs longer variants (more cycles after liquefaction, more turns of shear, a footing on
100-disc RVEs) and applies the same criteria to them.

usage: tools/hard_cases.py MPM_LIG WORK_DIR [--long] [--only NAME ...] [--json FILE]

Each case writes WORK_DIR/<name>/; the table goes to stdout (markdown) and, with --json, to FILE.
Exit 1 if a criterion failed or a run did not end as it should."""
import argparse
import json
import os
import subprocess
import sys

from mpm_lig_post import checkout, cli
from mpm_lig_post.errors import InputError

HARD = checkout.path("tests", "hard")
CHECK_MPM = os.path.join(HARD, "check_mpm_hard.py")
CHECK_LIQ = os.path.join(HARD, "check_liquefaction.py")


def edited(case, work, name, edit):
    """The case file of tests/hard, edited for a long variant, written into WORK_DIR."""
    c = json.load(open(os.path.join(HARD, case)))
    if edit:
        edit(c)
    path = os.path.join(work, name + ".json")
    json.dump(c, open(path, "w"), indent=1)
    return path


def set_end_steps(steps):
    return lambda c: c["analysis"].update(end={"steps": steps})


def set_cycles(cycles):
    return lambda c: c["analysis"].update(cycles=cycles)


def bigger_rve(grains):
    def edit(c):
        c["materials"][0]["rve"]["grains"] = grains
    return edit


# name, case file, check command (output folder appended), long-variant edit
CASES = [
    ("element_liquefaction", "element_liquefaction.json",
     [CHECK_LIQ, "--fraction", "0.01", "--cycles", "2", "--increments-per-cycle", "200",
      "--max-substeps", "200", "--history-in"], set_cycles(30)),
    ("mpm_liquefaction", "mpm_liquefaction.json",
     [CHECK_LIQ, "--fraction", "0.01", "--cycles", "2", "--mean", "mean_stress", "--shear",
      "shear_stress", "--cycle-column", "cycle", "--history-in"], set_end_steps(3500)),
    ("mpm_extension", "mpm_extension.json", [CHECK_MPM, "extension"], None),
    ("mpm_free_surface", "mpm_free_surface.json", [CHECK_MPM, "free_surface"], None),
    ("mpm_large_shear", "mpm_large_shear.json", [CHECK_MPM, "large_shear"], None),
    ("mpm_velocity_step", "mpm_velocity_step.json", [CHECK_MPM, "velocity_step"], None),
    ("mpm_footing_deep", "mpm_footing_deep.json", [CHECK_MPM, "footing_deep"], bigger_rve(100)),
]


def run_case(exe, work, name, case, check, edit, long):
    out = os.path.join(work, name)
    case_file = edited(case, work, name, edit if long else None)
    subprocess.run(["rm", "-rf", out], check=True)
    run = subprocess.run([exe, case_file, "--output", out], capture_output=True, text=True)
    if run.returncode != 0:
        tail = (run.stderr or run.stdout).strip().splitlines()[-3:]
        return {"case": name, "row": "run failed (exit %d): %s" % (run.returncode, " / ".join(tail)),
                "passed": False}
    result = subprocess.run(["/usr/bin/python3"] + check + [out], capture_output=True, text=True)
    lines = result.stdout.strip().splitlines()
    return {"case": name, "row": lines[0] if lines else result.stderr.strip(),
            "failures": [l for l in lines[1:] if l.startswith("FAIL")],
            "passed": result.returncode == 0}


def main():
    ap = cli.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("mpm_lig")
    ap.add_argument("work")
    ap.add_argument("--long", action="store_true", help="the longer variants")
    ap.add_argument("--only", nargs="*", help="case names (default: all)")
    ap.add_argument("--json", help="write the table as JSON too")
    a = ap.parse_args()
    if not os.path.isfile(a.mpm_lig) or not os.access(a.mpm_lig, os.X_OK):
        raise InputError(f"{a.mpm_lig}: not an executable (give the mpm_lig program, e.g. "
                         "build/mpm_lig)")
    cli.writable_file(a.json, "--json file")
    cli.writable_folder(a.work, "work folder")
    names = [c[0] for c in CASES]
    unknown = [n for n in (a.only or []) if n not in names]
    if unknown:
        raise InputError(f"--only: unknown case(s) {', '.join(unknown)}; known: "
                         f"{', '.join(names)}")
    os.makedirs(a.work, exist_ok=True)
    results = []
    print("| run | case | criterion | measured margin | passed |\n|---|---|---|---|---|")
    for name, case, check, edit in CASES:
        if a.only and name not in a.only:
            continue
        r = run_case(os.path.abspath(a.mpm_lig), a.work, name, case, check, edit, a.long)
        cells = [c.replace("|", "\\|") for c in r["row"].split(" | ")]
        print("| %s | " % name + " | ".join(cells + [""] * (3 - len(cells))) + " | %s |" %
              ("yes" if r["passed"] else "NO: " + "; ".join(r.get("failures", []))), flush=True)
        results.append(dict(r, variant="long" if a.long else "test"))
    if a.json:
        json.dump(results, open(a.json, "w"), indent=1)
    sys.exit(0 if all(r["passed"] for r in results) else 1)


def entry():
    """The command: tools/hard_cases.py in a checkout (it needs the checkout's files)."""
    cli.run(main)


if __name__ == "__main__":
    entry()
