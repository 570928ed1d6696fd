#!/usr/bin/env python3
"""Fuzz test: mutates the shipped cases at random for a bounded time and runs mpm_lig on them.

Every mutated case goes through `mpm_lig --validate`, which must answer within its time limit
with exit 0 ("valid") or exit 2 and a non-empty, printable message of bounded size. A mutated
MPM case that validates and has only continuum materials and few points is then run for 3
steps: it must end with 0, or with 1 or 2 and a message (a valid case may still fail to run,
e.g. a point leaving the mesh, but never crash, hang, or blame an engine). DEM cases that
validate are not run: preparing their packings takes minutes.

    fuzz_cases.py BINARY WORK [--seconds 35] [--seed 1]

Failures are kept in WORK/failures/ with the seed and iteration; exit 1 if there is any.
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
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
VALIDATE_SECONDS = 20
RUN_SECONDS = 40
RUN_MAX_POINTS = 20000
MAX_MESSAGE_BYTES = 20000
MEMORY_LIMIT = 4 << 30  # per process; mpm_lig refuses cases that would not fit (ulimit -v)

ODD_VALUES = [0, -1, 1, 2, 0.5, -0.5, 1e308, -1e308, 5e-324, 1e-310, 1e9, 1e-9, 2**31, 2**63,
              -2**63, 10**30, 7.5, "", "x", "liggghts", "lammps", "x-", True, False, None, [],
              {}, [0, 0], [1, 2, 3], [[1]], {"type": "sine"}, {"min": [0, 0], "max": [1, 1]}]
TEXT_NUMBERS = ["1e400", "-1e400", "1e-400", "99999999999999999999999", "-0", "0e0"]


def shipped_cases():
    files = sorted((REPO / "cases").rglob("*.json")) + [REPO / "tests/coupling/tiny_2x2.json"]
    return [(f, f.read_text()) for f in files]


def paths(node, prefix=()):
    """Every (path, value) below `node`, containers included."""
    yield prefix, node
    if isinstance(node, dict):
        for k, v in node.items():
            yield from paths(v, prefix + (k,))
    elif isinstance(node, list):
        for i, v in enumerate(node):
            yield from paths(v, prefix + (i,))


def parent_of(root, path):
    node = root
    for key in path[:-1]:
        node = node[key]
    return node


def mutate_json(data, r):
    """One structural change of a parsed case (in place); returns a label."""
    all_paths = [p for p, _ in paths(data) if p]
    path = r.choice(all_paths)
    parent, key = parent_of(data, path), path[-1]
    kind = r.randrange(7)
    if kind <= 2:
        parent[key] = copy.deepcopy(r.choice(ODD_VALUES))
        return f"set {path} = {parent[key]!r}"[:120]
    if kind == 3:
        del parent[key]
        return f"delete {path}"
    if kind == 4 and isinstance(parent, dict):
        parent[key + r.choice(["_", "s", "x"])] = parent.pop(key)
        return f"rename {path}"
    if kind == 5:
        other = r.choice(all_paths)
        parent[key] = copy.deepcopy(parent_of(data, other)[other[-1]])
        return f"copy {other} to {path}"
    value = parent[key]
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        parent[key] = value * r.choice([-1, 0, 10, 1e6, 1e-6, 1e300, 1e-300])
        return f"scale {path}"
    if isinstance(value, list) and value:
        value.append(copy.deepcopy(r.choice(value)) if r.random() < 0.5 else value.pop(0))
        return f"resize {path}"
    parent[key] = [value]
    return f"wrap {path}"


def mutate_text(text, r):
    """One change of the case's bytes; returns (bytes, label)."""
    data = text.encode()
    at = r.randrange(len(data))
    kind = r.randrange(6)
    if kind == 0:
        return data[:at], f"truncate at {at}"
    if kind == 1:
        return data[:at] + bytes(r.randrange(256) for _ in range(r.randrange(1, 8))) + data[at:], \
            f"insert bytes at {at}"
    if kind == 2:
        flipped = bytes([data[at] ^ (1 << r.randrange(8))])
        return data[:at] + flipped + data[at + 1:], f"flip a bit at {at}"
    if kind == 3:
        numbers = list(re.finditer(rb"-?\d+(\.\d+)?([eE][-+]?\d+)?", data))
        if numbers:
            m = r.choice(numbers)
            new = r.choice(TEXT_NUMBERS).encode()
            return data[:m.start()] + new + data[m.end():], f"number -> {new.decode()}"
    if kind == 4:
        keys = list(re.finditer(rb'"[a-z_]+": [^,{}\[\]]+', data))
        if keys:
            m = r.choice(keys)
            return data[:m.end()] + b", " + m.group(0) + data[m.end():], "duplicate a key"
    depth = r.choice([100, 1000, 100000])
    return data[:at] + b"[" * depth + b"]" * depth + data[at:], f"nest {depth} deep at {at}"


def limit():
    resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    os.setsid()


def run(binary, args, cwd, seconds):
    p = subprocess.Popen([binary] + args, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                         preexec_fn=limit)
    try:
        out, err = p.communicate(timeout=seconds)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        p.communicate()
        return None, "", ""
    return p.returncode, out.decode(errors="replace"), err.decode(errors="replace")


def problem_of(code, out, err, allowed):
    if code is None:
        return "hang (time limit)"
    if code not in allowed:
        return f"exit {code}"
    message = err.strip()
    if code != 0 and not message:
        return "empty message"
    if len(message.encode()) > MAX_MESSAGE_BYTES:
        return f"message of {len(message.encode())} bytes"
    if "\ufffd" in message or re.search(r"[\x00-\x08\x0b-\x1f\x7f]", message):
        return "message holds raw bytes"
    return ""


def runnable(case):
    """A continuum MPM case small enough to run a few steps of."""
    try:
        if case["analysis"]["type"] != "mpm":
            return False
        if any(m.get("type") == "dem_rve" for m in case["materials"]):
            return False
        d, mesh = case["dimension"], case["mesh"]
        points = 0
        for b in case["bodies"]:
            n = 1
            for k in range(d):
                cell = mesh["size"][k] / mesh["cells"][k]
                n *= max(1, round((b["box"]["max"][k] - b["box"]["min"][k]) / cell
                                  * b.get("points_per_cell", 2)))
            points += n
        return points <= RUN_MAX_POINTS
    except Exception:  # a mutated case may have any shape: then it is not run
        return False


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("binary")
    parser.add_argument("work")
    parser.add_argument("--seconds", type=float, default=35.0)
    parser.add_argument("--seed", type=int, default=int(os.environ.get("FUZZ_SEED", "1")))
    a = parser.parse_args()
    binary = str(Path(a.binary).resolve())
    work = Path(a.work)
    shutil.rmtree(work, ignore_errors=True)
    (work / "failures").mkdir(parents=True)
    r = random.Random(a.seed)
    cases = shipped_cases()
    counts = {"tried": 0, "valid": 0, "refused": 0, "runs": 0, "failures": 0}
    deadline = time.monotonic() + a.seconds
    iteration = 0
    while time.monotonic() < deadline:
        iteration += 1
        source, text = r.choice(cases)
        labels = []
        if r.random() < 0.7:
            data = json.loads(text)
            for _ in range(r.randint(1, 3)):
                labels.append(mutate_json(data, r))
            blob = json.dumps(data, indent=1).encode()
        else:
            blob, label = mutate_text(text, r)
            labels.append(label)
        folder = work / "current"
        shutil.rmtree(folder, ignore_errors=True)
        folder.mkdir()
        case_file = work / "case.json"  # the shipped cases name no files of their own
        case_file.write_bytes(blob)
        code, out, err = run(binary, ["--validate", str(case_file)], folder, VALIDATE_SECONDS)
        problem = problem_of(code, out, err, {0, 2})
        counts["tried"] += 1
        counts["valid" if code == 0 else "refused"] += 1
        stage = "validate"
        if not problem and code == 0:
            case = json.loads(blob)
            if runnable(case):
                case["analysis"]["end"] = {"steps": 3}
                case["analysis"].pop("gravity_stage", None)
                case_file.write_text(json.dumps(case))
                code, out, err = run(binary, [str(case_file), "--output", "out"], folder,
                                     RUN_SECONDS)
                problem = problem_of(code, out, err, {0, 1, 2})
                counts["runs"] += 1
                stage = "run"
        if problem:
            counts["failures"] += 1
            kept = work / "failures" / f"seed{a.seed}_it{iteration}_{source.stem}.json"
            kept.write_bytes(blob)
            print(f"FAIL {stage} {kept.name}: {problem}; mutations: {'; '.join(labels)}")
            print("    " + (err.strip() or out.strip())[-400:].replace("\n", "\n    "))
    shutil.rmtree(work / "current", ignore_errors=True)
    print(f"seed {a.seed}, {a.seconds:.0f} s: " + ", ".join(f"{k} {v}" for k, v in counts.items()))
    return 1 if counts["failures"] or counts["tried"] == 0 else 0


if __name__ == "__main__":
    sys.exit(main())
