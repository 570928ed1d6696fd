#!/usr/bin/python3
"""Whether two output directories of one case hold the same results, bit for bit.

usage: compare_outputs.py REFERENCE_DIR OTHER_DIR

history.csv byte for byte; results.h5 (when present) every dataset and attribute; summary.json
every value except timings (keys with 'seconds', 'time_split', 'per_s' or 'rate' in their path).
Prints what differs and exits 1, or exits 0."""
import json
import os
import sys

from mpm_lig_post.fields import every_item

TIMING_MARKS = ("seconds", "time_split", "per_s", "rate", "balance")


def flatten(node, prefix=""):
    if isinstance(node, dict):
        for key, value in node.items():
            yield from flatten(value, f"{prefix}.{key}" if prefix else key)
    elif isinstance(node, list):
        for k, value in enumerate(node):
            yield from flatten(value, f"{prefix}[{k}]")
    else:
        yield prefix, node


def compare(reference, other):
    problems = []
    if open(f"{reference}/history.csv", "rb").read() != open(f"{other}/history.csv", "rb").read():
        problems.append("history.csv differs")
    ref_h5, other_h5 = f"{reference}/results.h5", f"{other}/results.h5"
    if os.path.exists(ref_h5) != os.path.exists(other_h5):
        problems.append("results.h5 present in one run only")
    elif os.path.exists(ref_h5):
        a, b = every_item(ref_h5), every_item(other_h5)
        if sorted(a) != sorted(b):
            problems.append("results.h5 holds other datasets")
        problems += [f"results.h5:{n} differs" for n in a
                     if n in b and (a[n].shape != b[n].shape or a[n].tobytes() != b[n].tobytes())]
    a = dict(flatten(json.load(open(f"{reference}/summary.json"))))
    b = dict(flatten(json.load(open(f"{other}/summary.json"))))
    for key in sorted(set(a) | set(b)):
        if any(mark in key for mark in TIMING_MARKS):
            continue
        if a.get(key) != b.get(key):
            problems.append(f"summary.json {key}: {a.get(key)} vs {b.get(key)}")
    return problems


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    problems = compare(sys.argv[1], sys.argv[2])
    for p in problems:
        print(p)
    sys.exit(1 if problems else 0)


if __name__ == "__main__":
    main()
