#!/usr/bin/python3
"""Checks that several runs of one case are bit-identical: history.csv byte for byte, every
dataset and attribute of results.h5 bit for bit (the rank count must not change results).

usage: compare_runs.py REFERENCE_DIR OTHER_DIR... [--ranks N...]
Each summary.json must say the run had the given number of ranks (--ranks, one per dir)."""
import argparse
import json
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "tools"))
from mpm_lig_post.fields import every_item as datasets  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("dirs", nargs="+")
    parser.add_argument("--ranks", nargs="*", type=int)
    args = parser.parse_args()
    reference = args.dirs[0]
    ref_history = open(reference + "/history.csv", "rb").read()
    ref_fields = datasets(reference + "/results.h5")
    if len(ref_history.splitlines()) < 3 or not ref_fields:
        sys.exit("reference run has too little output")
    failures = []
    for d in args.dirs[1:]:
        if open(d + "/history.csv", "rb").read() != ref_history:
            failures.append(d + "/history.csv differs from " + reference)
        fields = datasets(d + "/results.h5")
        if sorted(fields) != sorted(ref_fields):
            failures.append(d + "/results.h5 has other datasets than " + reference)
            continue
        for name, value in ref_fields.items():
            other = fields[name]
            if value.shape != other.shape or value.tobytes() != other.tobytes():
                diff = np.max(np.abs(value.astype(float) - other.astype(float))) \
                    if value.shape == other.shape and value.dtype.kind in "fi" else "shape"
                failures.append("%s/results.h5:%s differs (max |diff| %s)" % (d, name, diff))
    for d, ranks in zip(args.dirs, args.ranks or []):
        summary = json.load(open(d + "/summary.json"))
        if summary["ranks"] != ranks:
            failures.append("%s/summary.json: ranks %s, expected %d" % (d, summary["ranks"], ranks))
    if failures:
        print("\n".join(failures))
        sys.exit(1)
    print("bit-identical: %d runs, %d datasets, %d history lines" %
          (len(args.dirs), len(ref_fields), len(ref_history.splitlines())))


if __name__ == "__main__":
    main()
