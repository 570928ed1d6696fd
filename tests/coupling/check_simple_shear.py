#!/usr/bin/python3
"""Checks the simple-shear history columns of a run of tests/coupling/simple_shear_short.json
against the case's prescribed motion and the point fields of results.h5 (written every step).

usage: check_simple_shear.py CASE OUTPUT_DIR"""
import csv
import json
import math
import sys

import h5py
import numpy as np


def prescribed(case):
    """(period T, amplitude gamma_a, time step): the top row's velocity over its height."""
    bc = case["boundary_conditions"][case["output"]["simple_shear"]["boundary_condition"]]
    height = bc["nodes"]["box"]["min"][1]
    period = bc["function"]["period"]
    return period, bc["velocity"] / height * period / 4, case["analysis"]["time_step"]["fixed"]


def triangle(t, period):
    """Displacement shape of a square-wave velocity: 0 -> 1 at T/4 -> -1 at 3T/4 -> 0."""
    phase = t / period - math.floor(t / period)
    return 4 * phase if phase < 0.25 else 2 - 4 * phase if phase < 0.75 else 4 * phase - 4


def main():
    case = json.load(open(sys.argv[1]))
    out = sys.argv[2]
    period, amplitude, dt = prescribed(case)
    rows = [{k: float(v) for k, v in r.items()} for r in csv.DictReader(open(out + "/history.csv"))]
    failures = []

    def check(ok, what):
        if not ok:
            failures.append(what)

    check(len(rows) == case["analysis"]["end"]["steps"] + 1, "history rows %d" % len(rows))
    rate = 4 * amplitude / period  # |d gamma / dt|
    with h5py.File(out + "/results.h5") as f:
        for r in rows:
            step = int(r["step"])
            t = r["time"]
            check(r["cycle"] == max(1, math.ceil(t / period - 1e-6)), "cycle at step %d" % step)
            # The prescribed motion, within one step of the velocity's time sampling.
            check(abs(r["shear_strain"] - amplitude * triangle(t, period)) <= rate * dt * 1.0001,
                  "shear_strain %.6g vs prescribed %.6g at step %d"
                  % (r["shear_strain"], amplitude * triangle(t, period), step))
            g = f["step_%06d" % step]
            u, x = g["displacement"][:], g["positions"][:]
            y0 = x[:, 1] - u[:, 1]
            # Homogeneous simple shear: u_x = gamma Y at every point, u_y = 0.
            check(np.allclose(u[:, 0], r["shear_strain"] * y0, rtol=0, atol=1e-13)
                  and np.max(np.abs(u[:, 1])) < 1e-15,
                  "point displacements differ from gamma Y at step %d" % step)
            s, v = g["stress"][:], g["volume"][:]
            mean = (v[:, None] * s).sum(axis=0) / v.sum()  # Voigt xx yy zz xy xz yz
            scale = abs(mean[0]) + abs(mean[1])
            check(abs(r["shear_stress"] - mean[3]) <= 1e-12 * scale, "shear_stress at step %d" % step)
            check(abs(r["mean_stress"] + 0.5 * (mean[0] + mean[1])) <= 1e-12 * scale,
                  "mean_stress at step %d" % step)
            check(r["mean_stress"] > 0, "mean_stress not compressive at step %d" % step)
    check(rows[-1]["cycle"] == 2 and max(r["shear_strain"] for r in rows) > 0.99 * amplitude,
          "the run should reach +gamma_a and enter cycle 2")
    if failures:
        print("FAILED:\n  " + "\n  ".join(failures))
        sys.exit(1)
    print("simple shear columns ok over %d rows: gamma_max %.4g, p' %.4g -> %.4g Pa"
          % (len(rows), max(r["shear_strain"] for r in rows), rows[0]["mean_stress"],
             rows[-1]["mean_stress"]))


if __name__ == "__main__":
    main()
