#!/usr/bin/python3
"""Whether two output directories of one case hold the same results, bit for bit.

usage: compare_outputs.py REFERENCE_DIR OTHER_DIR [--allow-added]

history.csv byte for byte; results.h5 (when present) every dataset and attribute; summary.json
every value except timings (keys with 'seconds', 'time_split', 'per_s' or 'rate' in their path).
Prints what differs and exits 1, or exits 0. With --allow-added, outputs the reference lacks
(new history columns, datasets, summary keys) are listed but pass: every value the two share
must still be bit-identical (a new build that writes more against an older one)."""
import argparse
import csv
import json
import os
import sys

from mpm_lig_post.fields import every_item

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


def compare_history(reference, other, allow_added, problems, added):
    ref_text = open(f"{reference}/history.csv", "rb").read()
    other_text = open(f"{other}/history.csv", "rb").read()
    if ref_text == other_text:
        return
    if not allow_added:
        problems.append("history.csv differs")
        return
    ref_rows = list(csv.reader(ref_text.decode().splitlines()))
    other_rows = list(csv.reader(other_text.decode().splitlines()))
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
    a = dict(flatten(json.load(open(f"{reference}/summary.json"))))
    b = dict(flatten(json.load(open(f"{other}/summary.json"))))
    for key in sorted(set(a) | set(b)):
        if any(mark in key for mark in TIMING_MARKS):
            continue
        if allow_added and key not in a:
            added.append(f"summary.json {key}")
        elif a.get(key) != b.get(key):
            problems.append(f"summary.json {key}: {a.get(key)} vs {b.get(key)}")
    return problems, added


def main():
    parser = argparse.ArgumentParser(usage=__doc__)
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
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
