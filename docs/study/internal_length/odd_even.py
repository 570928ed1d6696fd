#!/usr/bin/python3
"""How much of a footing run's deviatoric strain alternates point by point: along each axis of
the points' reference grid, the mean |second difference| of eps_q (a point against the mean of
its two neighbours) over the mean |first difference| (half the difference of the two). A field
smooth over a few cells gives a ratio well below 1; a field alternating from one point to the
next (period 2 h) gives a large one, with a first difference near zero.

usage: odd_even.py MPM_RUN[:LABEL] ... [--at 0.1 0.2 0.3] [--region X0 X1 Y0 Y1]
       [--quantity eq|exy] [--speed 0.5] [--width 0.2] [--json OUT.json] [--growth]

--growth prints instead, for every output of each run, the mean |second difference| along x
and its growth over the output before, per unit of time, and the alternating component along
x: over each row of points in the region |mean of (-1)^i (v_i - (v_{i-1} + v_{i+1}) / 2) / 2|,
averaged over the rows (A for a pattern A (-1)^i from column to column, nothing for a linear
trend; for values independent from point to point about their spread over the square root
of the row's points).

--quantity exy measures the logarithmic shear strain (results.h5 `strain`, Voigt xy) instead
of eps_q.

The points are those whose reference position (position minus displacement) lies in the
region [m] (default: beside and under the footing's edge, 0 <= x <= 0.35, 0.25 <= y <= 0.6);
s/B is speed x time / width, the output nearest each --at.
"""
import argparse
import json

import h5py
import numpy as np


def nearest_output(f, time):
    steps = [k for k in f if k.startswith("step_")]
    return f[min(steps, key=lambda k: abs(f[k].attrs["time"] - time))]


def differences(group, region, quantity, axis):
    """(column i, row j, second difference, first difference) for every point of the region
    with a neighbour on both sides along `axis` (0: x, 1: y) in the points' reference grid:
    v_p - (v_a + v_b) / 2 and (v_b - v_a) / 2, a and b the neighbours before and after."""
    reference = group["positions"][:, :2] - group["displacement"][:, :2]
    if quantity == "exy":
        values = group["strain"][:, 3]
    else:
        values = group["deviatoric_strain"][()].ravel()
    h = np.min(np.diff(np.unique(np.round(reference[:, 0], 9))))
    index = {(int(round(x / h - 0.5)), int(round(y / h - 0.5))): p
             for p, (x, y) in enumerate(reference)}
    di, dj = (1, 0) if axis == 0 else (0, 1)
    x0, x1, y0, y1 = region
    out = []
    for (i, j), p in index.items():
        x, y = reference[p]
        if not (x0 <= x <= x1 and y0 <= y <= y1):
            continue
        a, b = index.get((i - di, j - dj)), index.get((i + di, j + dj))
        if a is None or b is None:
            continue
        out.append((i, j, values[p] - 0.5 * (values[a] + values[b]),
                    0.5 * (values[b] - values[a])))
    return h, out


def ratios(group, region, quantity):
    """{axis: (mean |second difference|, mean |first difference|)} over the region's points."""
    out = {}
    for axis, name in ((0, "x"), (1, "y")):
        h, rows = differences(group, region, quantity, axis)
        out[name] = (float(np.mean([abs(r[2]) for r in rows])),
                     float(np.mean([abs(r[3]) for r in rows])))
    return h, out


def alternating_component(group, region, quantity):
    """Mean over the region's rows of |mean over the row of (-1)^i (v_i - (v_{i-1} + v_{i+1})/2)
    / 2|: A for a pattern A (-1)^i, nothing for a linear trend."""
    by_row = {}
    for i, j, second, _ in differences(group, region, quantity, 0)[1]:
        by_row.setdefault(j, []).append((1.0 if i % 2 == 0 else -1.0) * second / 2)
    return float(np.mean([abs(np.mean(v)) for v in by_row.values()]))


def growth(args):
    rows = []
    print("| run | step | time [ms] | s/B | second difference along x | growth rate [1/ms] "
          "| alternating component |")
    print("|---|---|---|---|---|---|---|")
    for item in args.runs:
        run, _, label = item.partition(":")
        with h5py.File(f"{run}/results.h5", "r") as f:
            steps = sorted((k for k in f if k.startswith("step_")),
                           key=lambda k: f[k].attrs["time"])
            before = None
            for k in steps:
                t = f[k].attrs["time"]
                if t <= 0.0:
                    continue
                amplitude = ratios(f[k], args.region, args.quantity)[1]["x"][0]
                alternating = alternating_component(f[k], args.region, args.quantity)
                rate = "" if before is None else \
                    f"{np.log(amplitude / before[1]) / ((t - before[0]) * 1e3):.3f}"
                print(f"| {label or run} | {k[5:]} | {t * 1e3:.3f} | "
                      f"{args.speed * t / args.width:.4f} | {amplitude:.3e} | {rate} | "
                      f"{alternating:.3e} |")
                rows.append({"run": label or run, "step": int(k[5:]), "time": float(t),
                             "second_difference_x": float(amplitude),
                             "alternating_component_x": alternating})
                before = (t, amplitude)
    if args.json:
        with open(args.json, "w") as out:
            json.dump({"region": args.region, "quantity": args.quantity, "rows": rows}, out,
                      indent=1)


def main():
    a = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    a.add_argument("runs", nargs="+", metavar="MPM_RUN[:LABEL]")
    a.add_argument("--at", type=float, nargs="+", default=[0.1, 0.2, 0.3])
    a.add_argument("--region", type=float, nargs=4, default=[0.0, 0.35, 0.25, 0.6])
    a.add_argument("--quantity", choices=["eq", "exy"], default="eq")
    a.add_argument("--speed", type=float, default=0.5)
    a.add_argument("--width", type=float, default=0.2)
    a.add_argument("--json")
    a.add_argument("--growth", action="store_true")
    args = a.parse_args()
    if args.growth:
        growth(args)
        return
    rows = []
    print("| run | s/B | h [m] | along x: second / first difference (ratio) "
          "| along y: second / first difference (ratio) |")
    print("|---|---|---|---|---|")
    for item in args.runs:
        run, _, label = item.partition(":")
        with h5py.File(f"{run}/results.h5", "r") as f:
            seen = set()
            for at in args.at:
                group = nearest_output(f, at * args.width / args.speed)
                if group.name in seen:  # a run that ends before this s/B
                    continue
                seen.add(group.name)
                s = args.speed * group.attrs["time"] / args.width
                h, out = ratios(group, args.region, args.quantity)
                (sx, fx), (sy, fy) = out["x"], out["y"]
                rows.append({"run": label or run, "s_over_B": s, "h": h, "x": out["x"],
                             "y": out["y"], "ratio_x": sx / fx, "ratio_y": sy / fy})
                print(f"| {label or run} | {s:.2f} | {h:.4f} | {sx:.4f} / {fx:.4f} "
                      f"({sx / fx:.2f}) | {sy:.4f} / {fy:.4f} ({sy / fy:.2f}) |")
    if args.json:
        with open(args.json, "w") as out:
            record = {"region": args.region, "quantity": args.quantity, "rows": rows}
            json.dump(record, out, indent=1)


if __name__ == "__main__":
    main()
