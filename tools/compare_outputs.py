#!/usr/bin/python3
"""Whether two output directories of one case hold the same results, bit for bit.

usage: compare_outputs.py REFERENCE_DIR OTHER_DIR [--allow-added]

history.csv byte for byte; results.h5 (when present) every dataset and attribute; summary.json
every value except timings (keys with 'seconds', 'time_split', 'per_s' or 'rate' in their path).
Prints what differs and exits 1, or exits 0. With --allow-added, outputs the reference lacks
(new history columns, datasets, summary keys) are listed but pass: every value the two share
must still be bit-identical (a new build that writes more against an older one).
A missing folder or file, or one that cannot be read (damaged, truncated), exits 2 naming it."""
from mpm_lig_post.requirements import require

require("numpy", "h5py")

import csv  # noqa: E402
import io  # noqa: E402
import os  # noqa: E402

from mpm_lig_post import cli  # noqa: E402
from mpm_lig_post.errors import InputError  # noqa: E402
from mpm_lig_post.fields import every_item  # noqa: E402
from mpm_lig_post.tables import read_json, read_text  # noqa: E402

# Keys that say how and where a run was computed, not what: timings and the build's identity.
TIMING_MARKS = ("seconds", "time_split", "per_s", "rate", "balance", "build")


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


def compare(reference, other, allow_added=False):
    for d in (reference, other):
        if not os.path.isdir(d):
            raise InputError(f"{d}: no such output directory")
    problems, added = [], []
    compare_history(reference, other, allow_added, problems, added)
    ref_h5, other_h5 = f"{reference}/results.h5", f"{other}/results.h5"
    if os.path.exists(ref_h5) != os.path.exists(other_h5):
        problems.append("results.h5 present in one run only")
    elif os.path.exists(ref_h5):
        a, b = every_item(ref_h5), every_item(other_h5)
        if any(n not in b for n in a) or (not allow_added and sorted(a) != sorted(b)):
            problems.append("results.h5 holds other datasets")
        added += [f"results.h5:{n}" for n in b if n not in a]
        problems += [f"results.h5:{n} differs" for n in a
                     if n in b and (a[n].shape != b[n].shape or a[n].tobytes() != b[n].tobytes())]
    a = dict(flatten(read_json(os.path.join(reference, "summary.json"))))
    b = dict(flatten(read_json(os.path.join(other, "summary.json"))))
    for key in sorted(set(a) | set(b)):
        if any(mark in key for mark in TIMING_MARKS):
            continue
        if allow_added and key not in a:
            added.append(f"summary.json {key}")
        elif a.get(key) != b.get(key):
            problems.append(f"summary.json {key}: {a.get(key)} vs {b.get(key)}")
    return problems, added


def main():
    parser = cli.ArgumentParser(usage=__doc__)
    parser.add_argument("reference")
    parser.add_argument("other")
    parser.add_argument("--allow-added", action="store_true")
    args = parser.parse_args()
    problems, added = compare(args.reference, args.other, args.allow_added)
    if added:
        print(f"added (not in the reference): {len(added)}: " + ", ".join(added[:6]) +
              (" ..." if len(added) > 6 else ""))
    for p in problems:
        print(p)
    return 1 if problems else 0


if __name__ == "__main__":
    cli.run(main)
