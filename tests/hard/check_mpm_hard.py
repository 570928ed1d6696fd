#!/usr/bin/python3
"""Checks of the MPM hard cases from their outputs (history.csv, results.h5, summary.json).
Prints one table row: case | criterion | measured margin; exits 1 on a failed criterion.

usage: check_mpm_hard.py extension OUTPUT_DIR
       check_mpm_hard.py large_shear OUTPUT_DIR
       check_mpm_hard.py rotation OUTPUT_DIR"""
import csv
import math
import sys

import h5py
import numpy as np


def history(out):
    return [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(out + "/history.csv"))]


def last_step(out):
    with h5py.File(out + "/results.h5") as f:
        name = sorted(k for k in f.keys() if k.startswith("step_"))[-1]
        g = f[name]
        return {k: g[k][()] for k in g.keys()}


def finite_everywhere(out):
    with h5py.File(out + "/results.h5") as f:
        for name in f:
            if name.startswith("step_"):
                for k, d in f[name].items():
                    if np.issubdtype(d.dtype, np.floating) and not np.all(np.isfinite(d[()])):
                        return False
    return True


def extension(out, failures):
    """Pulled to det F = 1.5: stress -> 0 (below 1 % of the initial p') without NaN."""
    s = last_step(out)
    with h5py.File(out + "/results.h5") as f:
        first = f[sorted(k for k in f.keys() if k.startswith("step_"))[0]]
        p0 = -np.mean(first["stress"][:, :2].sum(axis=1) / 2)
        det = s["volume"] / first["volume"][()]
    stress = np.abs(s["stress"]).max()
    if not finite_everywhere(out):
        failures.append("non-finite output")
    if det.min() < 1.5 - 1e-3:
        failures.append("det F reached only %.4f" % det.min())
    if stress > 1e-2 * p0:
        failures.append("stress %.3g Pa left at det F = 1.5 (p0' %.3g Pa)" % (stress, p0))
    return ("extension to det F = 1.5 | |sigma| < 1e-2 p0', no NaN, no lost grains | "
            "det F %.4f, max |sigma| %.2e p0'" % (det.min(), stress / p0))


def large_shear(out, failures):
    """Monotonic simple shear to gamma = 5 at constant volume. A jump at a cell-basis reduction
    would be a one-step spike: the step's stress change (max of |d tau|, |d p'|) against the
    median change of the 50 steps around it. The largest spike after gamma = 0.45 (where the
    reductions begin) must stay within twice the largest one before (the RVE's own
    fluctuation, 0.05 < gamma < 0.45)."""
    rows = history(out)
    gamma = np.array([r["shear_strain"] for r in rows])
    tau = np.array([r["shear_stress"] for r in rows])
    p = np.array([r["mean_stress"] for r in rows])
    if not (np.all(np.isfinite(tau)) and np.all(np.isfinite(p))):
        failures.append("non-finite stress")
    jump = np.maximum(np.abs(np.diff(tau)), np.abs(np.diff(p)))
    spike = np.array([jump[i] / np.median(jump[max(0, i - 25):i + 26]) for i in range(len(jump))])
    g = gamma[1:]
    early = spike[(g > 0.05) & (g < 0.45)].max()
    late = spike[g >= 0.45].max()
    if gamma[-1] < 5.0 - 1e-6:
        failures.append("gamma reached only %.3f" % gamma[-1])
    if late > 2.0 * early:
        failures.append("spike %.2f after gamma 0.45 > 2 x %.2f before" % (late, early))
    return ("simple shear to gamma = 500 %% | largest one-step spike after the first reduction "
            "<= 2 x before | gamma %.2f, spikes %.2f after vs %.2f before (ratio %.2f of 2)"
            % (gamma[-1], late, early, late / early))


def main():
    kind, out = sys.argv[1], sys.argv[2]
    failures = []
    row = {"extension": extension, "large_shear": large_shear}[kind](out, failures)
    print(row)
    for f in failures:
        print("FAIL:", f)
    sys.exit(1 if failures else 0)


main()
