#!/usr/bin/env python3
"""Robustness probes: a catalogue of malformed inputs and failures, by category, run against an
mpm_lig binary; prints how many probes of each category were tried and how many ended cleanly.

A probe is clean when the process ends by itself within its time limit (no crash, no hang) with
the exit code the probe expects (2: bad input, refused before anything is created; 1: a run
that fails; 0: input that must work), with a non-empty, printable message of bounded size that
matches the probe's pattern (the JSON path or option at fault), and, for a refusal, with no
output folder and no other file created.

    tests/robustness/probe_robustness.py build/mpm_lig                 # every category
    tests/robustness/probe_robustness.py build/mpm_lig --category size # one category
    tests/robustness/probe_robustness.py build/mpm_lig --only deep_title --strict  # (CTest)
    tests/robustness/probe_robustness.py build/mpm_lig --list          # names, categories
    tests/robustness/probe_robustness.py build/mpm_lig --extra my_probes.py --json counts.json

Category hook: `--extra FILE.py` runs FILE.py with `probe`, `Probe`, `REPO`, `case`, `write_case`
and `run_in` in its namespace; every function it decorates with @probe(category, name, ...)
joins the catalogue (e.g. checkpoint and resume scenarios).

Exit status: 0; with --strict 1 when a probe run was not clean; 77 when every selected probe
was skipped (a full-disk probe where no tmpfs can be mounted).
"""
import argparse
import copy
import json
import os
import random
import re
import resource
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable, List, Optional

REPO = Path(__file__).resolve().parents[2]
FREE_FLIGHT = REPO / "cases/mpm/free_flight.json"  # continuum, 400 steps, < 1 s
PRANDTL = REPO / "cases/mpm/prandtl_tresca.json"  # continuum footing
TINY_DEM = REPO / "tests/coupling/tiny_2x2.json"  # 4 DEM points, 80 discs, a few seconds
ELEMENT = REPO / "cases/element_quickstart.json"  # element test on one RVE

MAX_MESSAGE_BYTES = 20000  # a message longer than this is not a message
MEMORY_LIMIT_BYTES = 8 << 30  # address space of a probed process: protects a shared machine
MPIRUN = ["mpirun", "--allow-run-as-root", "--oversubscribe"]
SKIPPED = 77  # exit status when every selected probe was skipped (CTest SKIP_RETURN_CODE)


@dataclass
class Probe:
    category: str
    name: str
    make: Callable[[Path], List[str]]  # writes inputs into a fresh folder, returns the arguments
    exit: int = 2
    expect: str = ""  # regex the output must match (the JSON path at fault)
    timeout: float = 30.0
    np: int = 0  # > 0: run under mpirun -np
    check: Optional[Callable[[Path, "Outcome"], str]] = None  # extra check, "" when fine
    needs: Optional[Callable[[], str]] = None  # "" when the probe can run here, else why not
    program: Optional[List[str]] = None  # the command probed instead of the mpm_lig binary


@dataclass
class Outcome:
    code: Optional[int]  # None: killed at the time limit
    output: str  # stdout and stderr
    errors: str  # stderr: the message of a failure
    seconds: float
    new_files: List[str] = field(default_factory=list)


CATALOGUE: List[Probe] = []


def probe(category, name, **options):
    """Decorator: `make(work) -> args` becomes a probe of `category`."""
    def register(make):
        CATALOGUE.append(Probe(category, name, make, **options))
        return make
    return register


def case(path):
    return json.loads(Path(path).read_text())


def write_case(work, data, name="case.json"):
    (work / name).write_text(json.dumps(data, indent=1) if not isinstance(data, str) else data)
    return str(work / name)


def text_with(path, old, new):
    text = Path(path).read_text()
    assert old in text, (path, old)
    return text.replace(old, new, 1)


def validate_edit(work, old, new):
    """--validate of the free-flight case with `old` replaced by `new` in its text."""
    return ["--validate", write_case(work, text_with(FREE_FLIGHT, old, new))]


def validate_bytes(work, data):
    (work / "case.json").write_bytes(data)
    return ["--validate", str(work / "case.json")]


def limit_memory():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT_BYTES, MEMORY_LIMIT_BYTES))
    os.setsid()  # the whole process group can be killed at the time limit


def run_in(work, binary, args, timeout, np=0, program=None):
    """Run `binary args` (or `program args`) in `work`; returns an Outcome (code None after the
    time limit)."""
    before = set(os.listdir(work))
    command = (MPIRUN + ["-np", str(np)] if np else []) + (program or [binary]) + args
    start = time.monotonic()
    process = subprocess.Popen(command, cwd=work, stdout=subprocess.PIPE,
                               stderr=subprocess.PIPE, preexec_fn=limit_memory)
    try:
        out, err = process.communicate(timeout=timeout)
        code = process.returncode
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        out, err = process.communicate()
        code = None
    seconds = time.monotonic() - start
    out, err = (d.decode("utf-8", errors="replace") for d in (out, err))
    new_files = sorted(set(os.listdir(work)) - before)
    return Outcome(code, out + err, err, seconds, new_files)


def judge(p, outcome):
    """'' when clean, else what was wrong."""
    if outcome.code is None:
        return f"hang: killed after {p.timeout:.0f} s"
    if outcome.code < 0 or outcome.code > 128:
        return f"crash: exit {outcome.code}"
    if outcome.code != p.exit:
        return f"exit {outcome.code}, expected {p.exit}"
    message = outcome.errors.strip()
    if p.exit != 0 and not message:
        return "empty message"
    if len(message.encode()) > MAX_MESSAGE_BYTES:
        return f"message of {len(message.encode())} bytes"
    if "\ufffd" in message or re.search(r"[\x00-\x08\x0b-\x1f\x7f]", message):
        return "message holds raw bytes"
    if p.expect and not re.search(p.expect, outcome.output):
        return f"message does not match /{p.expect}/"
    if p.exit == 2 and outcome.new_files:
        return "created " + ", ".join(outcome.new_files)
    return ""


# ---------------------------------------------------------------------------------------------
# case_text: what the JSON parser meets

@probe("case_text", "overflow_end_time", expect=r"analysis\.end\.time")
def _(work):
    return validate_edit(work, '"steps": 400', '"time": 1e400')


@probe("case_text", "overflow_cfl", expect=r"analysis\.time_step\.cfl")
def _(work):
    return validate_edit(work, '"cfl": 0.4', '"cfl": 1e400')


@probe("case_text", "overflow_negative", expect=r"bodies\[0\]\.velocity\[0\]")
def _(work):
    return validate_edit(work, "[2.0, 0.5]", "[-1e400, 0.5]")


@probe("case_text", "overflow_run", expect=r"analysis\.end\.time")
def _(work):
    text = text_with(FREE_FLIGHT, '"steps": 400', '"time": 1e400')
    return [write_case(work, text), "--output", "out"]


def nested(depth):
    return "[" * depth + "]" * depth


@probe("case_text", "deep_title", expect=r"title(\[0\])+: nested deeper")
def _(work):
    return validate_edit(work, '"Free-flying vibrating block"', nested(200000))


@probe("case_text", "deep_gravity", expect=r"gravity(\[0\])+: nested deeper")
def _(work):
    return validate_edit(work, '"dimension": 2,', '"dimension": 2, "gravity": ' + nested(200000) + ",")


@probe("case_text", "deep_analysis", expect=r"analysis(\[0\])+: nested deeper")
def _(work):
    text = '{"analysis": ' + nested(200000) + "}"
    return ["--validate", write_case(work, text)]


@probe("case_text", "deep_object", expect=r"(a\.)+a: nested deeper")
def _(work):
    return ["--validate", write_case(work, '{"a": ' * 100000 + "1" + "}" * 100000)]


@probe("case_text", "nul_after_json", expect=r"NUL byte")
def _(work):
    return ["--validate", write_case(work, FREE_FLIGHT.read_text() + "\0" * 16 + "garbage")]


@probe("case_text", "garbage_after_json", expect=r"not valid JSON")
def _(work):
    return ["--validate", write_case(work, FREE_FLIGHT.read_text() + "\n}{ more")]


@probe("case_text", "duplicate_key", expect=r": dimension: key given twice")
def _(work):
    return validate_edit(work, '"dimension": 2,', '"dimension": 3, "dimension": 2,')


@probe("case_text", "duplicate_nested_key", expect=r"analysis\.flip: key given twice")
def _(work):
    return validate_edit(work, '"flip": 0.95,', '"flip": 0.5, "flip": 0.95,')


@probe("case_text", "invalid_utf8", expect=r"not valid JSON.*title")
def _(work):
    data = FREE_FLIGHT.read_bytes().replace(b"Free-flying", b"Free\xff\xfe\xc3(flying", 1)
    return validate_bytes(work, data)


@probe("case_text", "random_bytes", expect=r"\(file\)")
def _(work):
    return validate_bytes(work, random.Random(9).randbytes(4096))


@probe("case_text", "random_printable", expect=r"not valid JSON")
def _(work):
    r = random.Random(3)
    return validate_bytes(work, bytes(r.randrange(0x80, 0x100) for _ in range(4096)))


@probe("case_text", "empty_file", expect=r"not valid JSON")
def _(work):
    return ["--validate", write_case(work, "")]


@probe("case_text", "lone_surrogate", expect=r"not valid JSON")
def _(work):
    return validate_edit(work, '"Free-flying vibrating block"', '"\\ud800"')


@probe("case_text", "huge_wrong_value", expect=r"^mpm_lig: .*dimension: expected an integer")
def _(work):
    return validate_edit(work, '"dimension": 2,', '"dimension": "' + "x" * 2000000 + '",')


@probe("case_text", "huge_wrong_array", expect=r"mesh\.origin: expected 2 numbers")
def _(work):
    return validate_edit(work, '"origin": [0, 0]', '"origin": [' + ",".join(["1"] * 500000) + "]")


@probe("case_text", "array_root", expect=r"\(root\)")
def _(work):
    return ["--validate", write_case(work, "[1, 2, 3]")]


# ---------------------------------------------------------------------------------------------
# case_file: what the case path names

@probe("case_file", "dev_zero", expect=r"/dev/zero.*not a regular file", timeout=20)
def _(work):
    return ["--validate", "/dev/zero"]


@probe("case_file", "directory", expect=r"is a folder")
def _(work):
    (work / "folder.json").mkdir()
    return ["--validate", str(work / "folder.json")]


@probe("case_file", "fifo", expect=r"is a pipe", timeout=10)
def _(work):
    os.mkfifo(work / "pipe.json")
    return ["--validate", str(work / "pipe.json")]


@probe("case_file", "oversized", expect=r"bytes")
def _(work):
    return ["--validate", write_case(work, " " * (20 << 20) + "{}")]


@probe("case_file", "missing", expect=r"cannot open case file")
def _(work):
    return ["--validate", str(work / "no_such_case.json")]


@probe("case_file", "symlink_loop", expect=r"cannot open case file")
def _(work):
    os.symlink("loop.json", work / "loop.json")
    return ["--validate", str(work / "loop.json")]


# ---------------------------------------------------------------------------------------------
# size: cases that cannot fit or cannot end, refused before anything is created

def tiny_dem(**rve):
    c = case(TINY_DEM)
    c["materials"][0]["rve"].update(rve)
    return c


@probe("size", "packings_1e6", expect=r"materials\[0\]\.packings", timeout=30)
def _(work):
    c = case(TINY_DEM)
    c["materials"][0]["packings"] = 1000000
    return [write_case(work, c), "--output", "out"]


@probe("size", "grains_1e9", expect=r"materials\[0\]\.rve\.grains", timeout=30)
def _(work):
    return [write_case(work, tiny_dem(grains=1e9)), "--output", "out"]


@probe("size", "grains_1e9_element", expect=r"rve\.grains", timeout=30)
def _(work):
    c = case(ELEMENT)
    c["rve"]["grains"] = 1e9
    return [write_case(work, c), "--output", "out"]


@probe("size", "cells_1e5_squared", expect=r"(mesh\.cells|bodies): the run would need", timeout=30)
def _(work):
    c = case(FREE_FLIGHT)
    c["mesh"]["cells"] = [100000, 100000]
    c["bodies"][0]["box"] = {"min": [0, 0], "max": [2.0, 1.0]}
    del c["bodies"][0]["velocity_profile"]
    return [write_case(work, c), "--output", "out"]


@probe("size", "cells_3d", expect=r"(mesh\.cells|bodies): the run would need", timeout=30)
def _(work):
    c = case(FREE_FLIGHT)
    c["dimension"] = 3
    c["mesh"] = {"origin": [0, 0, 0], "size": [1, 1, 1], "cells": [20000, 20000, 20000]}
    c["bodies"] = [{"material": 0, "box": {"min": [0, 0, 0], "max": [0.1, 0.1, 0.1]}}]
    return [write_case(work, c), "--output", "out"]


def fixed_step_end(end):
    c = case(FREE_FLIGHT)
    c["analysis"]["time_step"] = {"fixed": 1e-3}
    c["analysis"]["end"] = end
    return c


@probe("size", "end_time_1e30", expect=r"analysis\.end\.time")
def _(work):
    return [write_case(work, fixed_step_end({"time": 1e30})), "--output", "out"]


@probe("size", "end_time_1e20_fixed_step", expect=r"analysis\.end\.time")
def _(work):
    c = fixed_step_end({"time": 1e11})
    c["analysis"]["time_step"] = {"fixed": 1e-9}
    return [write_case(work, c), "--output", "out"]


@probe("size", "end_time_1e30_validate", expect=r"analysis\.end\.time")
def _(work):
    return ["--validate", write_case(work, fixed_step_end({"time": 1e30}))]


@probe("size", "end_steps_1e18", expect=r"analysis\.end\.steps")
def _(work):
    return [write_case(work, fixed_step_end({"steps": 10**18})), "--output", "out"]


@probe("size", "gravity_stage_1e15", expect=r"analysis\.gravity_stage\.steps")
def _(work):
    c = case(FREE_FLIGHT)
    c["analysis"]["gravity_stage"] = {"steps": 10**15}
    return [write_case(work, c), "--output", "out"]


@probe("size", "element_cycles_2e9", expect=r"analysis\.cycles", timeout=30)
def _(work):
    c = case(ELEMENT)
    c["analysis"] = {"type": "element_test", "test": "undrained_cyclic_simple_shear",
                     "shear_strain_amplitude": 2.0, "strain_increment": 1e-7, "cycles": 2000000000}
    return [write_case(work, c), "--output", "out"]


# ---------------------------------------------------------------------------------------------
# values: accepted by the baseline, wrong or impossible in the run

@probe("values", "footing_wider_than_mesh", expect=r"rigid_bodies\[0\]\.width")
def _(work):
    c = case(PRANDTL)
    c["rigid_bodies"][0]["width"] = [10.0]
    return [write_case(work, c), "--output", "out"]


@probe("values", "mesh_1e-300_wide", expect=r"mesh\.size")
def _(work):
    c = case(FREE_FLIGHT)
    c["mesh"]["size"] = [1e-300, 1.0]
    c["bodies"][0]["box"] = {"min": [0, 0.2], "max": [1e-300, 0.6]}
    del c["bodies"][0]["velocity_profile"]
    return [write_case(work, c), "--output", "out"]


@probe("values", "mesh_1e300_wide", expect=r"mesh\.size")
def _(work):
    c = case(FREE_FLIGHT)
    c["mesh"]["size"] = [1e300, 1.0]
    return [write_case(work, c), "--output", "out"]


@probe("values", "sine_period_denormal", expect=r"boundary_conditions\[1\]\.function\.period")
def _(work):
    c = case(TINY_DEM)
    c["boundary_conditions"][1]["function"] = {"type": "sine", "period": 1e-310}
    return [write_case(work, c), "--output", "out"]


@probe("values", "ramp_time_denormal", expect=r"rigid_bodies\[0\]\.function\.time")
def _(work):
    c = case(PRANDTL)
    c["rigid_bodies"][0]["function"] = {"type": "ramp", "time": 5e-324}
    return [write_case(work, c), "--output", "out"]


@probe("values", "youngs_modulus_above_engine", expect=r"contact\.youngs_modulus")
def _(work):
    c = case(TINY_DEM)
    c["materials"][0]["rve"]["contact"]["youngs_modulus"] = 5e9
    return ["--validate", write_case(work, c)]


@probe("values", "youngs_modulus_below_engine", expect=r"contact\.youngs_modulus")
def _(work):
    c = case(ELEMENT)
    c["rve"]["contact"]["youngs_modulus"] = 1e6
    return ["--validate", write_case(work, c)]


@probe("values", "ranks_per_rve_not_dividing", expect=r"materials\[0\]\.ranks_per_rve", np=3,
       timeout=60)
def _(work):
    c = case(TINY_DEM)
    c["materials"][0]["ranks_per_rve"] = 2
    return ["--validate", write_case(work, c)]


@probe("values", "log_file_missing_folder", expect=r"rve\.log_file")
def _(work):
    return ["--validate", write_case(work, tiny_dem(log_file="no_such_folder/rve.log"))]


@probe("values", "restart_file_name_star", expect=r"rve\.restart_file")
def _(work):
    (work / "pack*.restart").write_bytes(b"x" * 100)
    c = case(TINY_DEM)
    rve = c["materials"][0]["rve"]
    del rve["preparation"]
    rve["restart_file"] = str(work / "pack*.restart")
    c["materials"][0]["packings"] = 1
    return ["--validate", write_case(work, c)]


# ---------------------------------------------------------------------------------------------
# names: output folders the engines must take

def results_complete(steps):
    def check(work, outcome):
        folders = [f for f in outcome.new_files if (work / f).is_dir()]
        if len(folders) != 1:
            return "files outside the output folder: " + ", ".join(outcome.new_files)
        folder = work / folders[0]
        rows = (folder / "history.csv").read_text().splitlines() if (folder / "history.csv").exists() else []
        if len(rows) != steps + 2:  # header, step 0, steps
            return f"history.csv has {len(rows)} lines, expected {steps + 2}"
        if not (folder / "summary.json").exists():
            return "no summary.json"
        return ""
    return check


@probe("names", "output_space_dollar_hash", exit=0, timeout=120, check=results_complete(6))
def _(work):
    return [str(TINY_DEM), "--output", "a b $HOME #c"]


@probe("names", "output_quote_apostrophe", exit=0, timeout=120, check=results_complete(6))
def _(work):
    c = case(TINY_DEM)
    c["materials"][0]["rve"]["engine"] = "lammps"
    return [write_case(work, c), "--output", "it's $x #1"]


@probe("names", "output_star", expect=r"output folder")
def _(work):
    return [str(TINY_DEM), "--output", "runs*"]


@probe("names", "output_double_quote", expect=r"output folder")
def _(work):
    return [str(TINY_DEM), "--output", 'a"b']


@probe("names", "output_percent_element", expect=r"output folder")
def _(work):
    return [str(ELEMENT), "--output", "run%1"]


# ---------------------------------------------------------------------------------------------
# links: names inside the output folder never lead out of it (docs/running.md §3). A symbolic
# link or special file where the run keeps a file or folder is refused (exit 2, the path
# named) before anything is read, written or removed; the other run's folder B and the file
# victim.txt beside the output folder A stay as they were.

def short_run(work, **output):
    """The free-flight case cut to 20 steps (a fraction of a second) with `output`."""
    c = case(FREE_FLIGHT)
    c["analysis"]["end"] = {"steps": 20}
    c["output"].update(output)
    return write_case(work, c)


def beside(work):
    """The output folder A, another run's folder B (results and a checkpoint) and victim.txt."""
    (work / "A").mkdir()
    step = work / "B/checkpoints/step_4"
    step.mkdir(parents=True)
    (step / "MANIFEST.sha256").write_text("B's manifest\n")
    (work / "B/checkpoints/latest").write_text("step_4\n")
    (work / "B/history.csv").write_text("B's history\n")
    (work / "victim.txt").write_text("B's data\n")
    return work / "A"


def untouched(*names):
    """A check: victim.txt and B's files hold what beside() wrote; `names` were not created."""
    expected = {"victim.txt": "B's data\n", "B/checkpoints/latest": "step_4\n",
                "B/checkpoints/step_4/MANIFEST.sha256": "B's manifest\n",
                "B/history.csv": "B's history\n"}

    def check(work, outcome):
        for name in list(expected) + list(names):
            path = work / name
            text = path.read_bytes().decode(errors="replace") if path.is_file() else None
            if text != expected.get(name):
                return f"{name} changed: {text!r}"
        return ""
    return check


@probe("links", "replace_checkpoints_link", expect=r"A/checkpoints' is a symbolic link",
       check=untouched())
def _(work):
    os.symlink("../B/checkpoints", beside(work) / "checkpoints")
    return [short_run(work), "--output", "A", "--replace"]


@probe("links", "lock_link", expect=r"A/mpm_lig\.lock' is a symbolic link", check=untouched())
def _(work):
    os.symlink("../victim.txt", beside(work) / "mpm_lig.lock")
    return [short_run(work), "--output", "A"]


@probe("links", "history_dangling_link", expect=r"A/history\.csv' is a symbolic link",
       check=untouched("B/new_history.csv"))
def _(work):
    os.symlink("../B/new_history.csv", beside(work) / "history.csv")
    return [short_run(work), "--output", "A"]


@probe("links", "results_h5_dangling_link", expect=r"A/results\.h5' is a symbolic link",
       check=untouched("B/results.h5"))
def _(work):
    os.symlink("../B/results.h5", beside(work) / "results.h5")
    return [short_run(work), "--output", "A"]


@probe("links", "summary_temporary_link", expect=r"A/summary\.json\.partial' is a symbolic link",
       check=untouched())
def _(work):
    os.symlink("../victim.txt", beside(work) / "summary.json.partial")
    return [short_run(work), "--output", "A"]


@probe("links", "xdmf_temporary_pipe", expect=r"A/results\.xdmf\.tmp' is a pipe", timeout=10,
       check=untouched())
def _(work):
    os.mkfifo(beside(work) / "results.xdmf.tmp")  # writing it would wait for a reader forever
    return [short_run(work), "--output", "A"]


@probe("links", "resume_latest_link", expect=r"A/checkpoints/latest' is a symbolic link",
       check=untouched())
def _(work):
    (beside(work) / "checkpoints/step_4").mkdir(parents=True)
    os.symlink("../../B/checkpoints/latest", work / "A/checkpoints/latest")
    return [short_run(work, checkpoint_every=4), "--resume", "A"]


@probe("links", "validate_resume_history_link", expect=r"A/history\.csv' is a symbolic link",
       check=untouched())
def _(work):
    os.symlink("../B/history.csv", beside(work) / "history.csv")
    return ["--validate", short_run(work, checkpoint_every=4), "--resume", "A"]


def results_in(folder):
    def check(work, outcome):
        return "" if (work / folder / "summary.json").is_file() else f"no {folder}/summary.json"
    return check


@probe("links", "output_folder_is_a_link", exit=0, check=results_in("real"))
def _(work):
    (work / "real").mkdir()
    os.symlink("real", work / "A")  # the folder named on the command line: the user's choice
    return [short_run(work), "--output", "A"]


# ---------------------------------------------------------------------------------------------
# direct_dem: tools/direct_dem.py held to mpm_lig's outcomes (bad input exit 2 before anything is
# created, an engine that fails or hangs exit 3 at once, no name in its folder followed). Its
# checkpoint and resume scenarios run a real packing: tests/tools/check_direct_dem.py resume.
DIRECT_DEM = [sys.executable, str(REPO / "tools/direct_dem.py")]
DIRECT_DEM_TINY = REPO / "tests/tools/direct_dem_tiny.json"
# An engine that hangs gives up its start after 3 s here instead of 60.
DIRECT_DEM_QUICK_START = ["env", "MPM_LIG_TEST_ENGINE_START_SECONDS=3"] + DIRECT_DEM


def direct_dem_probe(name, expect, exit=2, program=DIRECT_DEM, **options):
    return probe("direct_dem", name, expect=expect, exit=exit, program=program, **options)


@direct_dem_probe("dd_negative_seed", r"--seed")
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--seed", "-1"]


@direct_dem_probe("dd_friction_not_a_number", r"materials\[0\]\.rve\.contact\.friction_deg")
def _(work):
    data = case(DIRECT_DEM_TINY)
    data["materials"][0]["rve"]["contact"]["friction_deg"] = "x"
    return [write_case(work, data), "--output", str(work / "out")]


@direct_dem_probe("dd_scale_too_small", r"--scale 0\.001")
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--scale", "1e-3"]


@direct_dem_probe("dd_settlement_past_base", r"--settlement 10")
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--settlement", "10"]


@direct_dem_probe("dd_no_such_engine", r"--liggghts")
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--liggghts", "/nonexistent/x"]


def fake_engine(work, body):
    path = work / "fake_liggghts"
    path.write_text(f"#!/bin/sh\n{body}\n")
    path.chmod(0o755)
    return str(path)


@direct_dem_probe("dd_engine_hangs", r"did not answer", exit=3, program=DIRECT_DEM_QUICK_START)
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--liggghts",
            fake_engine(work, "sleep 1000")]


@direct_dem_probe("dd_engine_echoes", r"did not answer", exit=3, program=DIRECT_DEM_QUICK_START)
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--liggghts",
            fake_engine(work, "cat")]


@direct_dem_probe("dd_engine_dies", r"liggghts stopped", exit=3)
def _(work):
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--liggghts",
            fake_engine(work, "echo LIGGGHTS; exit 7")]


@direct_dem_probe("dd_output_is_a_file", r"is a file")
def _(work):
    (work / "out").write_text("a file\n")
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out")]


def untouched(name):
    def check(work, outcome):
        return "" if (work / name).read_text() == "precious\n" else f"{name} was written through"
    return check


@direct_dem_probe("dd_history_link", r"symbolic link", check=untouched("elsewhere.csv"))
def _(work):
    (work / "out").mkdir()
    (work / "elsewhere.csv").write_text("precious\n")
    (work / "out" / "history.csv").symlink_to(work / "elsewhere.csv")
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out")]


@direct_dem_probe("dd_lock_link", r"symbolic link", check=untouched("elsewhere.txt"))
def _(work):
    (work / "out").mkdir()
    (work / "elsewhere.txt").write_text("precious\n")
    (work / "out" / "direct_dem.lock").symlink_to(work / "elsewhere.txt")
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--resume"]


@direct_dem_probe("dd_resume_nothing", r"no checkpoint")
def _(work):
    (work / "out").mkdir()
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--resume"]


@direct_dem_probe("dd_resume_empty_checkpoint", r"checkpoint\.json")
def _(work):
    (work / "out").mkdir()
    (work / "out" / "checkpoint.json").write_text("{}")
    return [str(DIRECT_DEM_TINY), "--output", str(work / "out"), "--resume"]


# ---------------------------------------------------------------------------------------------
# writes: a disk that fills up during the run

def can_mount():
    probe_dir = Path(tempfile.mkdtemp(prefix="mount_probe_"))
    ok = subprocess.run(["mount", "-t", "tmpfs", "-o", "size=64k", "tmpfs", str(probe_dir)],
                        capture_output=True).returncode == 0
    if ok:
        subprocess.run(["umount", str(probe_dir)])
    probe_dir.rmdir()
    return "" if ok else "cannot mount a tmpfs here (needs root)"


def full_disk(work, fields, size):
    disk = work / "disk"
    disk.mkdir()
    subprocess.run(["mount", "-t", "tmpfs", "-o", "size=" + size, "tmpfs", str(disk)], check=True)
    c = case(FREE_FLIGHT)
    c["output"] = {"every": 1, "fields": fields, "history_every": 1}  # 17 kB of history
    return [write_case(work, c), "--output", str(disk / "out")]


def unmount(work, outcome):
    subprocess.run(["umount", str(work / "disk")])
    return ""


@probe("writes", "full_disk_history", exit=1, expect=r"cannot write .*history\.csv", needs=can_mount,
       check=unmount)
def _(work):
    return full_disk(work, False, "8k")


@probe("writes", "full_disk_fields", exit=1, expect=r"cannot|HDF5", needs=can_mount, check=unmount)
def _(work):
    return full_disk(work, True, "64k")


# ---------------------------------------------------------------------------------------------
# runtime: loads that would overflow the run's state are refused before it starts (the value
# limits of docs/running.md §4), naming the JSON path

@probe("runtime", "overflow_continuum", exit=2, expect=r"gravity: must be within")
def _(work):
    c = case(FREE_FLIGHT)
    c["gravity"] = [0, -1e308]
    c["materials"][0]["density"] = 1e300
    return [write_case(work, c), "--output", "out"]


@probe("runtime", "overflow_dem", exit=2, expect=r"gravity: must be within", timeout=120)
def _(work):
    c = case(TINY_DEM)
    c["gravity"] = [0, -1e308]
    return [write_case(work, c), "--output", "out"]


# ---------------------------------------------------------------------------------------------

def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("binary")
    parser.add_argument("--category", action="append", help="only these categories")
    parser.add_argument("--only", action="append", help="only these probes")
    parser.add_argument("--extra", action="append", default=[], help="more probes (category hook)")
    parser.add_argument("--list", action="store_true")
    parser.add_argument("--json", help="write counts and outcomes here")
    parser.add_argument("--keep", help="keep the probes' folders under this folder")
    parser.add_argument("--strict", action="store_true", help="exit 1 unless every probe is clean")
    parser.add_argument("-v", "--verbose", action="store_true", help="print every outcome")
    a = parser.parse_args()

    for extra in a.extra:
        namespace = {"probe": probe, "Probe": Probe, "REPO": REPO, "case": case,
                     "write_case": write_case, "run_in": run_in, "__file__": extra}
        exec(compile(Path(extra).read_text(), extra, "exec"), namespace)
    selected = [p for p in CATALOGUE
                if (not a.category or p.category in a.category) and (not a.only or p.name in a.only)]
    if a.list:
        for p in selected:
            print(p.category, p.name)
        return 0
    if not selected:
        print("no probe selected", file=sys.stderr)
        return 2
    binary = str(Path(a.binary).resolve())
    root = Path(a.keep) if a.keep else Path(tempfile.mkdtemp(prefix="probe_robustness_"))
    root.mkdir(parents=True, exist_ok=True)
    results, categories = [], {}
    for p in selected:
        work = root / p.name
        shutil.rmtree(work, ignore_errors=True)
        work.mkdir(parents=True)
        why_not = p.needs() if p.needs else ""
        counts = categories.setdefault(p.category, {"tried": 0, "clean": 0, "skipped": 0})
        if why_not:
            counts["skipped"] += 1
            results.append({"category": p.category, "name": p.name, "skipped": why_not})
            print(f"skip   {p.category}/{p.name}: {why_not}")
            continue
        args = p.make(work)
        outcome = run_in(work, binary, args, p.timeout, p.np, p.program)
        problem = judge(p, outcome)
        extra = p.check(work, outcome) if p.check else ""
        problem = problem or extra
        counts["tried"] += 1
        counts["clean"] += not problem
        shown = outcome.errors.strip() or outcome.output.strip()
        first_line = shown.splitlines()[0][:160] if shown else ""
        results.append({"category": p.category, "name": p.name, "exit": outcome.code,
                        "seconds": round(outcome.seconds, 2), "problem": problem,
                        "message": first_line})
        if problem or a.verbose:
            print(f"{'ok    ' if not problem else 'UNCLEAN'} {p.category}/{p.name} "
                  f"({outcome.seconds:.1f} s): {problem or first_line}")
            if problem and a.verbose:
                print("    " + outcome.output.strip()[-600:].replace("\n", "\n    "))
    if not a.keep:
        shutil.rmtree(root, ignore_errors=True)
    print(f"\n{'category':<12} {'tried':>5} {'clean':>5} {'skipped':>7}")
    total = {"tried": 0, "clean": 0, "skipped": 0}
    for name, c in categories.items():
        print(f"{name:<12} {c['tried']:>5} {c['clean']:>5} {c['skipped']:>7}")
        for k in total:
            total[k] += c[k]
    print(f"{'all':<12} {total['tried']:>5} {total['clean']:>5} {total['skipped']:>7}")
    if a.json:
        Path(a.json).write_text(json.dumps({"binary": binary, "categories": categories,
                                            "total": total, "probes": results}, indent=1))
    if a.strict and total["clean"] < total["tried"]:
        return 1
    return SKIPPED if total["tried"] == 0 and total["skipped"] > 0 else 0


if __name__ == "__main__":
    sys.exit(main())
