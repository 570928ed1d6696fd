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
Exit 0 when every variant ran, 1 when some failed (reported), 2 on bad input. Ctrl-C (SIGINT)
stops the running variants and runs no further one: the study is left to --resume (the
variants finished so far are kept), exit 130 (SIGTERM likewise, exit 143).
"""
from mpm_lig_post.requirements import require

require("numpy", "matplotlib")

import concurrent.futures  # noqa: E402
import os  # noqa: E402
import shutil  # noqa: E402
import signal  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import threading  # noqa: E402
import time  # noqa: E402

from mpm_lig_post import checkout, cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.quantities import quantities  # noqa: E402
from mpm_lig_post.study_spec import Study, write_case  # noqa: E402
from mpm_lig_post.study_report import COST_AXES, collect, write_report  # noqa: E402
from mpm_lig_post.tables import read_json  # noqa: E402


def validate(study, variants, mpm_lig):
    """Write every variant's case to a scratch folder and let the case reader check it."""
    knobs = study.knobs
    with tempfile.TemporaryDirectory(prefix="accuracy_cost_") as scratch:
        for v in variants:
            path = os.path.join(scratch, f"{v.name}.json")
            write_case(study.case_of(v), path)
            r = subprocess.run([mpm_lig, "--validate", path], capture_output=True, text=True)
            if r.returncode != 0:
                # The reader's message is its last line (an MPI library may print more).
                said = (r.stderr.strip() or r.stdout.strip() or f"exit {r.returncode}")
                reason = said.splitlines()[-1].replace(path, "case")
                raise InputError(f"variant {v.name} ({v.label(knobs)}): the case reader refuses "
                                 f"it: {reason}")


def finished(directory, case):
    """A variant whose run ended (exit code recorded) with this very case."""
    try:
        same = read_json(os.path.join(directory, "case.json")) == case
        with open(os.path.join(directory, "exit_code")) as f:
            return same and int(f.read()) == 0 and os.path.isfile(
                os.path.join(directory, "run", "summary.json"))
    except (InputError, OSError, ValueError):
        return False


# A run ended by a signal: mpm_lig's clean stop (SIGINT, SIGTERM, SIGHUP), or killed by one.
STOPPED_CODES = (4, 128 + signal.SIGINT, 128 + signal.SIGTERM, -signal.SIGINT, -signal.SIGTERM)


class Stopped(Exception):
    """A running variant was stopped by a signal (a Ctrl-C that reached it first), or the tool
    got SIGTERM (a batch job's end): args[0] the signal."""


def _terminated(signum, frame):
    raise Stopped(signum)


class Runs:
    """The variants' running processes, so that Ctrl-C can stop them and start no more."""

    def __init__(self):
        self.lock = threading.Lock()
        self.children = {}  # pid -> Popen
        self.stopping = False
        self.stopped = []  # folders of the variants stopped before their end

    def start(self, command, log):
        """Popen(command), or None once stopping."""
        with self.lock:
            if self.stopping:
                return None
            child = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT)
            self.children[child.pid] = child
            return child

    def done(self, child, directory):
        """True when the run ended by itself, False when stop() or a signal ended it (then no
        further run starts)."""
        with self.lock:
            del self.children[child.pid]
            if child.returncode in STOPPED_CODES:
                self.stopping = True
            if self.stopping:
                self.stopped.append(directory)
            return not self.stopping

    def stop(self, grace=30.0):
        """Start no more runs; SIGTERM the running ones (mpm_lig stops cleanly, mpirun passes
        it to its ranks), SIGKILL what is left after `grace` seconds."""
        with self.lock:
            self.stopping = True
            children = list(self.children.values())
        for c in children:
            c.send_signal(signal.SIGTERM)
        deadline = time.monotonic() + grace
        while time.monotonic() < deadline and any(c.pid in self.children for c in children):
            time.sleep(0.05)
        for c in children:
            if c.pid in self.children:
                c.kill()


def run_variant(runs, directory, mpm_lig, ranks):
    """Run one variant; its exit code, or None when the study was stopped (no exit_code
    written: --resume runs it again)."""
    case = os.path.join(directory, "case.json")
    out = os.path.join(directory, "run")
    shutil.rmtree(out, ignore_errors=True)
    command = [mpm_lig, case, "--output", out]
    if ranks > 1:
        command = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks)] + command
    start = time.monotonic()
    with open(os.path.join(directory, "log.txt"), "w") as log:
        child = runs.start(command, log)
        if child is None:
            return None
        # The CPU time of the run and of every process it waited for (the ranks under
        # mpirun): on a shared machine the honest core-seconds, where wall time is not.
        _, status, usage = os.wait4(child.pid, 0)
        child.returncode = code = os.waitstatus_to_exitcode(status)
    if not runs.done(child, directory):
        return None
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
    runs = Runs()
    pool = concurrent.futures.ThreadPoolExecutor(max_workers=jobs)
    ended = 0
    signal.signal(signal.SIGTERM, _terminated)
    try:
        futures = {pool.submit(run_variant, runs, d, mpm_lig, ranks): v for v, d in todo}
        for f in concurrent.futures.as_completed(futures):
            v = futures[f]
            code = f.result()
            if code is None:
                raise Stopped(signal.SIGINT)
            ended += 1
            print(f"{v.name} {v.label(study.knobs)}: "
                  f"{'done' if code == 0 else f'FAILED (exit {code}, see log.txt)'}", flush=True)
    except (KeyboardInterrupt, Stopped) as e:
        # A second signal must not leave runs behind while they are being stopped.
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        signal.signal(signal.SIGTERM, signal.SIG_IGN)
        signum = e.args[0] if isinstance(e, Stopped) else signal.SIGINT
        pool.shutdown(wait=False, cancel_futures=True)
        runs.stop()
        pool.shutdown(wait=True)
        stopped = ", ".join(os.path.basename(d) for d in runs.stopped) or "none"
        how = ("interrupted" if signum == signal.SIGINT
               else f"stopped by {signal.Signals(signum).name}")
        print(f"{cli.tool_name()}: {how}: {ended} of {len(todo)} variants to run ended, "
              f"stopped: {stopped}; the study in {output} is kept: run the same command with "
              "--resume to continue it", file=sys.stderr)
        sys.exit(128 + signum)
    pool.shutdown(wait=True)


def main():
    p = cli.ArgumentParser(description=__doc__.split("\n")[1])
    p.add_argument("study", metavar="STUDY.json")
    p.add_argument("--np", type=cli.positive_int, default=1,
                   help="MPI ranks per variant (default 1)")
    p.add_argument("--jobs", type=cli.positive_int, default=1,
                   help="variants run at a time (default 1)")
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
    p.add_argument("--dpi", type=cli.dpi, default=150)
    a = p.parse_args()
    study = Study(a.study)
    measures = quantities(study.quantities, study.base, a.study)
    variants = study.variants()
    output = cli.writable_folder(a.output or os.path.splitext(os.path.basename(a.study))[0],
                                 "study folder")
    if not a.report_only:
        mpm_lig = checkout.find_mpm_lig(a.mpm_lig)
        started = os.path.isdir(os.path.join(output, "variants"))
        if started and not a.resume:
            raise InputError(f"{output}: holds a study already; give --resume to continue it "
                             "or another --output")
        validate(study, variants, mpm_lig)
        os.makedirs(output, exist_ok=True)
        write_case(read_json(a.study), os.path.join(output, "study.json"))
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


def entry():
    """The command: tools/accuracy_cost.py in a checkout, mpm-lig-accuracy-cost installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
