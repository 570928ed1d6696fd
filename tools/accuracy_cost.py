#!/usr/bin/python3
"""What accuracy costs: run a sweep of settings of one case and measure each variant's error
against a reference variant and its cost.

usage: accuracy_cost.py STUDY.json [--np N] [--jobs J] [--resume] [--output DIR]
                        [--mpm-lig PATH] [--report-only]

STUDY.json names a base case, the knobs (JSON paths into the case) with their values, the
reference settings (the most accurate of the sweep) and optionally seeds whose scatter on the
reference is the noise floor (format: tools/mpm_lig_post/study_spec.py). Every variant's case is
checked with `mpm_lig --validate` first: an unknown knob path, a value the case reader refuses
or a missing reference stops the tool with exit code 2 before anything runs or is created.
Variants are written to OUTPUT/variants/vNNN/case.json and run there (mpirun -np N when N > 1,
J variants at a time); with --resume the variants already finished (summary.json written, same
case) are not run again. Then OUTPUT/accuracy_cost.{json,csv,png} are written and the table
printed: per variant the quantities, their errors, wall seconds, core-seconds, DEM
particle-steps and the rate model's predicted stepping core-seconds with its error.
Exit 0 when every variant ran, 1 when some failed (reported), 2 on bad input.
"""
import argparse
import concurrent.futures
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time

from mpm_lig_post import cli
from mpm_lig_post.errors import InputError
from mpm_lig_post.quantities import quantities
from mpm_lig_post.study_spec import Study, write_case
from mpm_lig_post.study_report import COST_AXES, collect, write_report

HERE = os.path.dirname(os.path.abspath(__file__))


def find_mpm_lig(given):
    candidates = [given] if given else [os.path.join(HERE, "..", "build", "mpm_lig"),
                                        shutil.which("mpm_lig")]
    for c in candidates:
        if c and os.path.isfile(c) and os.access(c, os.X_OK):
            return os.path.abspath(c)
    raise InputError(f"mpm_lig executable not found ({given or 'build/mpm_lig or PATH'}): "
                     "give --mpm-lig PATH")


def validate(study, variants, mpm_lig):
    """Write every variant's case to a scratch folder and let the case reader check it."""
    knobs = study.knobs
    with tempfile.TemporaryDirectory(prefix="accuracy_cost_") as scratch:
        for v in variants:
            path = os.path.join(scratch, f"{v.name}.json")
            write_case(study.case_of(v), path)
            r = subprocess.run([mpm_lig, "--validate", path], capture_output=True, text=True)
            if r.returncode != 0:
                reason = (r.stderr.strip() or r.stdout.strip()).replace(path, "case")
                raise InputError(f"variant {v.name} ({v.label(knobs)}): the case reader refuses "
                                 f"it: {reason}")


def finished(directory, case):
    """A variant whose run ended (exit code recorded) with this very case."""
    try:
        with open(os.path.join(directory, "case.json")) as f:
            same = json.load(f) == case
        with open(os.path.join(directory, "exit_code")) as f:
            return same and int(f.read()) == 0 and os.path.isfile(
                os.path.join(directory, "run", "summary.json"))
    except (OSError, ValueError):
        return False


def run_variant(directory, mpm_lig, ranks):
    case = os.path.join(directory, "case.json")
    out = os.path.join(directory, "run")
    shutil.rmtree(out, ignore_errors=True)
    command = [mpm_lig, case, "--output", out]
    if ranks > 1:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    start = time.monotonic()
    with open(os.path.join(directory, "log.txt"), "w") as log:
        child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
        # The CPU time of the run and of every process it waited for (the ranks under
        # mpirun): on a shared machine the honest core-seconds, where wall time is not.
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = code = os.waitstatus_to_exitcode(status)
    with open(os.path.join(directory, "wall_seconds"), "w") as f:
        f.write(f"{time.monotonic() - start:.6g}\n")
    with open(os.path.join(directory, "cpu_seconds"), "w") as f:
        f.write(f"{usage.ru_utime + usage.ru_stime:.6g}\n")
    with open(os.path.join(directory, "exit_code"), "w") as f:
        f.write(f"{code}\n")
    return code


def run_all(study, variants, output, mpm_lig, ranks, jobs):
    todo = []
    for v in variants:
        directory = os.path.join(output, "variants", v.folder)
        case = study.case_of(v)
        if finished(directory, case):
            print(f"{v.name} {v.label(study.knobs)}: finished before, not run again")
            continue
        write_case(case, os.path.join(directory, "case.json"))
        todo.append((v, directory))
    with concurrent.futures.ThreadPoolExecutor(max_workers=jobs) as pool:
        futures = {pool.submit(run_variant, d, mpm_lig, ranks): v for v, d in todo}
        for f in concurrent.futures.as_completed(futures):
            v = futures[f]
            code = f.result()
            print(f"{v.name} {v.label(study.knobs)}: "
                  f"{'done' if code == 0 else f'FAILED (exit {code}, see log.txt)'}", flush=True)


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("study", metavar="STUDY.json")
    p.add_argument("--np", type=int, default=1, help="MPI ranks per variant (default 1)")
    p.add_argument("--jobs", type=int, default=1, help="variants run at a time (default 1)")
    p.add_argument("--resume", action="store_true",
                   help="continue in an existing OUTPUT; finished variants are not run again")
    p.add_argument("--output", help="study folder (default ./<study name>)")
    p.add_argument("--mpm-lig", help="the mpm_lig executable (default build/mpm_lig, PATH)")
    p.add_argument("--report-only", action="store_true",
                   help="run nothing: report the variants already finished in OUTPUT")
    p.add_argument("--cost", choices=COST_AXES, default="core-seconds",
                   help="what the picture and the recommendations count as cost: wall x ranks "
                        "(default), the runs' CPU time (robust on a shared machine) or DEM "
                        "particle-steps (deterministic)")
    p.add_argument("--dpi", type=int, default=150)
    a = p.parse_args()
    if a.np < 1 or a.jobs < 1:
        raise InputError(f"--np and --jobs must be >= 1 (got {a.np}, {a.jobs})")
    study = Study(a.study)
    measures = quantities(study.quantities, study.base, a.study)
    variants = study.variants()
    output = a.output or os.path.splitext(os.path.basename(a.study))[0]
    if not a.report_only:
        mpm_lig = find_mpm_lig(a.mpm_lig)
        started = os.path.isdir(os.path.join(output, "variants"))
        if started and not a.resume:
            raise InputError(f"{output}: holds a study already; give --resume to continue it "
                             "or another --output")
        validate(study, variants, mpm_lig)
        os.makedirs(output, exist_ok=True)
        write_case(json.load(open(a.study)), os.path.join(output, "study.json"))
        print(f"{len(variants)} variants of {study.base_path} in {output}", flush=True)
        run_all(study, variants, output, mpm_lig, a.np, a.jobs)
    elif not os.path.isdir(os.path.join(output, "variants")):
        raise InputError(f"{output}: no variants to report (nothing has run there)")
    results = collect(study, variants, measures, output, a.np, a.cost.replace("-", "_"))
    write_report(study, results, measures, output, a.dpi)
    failed = [r for r in results["variants"] if r["status"] != "done"]
    if failed:
        print(f"{len(failed)} variant(s) did not finish: "
              f"{', '.join(r['name'] for r in failed)}", file=sys.stderr)
        sys.exit(1)


if __name__ == "__main__":
    cli.run(main)
