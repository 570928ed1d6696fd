"""Whether output directories of one case hold the same results, bit for bit.

usage: compare_outputs.py REFERENCE_DIR OTHER_DIR... [--allow-added] [--results-only]
                          [--ranks N...]

Each OTHER_DIR against REFERENCE_DIR: history.csv byte for byte; results.h5 (when present)
every dataset and attribute; summary.json every value except timings (keys with 'seconds',
'time_split', 'per_s', 'rate', 'balance' or 'waiting' in their path) and the build's identity. Prints what differs
and exits 1, or prints "bit-identical: ..." and exits 0. With --allow-added, outputs the
reference lacks (new history columns, datasets, summary keys) are listed but pass: every value
the two share must still be bit-identical (a new build that writes more against an older one).
With --results-only, summary.json is not compared: runs of one case that differ by design in
how they ran (rank counts, stopped and resumed, with or without checkpoints) must agree in
history.csv and results.h5, and the reference must hold some of both (at least two history
rows and one dataset), so that a comparison of nothing cannot pass. --ranks N... (one per
directory, the reference first) checks the rank count each summary.json records.
A missing folder or file, or one that cannot be read (damaged, truncated), exits 2 naming it."""
from mpm_lig_post.requirements import require

require("numpy", "h5py")

import csv  # noqa: E402
import io  # noqa: E402
import os  # noqa: E402

import numpy as np  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import every_item  # noqa: E402
from mpm_lig_post.tables import read_json, read_text  # noqa: E402

# Keys that say how and where a run was computed, not what: timings and the build's identity.
TIMING_MARKS = ("seconds", "time_split", "per_s", "rate", "balance", "build", "waiting")


def flatten(node, prefix=""):
    if isinstance(node, dict):
        for key, value in node.items():
            yield from flatten(value, f"{prefix}.{key}" if prefix else key)
    elif isinstance(node, list):
        for k, value in enumerate(node):
            yield from flatten(value, f"{prefix}[{k}]")
    else:
        yield prefix, node


def csv_rows(path, text):
    rows = list(csv.reader(io.StringIO(text, newline="")))
    if not rows:
        raise InputError(f"{path}: empty file (no header row)")
    return rows


def compare_history(reference, other, allow_added, problems, added):
    ref_path, other_path = os.path.join(reference, "history.csv"), os.path.join(other,
                                                                               "history.csv")
    ref_text, other_text = read_text(ref_path), read_text(other_path)
    if ref_text == other_text:
        return
    if not allow_added:
        problems.append("history.csv differs")
        return
    ref_rows, other_rows = csv_rows(ref_path, ref_text), csv_rows(other_path, other_text)
    ref_cols, other_cols = ref_rows[0], other_rows[0]
    missing = [c for c in ref_cols if c not in other_cols]
    if missing or len(ref_rows) != len(other_rows):
        problems.append(f"history.csv: columns missing {missing} or {len(ref_rows)} vs "
                        f"{len(other_rows)} rows")
        return
    added += [f"history.csv column {c}" for c in other_cols if c not in ref_cols]
    where = [other_cols.index(c) for c in ref_cols]
    for k, (r, o) in enumerate(zip(ref_rows[1:], other_rows[1:])):
        if [o[i] for i in where] != r:
            problems.append(f"history.csv row {k + 1} differs")
            return


def compare_fields(ref_h5, other_h5, allow_added, problems, added):
    """results.h5 of two runs: every dataset and attribute bit for bit; the number compared."""
    if os.path.exists(ref_h5) != os.path.exists(other_h5):
        problems.append("results.h5 present in one run only")
        return 0
    if not os.path.exists(ref_h5):
        return 0
    a, b = every_item(ref_h5), every_item(other_h5)
    if any(n not in b for n in a) or (not allow_added and sorted(a) != sorted(b)):
        problems.append("results.h5 holds other datasets")
    added += [f"results.h5:{n}" for n in b if n not in a]
    for n in a:
        if n in b and (a[n].shape != b[n].shape or a[n].tobytes() != b[n].tobytes()):
            problems.append(f"results.h5:{n} differs (max |diff| {max_difference(a[n], b[n])})")
    return len(a)


def max_difference(a, b):
    """The largest |a - b| of two numeric arrays of one shape, or what makes them incomparable."""
    if a.shape != b.shape:
        return f"shapes {a.shape} vs {b.shape}"
    if a.dtype.kind not in "fiu" or b.dtype.kind not in "fiu" or not a.size:
        return "not numeric"
    return f"{np.max(np.abs(a.astype(float) - b.astype(float))):.3g}"


def compare_summaries(reference, other, allow_added, problems, added):
    a = dict(flatten(read_json(os.path.join(reference, "summary.json"))))
    b = dict(flatten(read_json(os.path.join(other, "summary.json"))))
    for key in sorted(set(a) | set(b)):
        if any(mark in key for mark in TIMING_MARKS):
            continue
        if allow_added and key not in a:
            added.append(f"summary.json {key}")
        elif a.get(key) != b.get(key):
            problems.append(f"summary.json {key}: {a.get(key)} vs {b.get(key)}")


def compare(reference, other, allow_added=False, results_only=False):
    """What differs between two runs' outputs and what the other adds, and the number of
    datasets compared."""
    for d in (reference, other):
        if not os.path.isdir(d):
            raise InputError(f"{d}: no such output directory")
    problems, added = [], []
    compare_history(reference, other, allow_added, problems, added)
    datasets = compare_fields(f"{reference}/results.h5", f"{other}/results.h5", allow_added,
                              problems, added)
    if not results_only:
        compare_summaries(reference, other, allow_added, problems, added)
    return problems, added, datasets


def check_ranks(dirs, ranks):
    """Each run's summary.json records the rank count given for it."""
    if len(ranks) != len(dirs):
        raise InputError(f"--ranks: {len(ranks)} counts for {len(dirs)} output directories")
    problems = []
    for d, n in zip(dirs, ranks):
        recorded = read_json(os.path.join(d, "summary.json")).get("ranks")
        if recorded != n:
            problems.append(f"{d}/summary.json: ranks {recorded}, expected {n}")
    return problems


def history_lines(run):
    return len(read_text(os.path.join(run, "history.csv")).splitlines())


def main():
    parser = cli.ArgumentParser(usage=__doc__)
    parser.add_argument("reference")
    parser.add_argument("others", nargs="+", metavar="other")
    parser.add_argument("--allow-added", action="store_true")
    parser.add_argument("--results-only", action="store_true")
    parser.add_argument("--ranks", nargs="+", type=cli.positive_int)
    args = parser.parse_args()
    problems, datasets = [], 0
    for other in args.others:
        found, added, datasets = compare(args.reference, other, args.allow_added,
                                         args.results_only)
        prefix = f"{other}: " if len(args.others) > 1 else ""
        if added:
            print(f"{prefix}added (not in the reference): {len(added)}: " +
                  ", ".join(added[:6]) + (" ..." if len(added) > 6 else ""))
        problems += [prefix + p for p in found]
    lines = history_lines(args.reference)
    if args.results_only and (lines < 3 or not datasets):
        raise InputError(f"{args.reference}: too little output to compare ({lines} history "
                         f"lines, {datasets} datasets in results.h5)")
    if args.ranks:
        problems += check_ranks([args.reference, *args.others], args.ranks)
    for p in problems:
        print(p)
    if problems:
        return 1
    print(f"bit-identical: {1 + len(args.others)} runs, {datasets} datasets, {lines} history "
          "lines")
    return 0


def entry():
    """The command: tools/compare_outputs.py in a checkout, mpm-lig-compare-outputs installed."""
    cli.run(main)


if __name__ == "__main__":
    entry()
